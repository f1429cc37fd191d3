#!/usr/bin/env bash
# Measures strand-space shading (techniques.shading_space = strand, Tafuri
# 2019) against per-fragment shading: RMSE / SSIM / FLIP and frame time, for
# 4, 8, 16 and 32 shading points per strand, with `plait ab` (the fragment
# pipeline is the reference). 32 exceeds the points of the small (17) and
# stray (25) scenes' strands — an error by design — so those two scenes stop
# at 16. Writes two reports under the folder given (default target/shading_space)
# and prints their report.md. A few minutes on lavapipe; GPU times want an
# otherwise idle machine.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=${1:-target/shading_space}
bash scripts/ensure-vulkan.sh
cargo build --quiet --locked -p plait-cli
plait=${CARGO_TARGET_DIR:-target}/debug/plait
common=(pipelines/occupancy.toml --reference pipelines/occupancy.toml
    --sweep techniques.shading_space=strand --size 256x192 --repeats 1)
"$plait" ab "${common[@]}" --sweep params.shading_points=4,8,16 \
    --scene examples/scenes/small.toml --scene examples/scenes/stray.toml --out "$out/small_stray"
"$plait" ab "${common[@]}" --sweep params.shading_points=4,8,16,32 --out "$out/default"
cat "$out/small_stray/report.md" "$out/default/report.md"
