#!/usr/bin/env bash
# Make sure the web build's tools are there: Rust's wasm32-unknown-unknown
# target and wasm-bindgen's CLI at exactly the version of the wasm-bindgen
# crate in Cargo.lock (the two must match), installed once per machine into
# ${PLAIT_TOOLS:-~/.cache/plait/tools}/wasm-bindgen-VERSION (not the build
# folder: compiling the CLI takes minutes, and a fresh clone — CI's — would
# pay them every run), so a second run only checks. Prints the CLI's path.
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
tools="${PLAIT_TOOLS:-${HOME:-/root}/.cache/plait/tools}"
cli="$tools/wasm-bindgen-$version/bin/wasm-bindgen"
# Not --locked: the CLI's own lock file names a webpki-roots release (for its
# unused download feature's TLS) that the registry mirror may not carry yet;
# the CLI's version itself is pinned exactly.
if ! [ -x "$cli" ] || [ "$("$cli" --version | awk '{print $2}')" != "$version" ]; then
    echo "plait: installing wasm-bindgen-cli $version into $tools (once per machine)" >&2
    # Optimized less than a release build (it compiles in about half the
    # time, and binds plait's wasm in seconds all the same); its own target
    # folder, so the CLI's dependencies do not mix with plait's.
    CARGO_PROFILE_RELEASE_OPT_LEVEL=1 CARGO_PROFILE_RELEASE_LTO=false \
        CARGO_PROFILE_RELEASE_CODEGEN_UNITS=16 CARGO_TARGET_DIR="$target/wasm-bindgen-build" \
        cargo install wasm-bindgen-cli --version "=$version" \
        --root "$tools/wasm-bindgen-$version" --quiet >&2
fi
echo "$cli"
