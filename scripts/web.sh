#!/usr/bin/env bash
# The live page: plait's engine compiled to WebAssembly (crates/plait-web)
# with the built-in library, and a static site that renders any gallery
# pipeline on the built-in small scene in a browser with WebGPU. No network:
# every file the page loads is in the site.
#
#   bash scripts/web.sh [OUT]      # default ${CARGO_TARGET_DIR:-target}/web
#
# Serve OUT over HTTP (browsers refuse WebAssembly from file://), e.g.
# `python3 -m http.server -d OUT -b 127.0.0.1 8000`.
#
#   bash scripts/web.sh --figures  # issue 44's figures into the book
#
# --figures measures (tests/web/figures.rs; CPU-heavy, minutes): the wasm's
# size and gzipped size (dev, and release, which it builds first), the
# first frame of occupancy and depth_peeling in
# the page on SwiftShader beside lavapipe's, and the gallery pipelines within
# WebGPU's default limits; it writes them with the commit between the
# `<!-- web-figures -->` markers of book/src/guide/browser.md.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
if [ "${1:-}" = --figures ]; then
    # The release profile's wasm too, for its size beside the dev one the
    # tests load (a second build of wgpu and naga for wasm: long the first
    # time). PLAIT_WEB_RELEASE_WASM=none leaves it out.
    if [ -z "${PLAIT_WEB_RELEASE_WASM:-}" ]; then
        release_site="${CARGO_TARGET_DIR:-$root/target}/web-release"
        PLAIT_WEB_PROFILE=release bash "$0" "$release_site" >/dev/null
        export PLAIT_WEB_RELEASE_WASM="$release_site/plait_web_bg.wasm"
    elif [ "$PLAIT_WEB_RELEASE_WASM" = none ]; then
        unset PLAIT_WEB_RELEASE_WASM
    fi
    # Mesa's shader disk cache off: lavapipe's first frame compiles its
    # shaders as the browser's fresh profile does.
    export PLAIT_WEB_FIGURES_PAGE="$root/book/src/guide/browser.md" MESA_SHADER_CACHE_DISABLE=true
    exec cargo test --manifest-path "$root/Cargo.toml" -p plait-tests --test web --locked \
        -- --ignored --exact figures::figures --nocapture --test-threads=1
fi
target="${CARGO_TARGET_DIR:-$root/target}"
out="${1:-$target/web}"
# The dev profile (opt-level 1, as the tests build): a release build would be
# a second full build of wgpu and naga for one page. PLAIT_WEB_PROFILE=release
# for a smaller, faster page.
profile="${PLAIT_WEB_PROFILE:-dev}"

bindgen="$(bash "$root/scripts/ensure-wasm.sh")"
dir=$([ "$profile" = dev ] && echo debug || echo "$profile")
echo "plait: building the engine for wasm32 ($profile)" >&2
# plait-passes in one codegen unit: its pass types register themselves
# (`inventory`), and wasm-ld drops an object file nothing else references
# with its registration (data_only.rs's `fullscreen`, `raster`, `compute`).
cargo build --manifest-path "$root/Cargo.toml" -p plait-web --lib --locked \
    --target wasm32-unknown-unknown --profile "$profile" \
    --config "profile.$profile.package.plait-passes.codegen-units=1" >&2
mkdir -p "$out"
"$bindgen" --target web --no-typescript --out-dir "$out" \
    "$target/wasm32-unknown-unknown/$dir/plait_web.wasm"
cp "$root"/crates/plait-web/site/* "$out/"
echo "plait: site in $out ($(du -k "$out/plait_web_bg.wasm" | cut -f1) KiB wasm)" >&2
echo "$out"
