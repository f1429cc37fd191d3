#!/usr/bin/env bash
# The README's render command: make sure a Vulkan driver exists, then render
# the default pipeline (pipelines/occupancy.toml) on the built-in scene.
# Extra arguments go to `plait render` (e.g. --size 1280x960 --out hair.png).
set -euo pipefail
cd "$(dirname "$0")/.."
bash scripts/ensure-vulkan.sh
exec cargo run --quiet --locked -p plait-cli -- render "$@"
