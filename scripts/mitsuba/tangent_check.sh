#!/usr/bin/env bash
# Issue 47's top/bottom residual, one command: plait's exact single
# scattering (pipelines/reference.toml, chiang shading, opaque fibres:
# params.shadow_opaque=1) against Mitsuba 3 at max depth 2, on
# scripts/mitsuba/hair-check.toml's groom at 24 segments a strand (the
# issue's recipe) and at 96 (the same generator, finer), blond, dark brown
# and black, 160x120. Then scripts/mitsuba/tangent_table.py prints per
# colour and segment count: mean hair light and the top/middle/bottom thirds
# of the hair mask (Mitsuba's coverage >= 0.9), and the split by
# direct_probe.py: plait ÷ Mitsuba's BSDF about plait's own shading tangent,
# and that ÷ the same BSDF about the B-spline's tangent (Mitsuba's); and
# Mitsuba with the strands as Catmull-Rom pieces (scripts/mitsuba/
# catmull_rom.py: tangents at the points = plait's former central differences) ÷ Mitsuba; and plait
# given the export's B-spline sampled 4 times a segment (resample_curve.py:
# the curve Mitsuba draws) ÷ Mitsuba.
# plait uses transparency=linked_list here (exact per-pixel sort, as depth
# peeling; 9 s a render instead of minutes): on blond at 24 segments,
# unshadowed (self_shadow=none), depth_peeling ÷ linked_list is 0.997 / 0.995 /
# 0.997 by thirds (max pixel difference 0.032 of 0.565).
# Usage: bash scripts/mitsuba/tangent_check.sh [OUT_DIR]  (default
# target/tangent-check); SPP (default 64) for Mitsuba.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
out="${1:-$CARGO_TARGET_DIR/tangent-check}"
spp="${SPP:-64}"
mkdir -p "$out"
eval "$(bash "$root/scripts/ensure-mitsuba.sh")"
bash "$root/scripts/ensure-vulkan.sh"
(cd "$root" && cargo build -q -p plait-cli)
plait="$CARGO_TARGET_DIR/debug/plait"
py="$PLAIT_MITSUBA_PYTHON"
declare -A colours=(
    [blond]="[0.85, 0.65, 0.40]"
    [dark_brown]="[0.32, 0.20, 0.11]"
    [black]="[0.02, 0.02, 0.02]"
)
for segments in 24 96; do
    for c in blond dark_brown black; do
        name="${c}_$segments"
        sed -e "s/HAIR_COLOR/${colours[$c]}/" -e "s/^segments = 24$/segments = $segments/" \
            "$root/scripts/mitsuba/hair-check.toml" >"$out/$name.toml"
        grep -q "^segments = $segments$" "$out/$name.toml"
        "$plait" export mitsuba "$out/$name.toml" --size 160x120 --out "$out/$name" >/dev/null
        "$py" "$root/scripts/mitsuba/render.py" "$out/$name" "$out/${name}_mitsuba_d2.exr" \
            --spp "$spp" --max-depth 2 --seed 0 --coverage "$out/${name}_mask.exr"
        "$py" "$root/scripts/mitsuba/direct_probe.py" "$out/$name" "$out/${name}_probe" --spp "$spp" >/dev/null
        # The same points as Catmull-Rom pieces (knot tangents = central differences).
        "$py" "$root/scripts/mitsuba/catmull_rom.py" "$out/$name" "$out/${name}_cr" >/dev/null
        "$py" "$root/scripts/mitsuba/render.py" "$out/${name}_cr" "$out/${name}_cr_mitsuba_d2.exr" \
            --spp "$spp" --max-depth 2 --seed 0
        "$plait" render "$root/pipelines/reference.toml" --scene "$out/$name.toml" --size 160x120 \
            --set techniques.shading=chiang --set params.shadow_opaque=1 \
            --set techniques.transparency=linked_list --out "$out/${name}_plait.exr" >/dev/null 2>"$out/plait.err"
        # plait on the curve Mitsuba draws: the export's B-spline, 4 points a segment.
        "$py" "$root/scripts/mitsuba/resample_curve.py" "$out/$name" "$out/$name.toml" "$out/${name}_x4" 4
        "$plait" render "$root/pipelines/reference.toml" --scene "$out/${name}_x4.toml" --size 160x120 \
            --set techniques.shading=chiang --set params.shadow_opaque=1 \
            --set techniques.transparency=linked_list --out "$out/${name}_x4_plait.exr" >/dev/null 2>"$out/plait.err"
        "$plait" render "$root/pipelines/reference.toml" --scene "$out/$name.toml" --size 160x120 \
            --set techniques.shading=chiang --set techniques.self_shadow=none \
            --set techniques.transparency=linked_list --out "$out/${name}_plait_unshadowed.exr" >/dev/null 2>"$out/plait.err"
    done
done
"$py" "$root/scripts/mitsuba/tangent_table.py" "$out"
