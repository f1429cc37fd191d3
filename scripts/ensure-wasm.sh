#!/usr/bin/env bash
# Make sure the web build's tools are there: Rust's wasm32-unknown-unknown
# target and wasm-bindgen's CLI at exactly the version of the wasm-bindgen
# crate in Cargo.lock (the two must match), installed into the build folder
# (${CARGO_TARGET_DIR:-target}/wasm-bindgen) so a second run only checks.
# Prints the CLI's path on stdout.
set -euo pipefail

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
version=$(awk '/^name = "wasm-bindgen"$/ { getline; gsub(/[^0-9.]/, ""); print; exit }' "$root/Cargo.lock")
if [ -z "$version" ]; then
    echo "plait: no wasm-bindgen in Cargo.lock" >&2
    exit 2
fi
if ! rustup target list --installed | grep -qx wasm32-unknown-unknown; then
    echo "plait: adding Rust's wasm32-unknown-unknown target (the web build)" >&2
    rustup target add wasm32-unknown-unknown >&2
fi
cli="$target/wasm-bindgen/bin/wasm-bindgen"
# Not --locked: the CLI's own lock file names a webpki-roots release (for its
# unused download feature's TLS) that the registry mirror may not carry yet;
# the CLI's version itself is pinned exactly.
if ! [ -x "$cli" ] || [ "$("$cli" --version | awk '{print $2}')" != "$version" ]; then
    echo "plait: installing wasm-bindgen-cli $version into $target/wasm-bindgen" >&2
    cargo install wasm-bindgen-cli --version "=$version" \
        --root "$target/wasm-bindgen" --quiet >&2
fi
echo "$cli"
