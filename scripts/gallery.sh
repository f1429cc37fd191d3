#!/usr/bin/env bash
# Regenerates the book's measured gallery (book/src/guide/gallery.md): the
# tables between the
# `<!-- gallery:NAME -->` and `<!-- /gallery:NAME -->` markers come from the
# `report.md` of two `plait ab` runs, and the thumbnails in docs/variants/
# from their images — no figure in those tables is typed by hand.
# About 10 minutes on lavapipe (2 cores); run it on an otherwise idle machine,
# since the tables hold GPU times.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/ensure-vulkan.sh
cargo build --quiet --locked -p plait-cli
plait=target/debug/plait
out=$(mktemp -d)
trap 'rm -rf "$out"' EXIT

# Self-shadowing against exact shadows, on three scenes.
"$plait" ab pipelines/{occupancy,occupancy_no_slab,deep_opacity,opacity_shadow_maps,density_clustering,modified_shadow_map,tressfx_shadow,no_self_shadow}.toml \
    --reference pipelines/exact_shadow.toml \
    --scene examples/scenes/small.toml --scene examples/scenes/stray.toml --scene examples/scenes/default.toml \
    --size 320x240 --repeats 1 --out "$out/shadows"
# Transparency against depth peeling (the default scene needs ~200 peeled
# layers, about 15 minutes a frame here, so it is not in this run).
"$plait" ab pipelines/{occupancy,weighted_average,alpha_to_coverage,opaque,linked_list,shortcut}.toml \
    --reference pipelines/depth_peeling.toml \
    --scene examples/scenes/small.toml --scene examples/scenes/stray.toml \
    --size 256x192 --repeats 2 --out "$out/transparency"

# Thumbnails: the default scene for self-shadowing, the stray scene for transparency.
mkdir -p docs/variants
for v in occupancy occupancy_no_slab deep_opacity opacity_shadow_maps density_clustering modified_shadow_map tressfx_shadow no_self_shadow; do
    cp "$out/shadows/default-$v.png" "docs/variants/$v.png"
done
cp "$out/shadows/default-reference.png" docs/variants/exact_shadow.png
for v in weighted_average alpha_to_coverage opaque linked_list shortcut; do
    cp "$out/transparency/stray-$v.png" "docs/variants/$v.png"
done
cp "$out/transparency/stray-reference.png" docs/variants/depth_peeling.png

# Put each report.md between its markers in the gallery page; the book's
# technique and pipeline pages take their rows from there (scripts/book.sh).
page=book/src/guide/gallery.md
replace() {
    local name=$1 file=$2
    awk -v name="$name" -v file="$file" '
        $0 == "<!-- gallery:" name " -->" { print; while ((getline line < file) > 0) print line; skip = 1; next }
        $0 == "<!-- /gallery:" name " -->" { skip = 0 }
        !skip { print }
    ' "$page" > "$page.new"
    mv "$page.new" "$page"
}
replace shadows "$out/shadows/report.md"
replace transparency "$out/transparency/report.md"
echo "$page gallery tables and docs/variants/*.png regenerated; look at the thumbnails before committing them."
