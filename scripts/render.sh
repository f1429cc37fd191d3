#!/usr/bin/env bash
# The README's render command: make sure a Vulkan driver exists, then render
# the default pipeline (pipelines/occupancy.toml) on the built-in scene.
# Extra arguments go to `plait render` (e.g. --size 1280x960 --out hair.png).
# It runs where you are, so relative paths (--out mine.png, a pipeline or
# scene file) are relative to your directory, as with the `plait` binary.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
bash "$root/scripts/ensure-vulkan.sh"
# Build first with cargo's progress on stderr (the first build takes minutes),
# then run quietly, so the render's own output is not mixed with cargo's.
cargo build --locked --manifest-path "$root/Cargo.toml" -p plait-cli
exec cargo run --quiet --locked --manifest-path "$root/Cargo.toml" -p plait-cli -- render "$@"
