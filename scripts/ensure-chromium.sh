#!/usr/bin/env bash
# Make sure headless Chromium is present: the book's browser check opens every
# page in it. Installed here, like the Vulkan driver, when missing and we may
# install packages (Debian's `chromium`); otherwise the check fails saying how
# to install it. PLAIT_CHROMIUM names another binary.
set -euo pipefail

if [ -n "${PLAIT_CHROMIUM:-}" ] || command -v chromium >/dev/null || command -v chromium-browser >/dev/null; then
    exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
    echo "plait: no Chromium found; installing it for the book's browser check (chromium)" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq chromium >/dev/null
else
    echo "plait: no Chromium found. Install it, e.g. 'sudo apt-get install -y chromium'" >&2
    echo "       (the book's browser check fails with this message until then)." >&2
fi
