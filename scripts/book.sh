#!/usr/bin/env bash
# Builds plait's book into target/book/index.html ($CARGO_TARGET_DIR/book when set): the guide (book/src/), a
# page per technique and per gallery pipeline generated from their files, the
# pictures rendered by `plait` on the small and stray scenes, and the design
# notes, and the live view (scripts/web.sh's site, under live/, opened from
# every technique and gallery page); then checks every link and image. No
# network is needed.
#   bash scripts/book.sh                     # build + file check
#   bash scripts/book.sh --browser           # + every page opened in headless Chromium
#   bash scripts/book.sh --screenshots DIR   # + pictures of the index and a technique page
# Further flags: --size WxH (pictures, default 256x192), --out DIR, --stage DIR.
set -euo pipefail
root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
cd "$root"
bash scripts/ensure-vulkan.sh
if [[ " $* " == *" --browser "* || " $* " == *" --screenshots "* ]]; then
    bash scripts/ensure-chromium.sh
fi
cargo build --locked -p plait-cli -p plait-book
target="${CARGO_TARGET_DIR:-$root/target}"
# The live view (plait's engine on WebGPU, crates/plait-web): the book
# carries it under live/ and every technique and gallery page opens it.
live="$(bash scripts/web.sh "$target/book-live")"
# The book goes under the build folder, wherever CARGO_TARGET_DIR puts it
# (later flags win, so --out and --stage still choose).
exec "$target/debug/plait-book" --plait "$target/debug/plait" \
    --out "$target/book" --stage "$target/book-src" --live "$live" "$@"
