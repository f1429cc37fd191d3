#!/usr/bin/env bash
# Make sure the GPU drivers the tests use are present. plait's GPU tests and
# default pipeline run on any Vulkan adapter; a machine without a GPU uses
# Mesa's software rasterizer lavapipe (package mesa-vulkan-drivers). The
# capability tests (crates/plait-cli/tests/adapter_cli.rs) also hide Vulkan so
# that wgpu falls back to OpenGL, which needs Mesa's EGL and its software GL
# driver llvmpipe (libegl1, libegl-mesa0, libgl1-mesa-dri). Each is installed
# here when missing and we may install packages.
#
# lavapipe is Mesa 25 or newer: Mesa 22.3 (Debian 12's own) has no ray
# queries, which the ray-traced techniques need (issue 48), so on Debian 12
# it comes from bookworm-backports (the suite is added to apt's sources).
# The goldens record the driver they were made on (tests/golden/*.driver).
set -euo pipefail

MIN_LAVAPIPE_MAJOR=25

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

# The installed mesa-vulkan-drivers is older than MIN_LAVAPIPE_MAJOR (or
# absent) on a Debian-packaged machine. Elsewhere nothing is known: say nothing.
old_lavapipe() {
    command -v dpkg-query >/dev/null || return 1
    local v
    v=$(dpkg-query -W -f='${Version}' mesa-vulkan-drivers 2>/dev/null || true)
    [ -z "$v" ] && return 0
    [ "${v%%.*}" -lt "$MIN_LAVAPIPE_MAJOR" ] 2>/dev/null
}

# Debian 12 (bookworm) ships Mesa 22.3: its backports suite has Mesa 25.
codename() { . /etc/os-release 2>/dev/null && echo "${VERSION_CODENAME:-}"; }
add_backports() {
    local list=/etc/apt/sources.list.d/plait-bookworm-backports.sources
    grep -rqs 'bookworm-backports' /etc/apt/sources.list /etc/apt/sources.list.d/ && return 0
    printf '%s\n' 'Types: deb' 'URIs: http://deb.debian.org/debian' \
        'Suites: bookworm-backports' 'Components: main' \
        'Signed-By: /usr/share/keyrings/debian-archive-keyring.gpg' > "$list"
}

missing=()
upgrade_lavapipe=0
if ! has_icd || old_lavapipe; then
    upgrade_lavapipe=1
fi
has_gl || missing+=(libegl1 libegl-mesa0 libgl1-mesa-dri)
if [ ${#missing[@]} -eq 0 ] && [ $upgrade_lavapipe = 0 ]; then
    exit 0
fi
if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
    export DEBIAN_FRONTEND=noninteractive
    from=()
    if [ $upgrade_lavapipe = 1 ] && [ "$(codename)" = bookworm ]; then
        add_backports
        from=(-t bookworm-backports)
    fi
    apt-get update -qq
    if [ ${#missing[@]} -gt 0 ]; then
        echo "plait: installing Mesa's software GL driver: ${missing[*]}" >&2
        apt-get install -y -qq "${missing[@]}" >/dev/null
    fi
    if [ $upgrade_lavapipe = 1 ]; then
        echo "plait: installing lavapipe (Mesa >= $MIN_LAVAPIPE_MAJOR): mesa-vulkan-drivers ${from[*]}" >&2
        apt-get install -y -qq "${from[@]}" mesa-vulkan-drivers >/dev/null
    fi
else
    [ $upgrade_lavapipe = 1 ] && missing+=("mesa-vulkan-drivers (Mesa >= $MIN_LAVAPIPE_MAJOR; on Debian 12 from bookworm-backports)")
    echo "plait: missing GPU drivers. Install them, e.g. 'sudo apt-get install -y ${missing[*]}'" >&2
    echo "       (GPU tests fail with this message until then)." >&2
fi
