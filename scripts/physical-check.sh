#!/usr/bin/env bash
# Issue 47's measurement, one command: plait's light against Mitsuba 3's
# path-traced light on the same scene (scripts/mitsuba/hair-check.toml,
# 160x120), for blond, dark brown and black hair.
#   - the ground's radiance at a few lit pixels against rho/pi * E * cos(theta);
#   - mean linear luminance over hair pixels: plait's pipelines/reference.toml
#     (exact single scattering) with Marschner shading, with Chiang et al.
#     2016's fibre (`chiang`, the model Mitsuba's hair BSDF is) and with its
#     default shading, against Mitsuba at max depth 2 (single scattering) and at full
#     depth (16), each Mitsuba image at two seeds for its noise.
# Like with like at depth 2 (Mitsuba's max depth 2: one scattering event, a
# shadow ray that meets a fibre is blocked): plait's chiang is also rendered
# with params.shadow_opaque=1 (fibres opaque to light, visibility =
# Π (1 - share); docs/formats.md, "Light and units") as C_plait_chiang_opaque,
# and scripts/mitsuba/direct_probe.py re-renders Mitsuba's single scattering
# by hand, with Mitsuba's frame and with one rebuilt from the curve's tangent
# (C_probe_fibre_shadowed; equal since the export is bsplinecurve: see that
# script), which scripts/mitsuba/ratio_map.py holds plait_chiang_opaque to,
# by region. Likewise marschner_opaque (marschner_reference), marschner_lut_opaque
# (the tables) and default_opaque (the default shading, Kajiya-Kay): compare.py's
# second table holds every shading to Mitsuba at depth 2 like with like.
# Mitsuba images kept by MITSUBA_REUSE=1 from before the switch to
# bsplinecurve shade about the wrong axis: render them again. The
# depth-16 comparison and compare.py's tables are unchanged.
# Usage: bash scripts/physical-check.sh [OUT_DIR]   (default target/physical-check)
# Env: SPP_D2 (default 64), SPP_FULL (default 256), PLAIT_SETS (extra --set
# flags for both plait renders), MITSUBA_REUSE=1 (keep Mitsuba images already
# in OUT_DIR: measure another plait build against the same references).
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export CARGO_TARGET_DIR="${CARGO_TARGET_DIR:-$root/target}"
out="${1:-$CARGO_TARGET_DIR/physical-check}"
spp_d2="${SPP_D2:-64}"
spp_full="${SPP_FULL:-256}"
size=160x120
mkdir -p "$out"

eval "$(bash "$root/scripts/ensure-mitsuba.sh")"
bash "$root/scripts/ensure-vulkan.sh"
(cd "$root" && cargo build -q -p plait-cli)
plait="$CARGO_TARGET_DIR/debug/plait"
py="$PLAIT_MITSUBA_PYTHON"
render="$root/scripts/mitsuba/render.py"

# Colours: the issue's blond and dark brown; black is our choice, 0.02 in
# every channel (Chiang 2016 §4.2 maps 0 to no finite absorption).
declare -A colours=(
    [blond]="[0.85, 0.65, 0.40]"
    [dark_brown]="[0.32, 0.20, 0.11]"
    [black]="[0.02, 0.02, 0.02]"
)
for c in blond dark_brown black; do
    scene="$out/$c.toml"
    sed "s/HAIR_COLOR/${colours[$c]}/" "$root/scripts/mitsuba/hair-check.toml" >"$scene"
    "$plait" export mitsuba "$scene" --size "$size" --out "$out/$c" >/dev/null
    start=$SECONDS
    if [ "${MITSUBA_REUSE:-0}" = 1 ] && [ -f "$out/${c}_mitsuba_full_s1.exr" ]; then
        echo "$c: Mitsuba images reused from $out" >&2
    else
        "$py" "$render" "$out/$c" "$out/${c}_mitsuba_d2_s0.exr" --spp "$spp_d2" --max-depth 2 --seed 0 \
            --coverage "$out/${c}_mask.exr"
        "$py" "$render" "$out/$c" "$out/${c}_mitsuba_d2_s1.exr" --spp "$spp_d2" --max-depth 2 --seed 1
        "$py" "$render" "$out/$c" "$out/${c}_mitsuba_full_s0.exr" --spp "$spp_full" --max-depth 16 --seed 0
        "$py" "$render" "$out/$c" "$out/${c}_mitsuba_full_s1.exr" --spp "$spp_full" --max-depth 16 --seed 1
    fi
    echo "$c: Mitsuba (2 x ${spp_d2} spp depth 2 + coverage, 2 x ${spp_full} spp depth 16) took $((SECONDS - start)) s" >&2
    "$py" "$root/scripts/mitsuba/direct_probe.py" "$out/$c" "$out/${c}_probe" --spp "$spp_d2"
    for shading in default marschner chiang chiang_opaque marschner_opaque marschner_lut_opaque default_opaque; do
        sets=()
        [ "$shading" = marschner ] && sets=(--set techniques.shading=marschner_reference)
        [ "$shading" = chiang ] && sets=(--set techniques.shading=chiang)
        [ "$shading" = chiang_opaque ] && sets=(--set techniques.shading=chiang --set params.shadow_opaque=1)
        [ "$shading" = marschner_opaque ] && sets=(--set techniques.shading=marschner_reference --set params.shadow_opaque=1)
        [ "$shading" = marschner_lut_opaque ] && sets=(--set techniques.shading=marschner --set params.shadow_opaque=1)
        [ "$shading" = default_opaque ] && sets=(--set params.shadow_opaque=1)
        rm -f "$out/${c}_plait_$shading.exr"
        # shellcheck disable=SC2086
        if ! "$plait" render "$root/pipelines/reference.toml" --scene "$scene" --size "$size" \
            "${sets[@]}" ${PLAIT_SETS:-} --out "$out/${c}_plait_$shading.exr" >/dev/null 2>"$out/plait.err"; then
            echo "plait render ($c, $shading shading) failed: $(head -3 "$out/plait.err")" >&2
        fi
    done
done
"$py" "$root/scripts/mitsuba/compare.py" "$out"
"$py" "$root/scripts/mitsuba/ratio_map.py" "$out"
