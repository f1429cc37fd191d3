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
# Headless Chromium for the book's browser check (crates/plait-cli/tests/book.rs)
# and the live page's test (tests/web.rs, WebGPU on SwiftShader).
bash scripts/ensure-chromium.sh
# The web build's tools for the browser test (tests/web.rs): Rust's wasm32
# target and wasm-bindgen's CLI at Cargo.lock's version, cached in the build
# folder.
bash scripts/ensure-wasm.sh >/dev/null
# Mitsuba 3 (pinned, in the build folder) for the path-traced reference's
# tests (crates/plait-cli/tests/mitsuba_cli.rs); its exports are for callers
# that render, not needed here.
bash scripts/ensure-mitsuba.sh >/dev/null

# The GPU tests run on lavapipe: the golden images, the claims' measured
# bands and the loop budgets were made with it, and on another driver they
# measure something else (the loop-budget tests assert nothing). So lavapipe
# is pinned, and without it the tests are refused, unless you ask for another
# driver: your own VK_ICD_FILENAMES / VK_DRIVER_FILES, or PLAIT_DRIVER=any
# (whatever the Vulkan loader finds). PLAIT_ICD_DIRS replaces the ICD
# directories searched (for testing this script).
icd_dirs=${PLAIT_ICD_DIRS:-/usr/share/vulkan/icd.d /etc/vulkan/icd.d /usr/local/share/vulkan/icd.d}
icds() { # every ICD file in the searched directories
    local d
    for d in $icd_dirs; do compgen -G "$d/*.json" || true; done
}
lvp=$(icds | grep '/lvp_icd[^/]*\.json$' | head -n 1 || true)
if [ -n "${VK_ICD_FILENAMES:-}${VK_DRIVER_FILES:-}" ]; then
    driver="${VK_ICD_FILENAMES:-${VK_DRIVER_FILES:-}} (set by VK_ICD_FILENAMES / VK_DRIVER_FILES)"
elif [ -n "$lvp" ]; then
    export VK_ICD_FILENAMES="$lvp"
    driver="lavapipe, $lvp"
elif [ "${PLAIT_DRIVER:-}" = any ]; then
    driver="any (PLAIT_DRIVER=any), the loader picks from: $(icds | paste -sd ' ' -)"
else
    found=$(icds | paste -sd ' ' -)
    echo "scripts/test.sh: lavapipe's Vulkan driver (lvp_icd*.json) is not installed;" \
        "found: ${found:-no Vulkan driver} (in $icd_dirs)." >&2
    echo "The GPU tests' goldens, bands and loop budgets are lavapipe's: install it" \
        "(apt-get install -y mesa-vulkan-drivers), or ask for another driver with" \
        "PLAIT_DRIVER=any or VK_ICD_FILENAMES=<icd.json>." >&2
    exit 2
fi
echo "scripts/test.sh: Vulkan driver: $driver" >&2

# A blessing run rewrites every golden image and snapshot it compares, and
# passes: say so (CI clears PLAIT_BLESS, .ci/run).
if [ -n "${PLAIT_BLESS:-}" ] && [ "${PLAIT_BLESS}" != 0 ]; then
    echo "scripts/test.sh: PLAIT_BLESS=$PLAIT_BLESS: golden and snapshot tests rewrite their files instead of comparing" >&2
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
