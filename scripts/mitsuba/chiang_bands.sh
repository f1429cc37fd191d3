#!/usr/bin/env bash
# The shading page's figure `chiang-bands` (docs/figures.toml; issue 42):
# chiang, marschner and the Kajiya-Kay default (occupancy) on the built-in
# scene with blond hair at 160x120, against the path-traced reference
# (references/path_traced.toml, maximum depth 16) and against the same
# reference cut to maximum depth 2, split by band of the hair
# (scripts/mitsuba/ab_bands.py; the hair mask is `camera_alpha` >= 2.3).
# Prints the table on stdout, the runs' progress on stderr. Mitsuba renders
# the two references once; they are cached in the build folder.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
target="${CARGO_TARGET_DIR:-target}"
eval "$(bash scripts/ensure-mitsuba.sh)"
cargo build --quiet --locked -p plait-cli
plait="$target/debug/plait"
out="$target/chiang-bands"
rm -rf "$out"
mkdir -p "$out"

# The depth-2 reference: the same file with one value changed, checked so
# that an edit of the reference cannot leave it at depth 16 unnoticed.
sed 's/^max_depth = 16 /max_depth = 2 /' references/path_traced.toml >"$out/path_traced_d2.toml"
grep -q '^max_depth = 2 ' "$out/path_traced_d2.toml" || {
    echo "chiang_bands.sh: references/path_traced.toml has no 'max_depth = 16' line to cut to 2" >&2
    exit 2
}

variants=(pipelines/chiang.toml pipelines/marschner.toml pipelines/occupancy.toml)
for depth in 16 2; do
    reference=references/path_traced.toml
    [ "$depth" = 2 ] && reference="$out/path_traced_d2.toml"
    "$plait" ab "${variants[@]}" --reference "$reference" --hair-color blond=0.85,0.65,0.40 \
        --size 160x120 --repeats 1 --out "$out/d$depth" >&2
done
"$plait" render pipelines/chiang.toml --size 160x120 --show camera_alpha \
    --out "$out/camera_alpha.exr" >&2
"$PLAIT_MITSUBA_PYTHON" scripts/mitsuba/ab_bands.py "$out/camera_alpha.exr" 2.3 "$out/d16" "$out/d2"
