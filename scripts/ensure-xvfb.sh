#!/usr/bin/env bash
# Make sure Xvfb (a virtual X display) is present: the `plait view` test opens
# its window on one. Installed here, like the Vulkan driver, when missing and
# we may install packages; otherwise the test fails saying how to install it.
set -euo pipefail

if command -v Xvfb >/dev/null; then
    exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
    echo "plait: no Xvfb found; installing it for the viewer test (xvfb)" >&2
    apt-get update -qq
    # The X11 client libraries winit opens at run time come along.
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq xvfb xauth libxkbcommon-x11-0 \
        libxcursor1 libxi6 libxrandr2 >/dev/null
else
    echo "plait: no Xvfb found. Install it, e.g. 'sudo apt-get install -y xvfb'" >&2
    echo "       (the viewer test fails with this message until then)." >&2
fi
