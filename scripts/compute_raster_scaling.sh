#!/usr/bin/env bash
# The compute rasterizer against occupancy-order blending as the groom
# grows (issue 22): the scaling benchmark's default groom from 75k to 2M
# segments at 320x240, one run per groom size with the two variants
# interleaved in it (a size the compute rasterizer refuses — its per-tile
# capacity beyond the adapter's storage binding — is printed and the next
# size runs). Prints the benchmark's rows; GPU times want an idle machine.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/ensure-vulkan.sh
for n in ${SEGMENTS:-75000 150000 300000 600000 1200000 2000000}; do
    cargo bench --quiet --locked --profile dev -p plait --bench scaling -- \
        --repeats "${REPEATS:-1}" --segments "$n" \
        --variant techniques.transparency=occupancy_order \
        --variant techniques.transparency=compute_raster,techniques.shading_space=strand,params.tile_size=16 \
        2>&1 | grep -E '^\| [0-9]|holding everything|^occupancy.toml' || true
done
