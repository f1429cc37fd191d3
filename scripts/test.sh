#!/usr/bin/env bash
# plait's test command (README): every test tier, including the GPU tests,
# which run for real on Mesa's software Vulkan driver (lavapipe) when the
# machine has no GPU. `.ci/run` calls exactly this.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

# A Vulkan driver (ICD) is needed for the GPU tests; without one they FAIL
# with a message saying how to install it (they are never skipped).
bash scripts/ensure-vulkan.sh
# Xvfb for the `plait view` test (a window on a virtual display).
bash scripts/ensure-xvfb.sh
# Headless Chromium for the book's browser check (crates/plait-cli/tests/book.rs).
bash scripts/ensure-chromium.sh

# Pin the tests to lavapipe when it is installed, as blade's CI does: the
# golden images were made with it, and other ICDs on a GPU-less machine only
# fail to enumerate. Set VK_ICD_FILENAMES yourself to test another driver.
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -z "${VK_DRIVER_FILES:-}" ]; then
    lvp=$(compgen -G "/usr/share/vulkan/icd.d/lvp_icd*.json" | head -n 1 || true)
    if [ -n "$lvp" ]; then
        export VK_ICD_FILENAMES="$lvp"
    fi
fi

# Without XDG_RUNTIME_DIR there is no Wayland display, yet Mesa's device-select
# layer asks for one on every device the GPU tests open, and libwayland prints
# "XDG_RUNTIME_DIR is invalid or not set" each time. The layer only picks the
# GPU that drives a display, so switch it off by its own variable (the `plait`
# binary does the same for itself; see quiet_display_probe_when_headless).
if [ -z "${XDG_RUNTIME_DIR:-}" ] && [ -z "${WAYLAND_SOCKET:-}" ]; then
    export NODEVICE_SELECT="${NODEVICE_SELECT:-1}"
fi

# Two test threads per binary: the GPU tests serialize themselves (one
# lavapipe device uses every core); the CPU tests run alongside.
exec cargo test --workspace --locked --no-fail-fast "$@" -- --test-threads=2
