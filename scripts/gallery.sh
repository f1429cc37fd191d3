#!/usr/bin/env bash
# Regenerates the book's measured gallery (book/src/guide/gallery.md): its
# two tables are the published figures `gallery-shadows` and
# `gallery-transparency` (docs/figures.toml), measured by `plait ab` and
# written between their `<!-- figure:ID -->` markers with the commit they
# were measured at (`plait-figures write`), and the thumbnails in
# docs/variants/ come from the same runs' images — no figure in those tables
# is typed by hand. About 10 minutes on lavapipe (2 cores); run it on an
# otherwise idle machine, since the tables hold GPU times. The transparency
# run leaves out the default scene: depth peeling it takes ~200 layers.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/ensure-vulkan.sh
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then export NODEVICE_SELECT=1; fi
cargo build --quiet --locked -p plait-cli -p plait-book
target=${CARGO_TARGET_DIR:-target}
runs="$target/figures"
"$target/debug/plait-figures" --runs "$runs" write gallery-shadows gallery-transparency

# Thumbnails: the default scene for self-shadowing, the stray scene for transparency.
mkdir -p docs/variants
for v in occupancy occupancy_no_slab deep_opacity opacity_shadow_maps density_clustering modified_shadow_map tressfx_shadow no_self_shadow; do
    cp "$runs/gallery-shadows/default-$v.png" "docs/variants/$v.png"
done
cp "$runs/gallery-shadows/default-reference.png" docs/variants/exact_shadow.png
for v in weighted_average alpha_to_coverage opaque linked_list shortcut; do
    cp "$runs/gallery-transparency/stray-$v.png" "docs/variants/$v.png"
done
cp "$runs/gallery-transparency/stray-reference.png" docs/variants/depth_peeling.png
echo "book/src/guide/gallery.md tables and docs/variants/*.png regenerated; look at the thumbnails before committing them."
