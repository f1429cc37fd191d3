#!/usr/bin/env bash
# The compute rasterizer against occupancy-order blending as the groom
# grows (issue 22): the scaling benchmark's default groom from 75k to 2M
# segments at 320x240, one run per groom size with the two variants
# interleaved in it. compute_raster runs with 8-px tiles and 64 depth bins,
# the tiling whose densest tile stays inside lavapipe's loop budget at 2M
# (16-px tiles there fail the frame: their tiles' invocations could not
# finish, which the run reports). Prints the benchmark's rows; GPU times
# want an idle machine.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/ensure-vulkan.sh
for n in ${SEGMENTS:-75000 150000 300000 600000 1200000 2000000}; do
    cargo bench --quiet --locked --profile dev -p plait --bench scaling -- \
        --repeats "${REPEATS:-1}" --segments "$n" \
        --variant techniques.transparency=occupancy_order \
        --variant techniques.transparency=compute_raster,techniques.shading_space=strand,params.tile_size=8,params.depth_bins=64 \
        2>&1 | grep -E '^\| [0-9]|could not finish|holding everything|^occupancy.toml' || true
done
