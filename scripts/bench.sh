#!/usr/bin/env bash
# The book's performance figures, one benchmark after the other (see its
# "Performance" page): the floor benchmark at the page's size and
# repeats, the executor's encode time (criterion), the scaling run, the
# papers' speed claims. About
# 30 minutes on lavapipe (2 cores); run it on an otherwise idle machine —
# the figures are GPU times. Each benchmark also runs alone, with its
# defaults kept short: `cargo bench -p plait --bench floor|encode|scaling`.
#
#   bash scripts/bench.sh --check [ID…]   re-measure the published figures
#       (docs/figures.toml: the README's and the book's measured tables) and
#       print, per value, the published value, today's and today's spread;
#       exits 1 when one moved beyond its spread. Run it before resolving an
#       issue that touches a measured pass; regenerate what moved with
#       `target/debug/plait-figures write ID`. `--stale` lists the figures
#       measured before the last change to the files they measure (no GPU).
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
bash scripts/ensure-vulkan.sh
# Without a display session, Mesa's device-select layer has nothing to select (as scripts/test.sh).
if [ -z "${XDG_RUNTIME_DIR:-}" ]; then export NODEVICE_SELECT=1; fi
case "${1:-}" in
--check | --stale)
    cargo build --quiet --locked -p plait-cli -p plait-book
    figures="${CARGO_TARGET_DIR:-target}/debug/plait-figures"
    if [ "$1" = --stale ]; then exec "$figures" stale; fi
    shift
    # A figure measured against references/path_traced.toml renders with
    # Mitsuba (installed once into the build folder; a cached image needs none).
    eval "$(bash scripts/ensure-mitsuba.sh)"
    exec "$figures" check "$@"
    ;;
esac
cargo bench --locked -p plait --bench floor -- --size 320x240 --repeats 5
# Strand-space shading against its own floor, beside fragment space (issue 22).
cargo bench --locked -p plait --bench floor -- --only occupancy --set techniques.shading_space=strand --size 320x240 --repeats 9
cargo bench --locked -p plait --bench encode
cargo bench --locked -p plait --bench scaling -- --repeats 3 --largest
# The papers' speed claims, interleaved, into the book's claims page.
cargo bench --locked -p plait --bench claims -- --repeats 3 --write
