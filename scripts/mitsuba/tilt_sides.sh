#!/usr/bin/env bash
# Does the side of the R lobe along the strand explain a top-to-bottom
# gradient in plait ÷ Mitsuba at depth 2? (book: Shading, "Against the path
# tracer".) On scripts/physical-check.sh's blond scene (run that first), with
# opaque fibres (params.shadow_opaque=1) and exact order (linked_list):
#   1. both renderers with R on the tip's side (the convention before issue
#      42): Mitsuba's scale_tilt +2, plait's chiang_tilt −2;
#   2. the two on opposite sides: Mitsuba +2, plait +2 (R toward the root).
# scripts/mitsuba/ratio_map.py prints plait ÷ Mitsuba overall and by rows of
# the hair mask for each. Usage: bash scripts/mitsuba/tilt_sides.sh
# [PHYSICAL_CHECK_DIR [OUT_DIR]]
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
src="${1:-$CARGO_TARGET_DIR/physical-check}"
out="${2:-$CARGO_TARGET_DIR/tilt-sides}"
[ -f "$src/blond/scene.xml" ] || { echo "tilt_sides.sh: no $src/blond/scene.xml: run scripts/physical-check.sh first" >&2; exit 2; }
eval "$(bash "$root/scripts/ensure-mitsuba.sh")"
bash "$root/scripts/ensure-vulkan.sh"
(cd "$root" && cargo build -q -p plait-cli)
plait="$CARGO_TARGET_DIR/debug/plait"
py="$PLAIT_MITSUBA_PYTHON"
rm -rf "$out" && mkdir -p "$out"
cp -r "$src/blond" "$out/blond" && cp "$src/blond.toml" "$out/"
sed -i 's/scale_tilt" value="-2"/scale_tilt" value="2"/' "$out/blond/scene.xml"
grep -q 'scale_tilt" value="2"' "$out/blond/scene.xml" || { echo "tilt_sides.sh: the export's scale_tilt is not -2" >&2; exit 2; }
"$py" "$root/scripts/mitsuba/render.py" "$out/blond" "$out/blond_mitsuba_d2_s0.exr" --spp 64 --max-depth 2 --seed 0 \
    --coverage "$out/blond_mask.exr"
"$py" "$root/scripts/mitsuba/render.py" "$out/blond" "$out/blond_mitsuba_d2_s1.exr" --spp 64 --max-depth 2 --seed 1
for t in -2 2; do
    "$plait" render "$root/pipelines/reference.toml" --scene "$out/blond.toml" --size 160x120 \
        --set techniques.shading=chiang --set params.shadow_opaque=1 \
        --set techniques.transparency=linked_list --set params.chiang_tilt=$t --out "$out/plait_tilt$t.exr" >/dev/null
done
echo "== 1. both with R on the tip's side (Mitsuba scale_tilt +2, plait chiang_tilt -2)"
cp "$out/plait_tilt-2.exr" "$out/blond_plait_chiang.exr"
"$py" "$root/scripts/mitsuba/ratio_map.py" "$out" | grep '^blond'
echo "== 2. opposite sides (Mitsuba scale_tilt +2, plait chiang_tilt +2)"
cp "$out/plait_tilt2.exr" "$out/blond_plait_chiang.exr"
"$py" "$root/scripts/mitsuba/ratio_map.py" "$out" | grep '^blond'
