#!/usr/bin/env bash
# The README's render command: make sure a Vulkan driver exists, then render
# pipelines/default.toml (the Chiang fibre with dual scattering on the
# occupancy maps, issue 43) on the built-in scene.
# Arguments go to `plait render` (e.g. --size 1280x960 --out hair.png). A
# first argument that is not a flag is the pipeline instead, e.g. the
# occupancy paper's own pipeline, which `plait render` alone renders:
#   bash scripts/render.sh pipelines/occupancy.toml
# It runs where you are, so relative paths (--out mine.png, a pipeline or
# scene file) are relative to your directory, as with the `plait` binary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/ensure-vulkan.sh"
# Build first with cargo's progress on stderr (the first build takes minutes),
# then run quietly, so the render's own output is not mixed with cargo's.
cargo build --locked --manifest-path "$root/Cargo.toml" -p plait-cli
if [[ $# -eq 0 || "$1" == -* ]]; then
    set -- "$root/pipelines/default.toml" "$@"
fi
exec cargo run --quiet --locked --manifest-path "$root/Cargo.toml" -p plait-cli -- render "$@"
