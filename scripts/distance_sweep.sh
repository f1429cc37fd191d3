#!/usr/bin/env bash
# The camera-distance sweep (issue 23): every geometry technique against all
# strands rendered 4× supersampled, the camera moved back to 1, 2, 4 and 8
# times its distance, on the built-in scene; writes the `plait ab` report
# (html, md, json, charts) and prints its Markdown table of error (ꟻLIP mean
# against the reference) and frame time against the distance — what the
# README shows beside the thesis's figures. No number in it is typed by hand.
#
#   scripts/distance_sweep.sh [OUT_DIR] [extra plait ab flags…]
#
# Defaults: out = distance-sweep/, 960x720 (SIZE=320x240 for a quick look),
# 3 repeats (REPEATS), the built-in scene (SCENE=path to use another).
# Geometry techniques (GEOMETRY, comma-separated): strands and lod, and
# wisps when techniques/geometry/wisps exists. On lavapipe the 960x720 run
# takes several minutes (the reference renders at 3840x2880); run it on an
# otherwise idle machine, since the table holds frame times.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
out=${1:-distance-sweep}
shift || true
size=${SIZE:-960x720}
repeats=${REPEATS:-3}
distances=${DISTANCES:-1,2,4,8}
if [[ -z ${GEOMETRY:-} ]]; then
    GEOMETRY=strands,lod
    [[ -d techniques/geometry/wisps ]] && GEOMETRY=$GEOMETRY,wisps
fi
scene=()
[[ -n ${SCENE:-} ]] && scene=(--scene "$SCENE")

bash scripts/ensure-vulkan.sh
cargo build --quiet --locked -p plait-cli
plait=${CARGO_TARGET_DIR:-target}/debug/plait

"$plait" ab pipelines/forward.toml \
    --sweep "techniques.geometry=$GEOMETRY" \
    --reference pipelines/forward.toml --supersample 4 \
    --camera-distance "$distances" \
    "${scene[@]}" --size "$size" --repeats "$repeats" \
    --out "$out" "$@"

# The distance table(s): from the first `**…camera distance**` heading to
# the first per-scene table.
echo
awk '/camera distance\*\*$/ {on = 1} on && /^\*\*/ && !/camera distance\*\*$/ {exit} on' "$out/report.md"
echo "report: $out/report.html"
