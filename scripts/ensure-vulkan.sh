#!/usr/bin/env bash
# Make sure the GPU drivers the tests use are present. plait's GPU tests and
# default pipeline run on any Vulkan adapter; a machine without a GPU uses
# Mesa's software rasterizer lavapipe (package mesa-vulkan-drivers). The
# capability tests (crates/plait-cli/tests/adapter_cli.rs) also hide Vulkan so
# that wgpu falls back to OpenGL, which needs Mesa's EGL and its software GL
# driver llvmpipe (libegl1, libegl-mesa0, libgl1-mesa-dri). Each is installed
# here when missing and we may install packages.
set -euo pipefail

has_icd() {
    local d
    for d in /usr/share/vulkan/icd.d /etc/vulkan/icd.d /usr/local/share/vulkan/icd.d; do
        compgen -G "$d/*.json" >/dev/null && return 0
    done
    return 1
}

# Mesa's EGL vendor library and the software DRI driver wgpu's GL backend opens.
has_gl() {
    local d
    for d in /usr/lib/*-linux-gnu /usr/lib64 /usr/lib; do
        if compgen -G "$d/libEGL.so.1" >/dev/null && compgen -G "$d/libEGL_mesa.so.0" >/dev/null \
            && compgen -G "$d/dri/swrast_dri.so" >/dev/null; then
            return 0
        fi
    done
    return 1
}

missing=()
has_icd || missing+=(mesa-vulkan-drivers)
has_gl || missing+=(libegl1 libegl-mesa0 libgl1-mesa-dri)
if [ ${#missing[@]} -eq 0 ]; then
    exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
    echo "plait: installing Mesa's software GPU drivers: ${missing[*]}" >&2
    apt-get update -qq
    DEBIAN_FRONTEND=noninteractive apt-get install -y -qq "${missing[@]}" >/dev/null
else
    echo "plait: missing GPU drivers. Install them, e.g. 'sudo apt-get install -y ${missing[*]}'" >&2
    echo "       (GPU tests fail with this message until then)." >&2
fi
