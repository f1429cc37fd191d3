#!/usr/bin/env bash
# Make sure a Vulkan driver is present. plait's GPU tests and default
# pipeline run on any Vulkan adapter; a machine without a GPU uses Mesa's
# software rasterizer lavapipe (package mesa-vulkan-drivers), installed here
# when no Vulkan driver is found and we may install packages.
set -euo pipefail

has_icd() {
    local d
    for d in /usr/share/vulkan/icd.d /etc/vulkan/icd.d /usr/local/share/vulkan/icd.d; do
        compgen -G "$d/*.json" >/dev/null && return 0
    done
    return 1
}

if has_icd; then
    exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
    echo "plait: no Vulkan driver found; installing Mesa's software Vulkan (mesa-vulkan-drivers)" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq mesa-vulkan-drivers >/dev/null
else
    echo "plait: no Vulkan driver found. Install one, e.g. 'sudo apt-get install -y mesa-vulkan-drivers'" >&2
    echo "       (GPU tests fail with this message until then)." >&2
fi
