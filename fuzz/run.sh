#!/usr/bin/env bash
# Coverage-guided fuzzing of plait's parsers with cargo-fuzz (libFuzzer).
# Needs a nightly toolchain and `cargo install cargo-fuzz`. Seeds every
# target's corpus from the repository's own files, runs each target for
# SECONDS (default 60), bounded per input in time (-timeout) and memory
# (-rss_limit_mb), and prints libFuzzer's input count. Crashes land in
# fuzz/artifacts/TARGET/ and must become regression tests.
#   bash fuzz/run.sh [SECONDS]
set -euo pipefail
here="$(cd "$(dirname "$0")" && pwd)"
root="$(dirname "$here")"
secs="${1:-60}"
cd "$root"
mkdir -p "$here"/corpus/{hair,tfx,usd,scene,pipeline,gltf} "$here/logs"
cp examples/scenes/*.toml "$here/corpus/scene/"
cp pipelines/*.toml "$here/corpus/pipeline/"
cp examples/scenes/*.glb "$here/corpus/gltf/"
for spec in "4 3" "40 16"; do
    set -- $spec
    cargo run -q -p plait-cli -- hair generate --strands "$1" --segments "$2" \
        --out "$here/corpus/hair/g$1x$2.hair" >/dev/null
    cargo run -q -p plait-cli -- hair convert "$here/corpus/hair/g$1x$2.hair" \
        "$here/corpus/tfx/g$1x$2.tfx" >/dev/null
    # The usd target reads text and binary alike (as a .usd): both seeded.
    for ext in usda usdc; do
        cargo run -q -p plait-cli -- hair convert "$here/corpus/hair/g$1x$2.hair" \
            "$here/corpus/usd/g$1x$2.$ext" >/dev/null
    done
done
cd "$here"
total=0
for target in hair tfx usd scene pipeline gltf; do
    # -s none: plait has no unsafe code; coverage guidance without ASan runs
    # several times faster.
    cargo +nightly fuzz run -s none "$target" "corpus/$target" -- \
        -max_total_time="$secs" -timeout=10 -rss_limit_mb=2048 -max_len=65536 \
        -print_final_stats=1 >"logs/$target.log" 2>&1 || {
        echo "$target: FAILED, see fuzz/logs/$target.log and fuzz/artifacts/$target/"
        exit 1
    }
    runs=$(grep -o 'stat::number_of_executed_units: *[0-9]*' "logs/$target.log" | grep -o '[0-9]*$')
    cov=$(grep -o 'cov: [0-9]*' "logs/$target.log" | tail -1)
    echo "$target: $runs inputs, $cov, 0 crashes, 0 timeouts, 0 out-of-memory"
    total=$((total + runs))
done
echo "all: $total inputs"
