#!/usr/bin/env bash
# The evidence behind the default tone-mapping operator: runs
# tests/display.rs's tone_mapping_choice (every operator on the default and
# mesh-head scenes, at exposure 0 and +2) and writes its table into the
# comment block of techniques/tone_mapping/point.toml between the
# `measured:` markers, so the numbers there are this command's output.
# Run it again after anything changes the radiance (light units, shading).
# `bash scripts/tone_mapping_choice.sh default` does the same for
# pipelines/default.toml (tests/display.rs's
# default_pipeline_tone_mapping_choice), into that file's comment.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."
case "${1:-}" in
    "") test=tone_mapping_choice; file=techniques/tone_mapping/point.toml ;;
    default) test=default_pipeline_tone_mapping_choice; file=pipelines/default.toml ;;
    *) echo "usage: bash scripts/tone_mapping_choice.sh [default]" >&2; exit 2 ;;
esac
out=$(cargo test -p plait-tests --test display --locked -- --test-threads=1 --nocapture --exact "$test")
table=$(printf '%s\n' "$out" | sed -n "s/^test $test \\.\\.\\. //; /^|/p")
adapter=$(printf '%s\n' "$out" | sed -n 's/^.*adapter: //p' | head -1)
python3 - "$table" "$adapter" "$file" "${1:-}" <<'PY'
import sys, pathlib
table, adapter, file, arg = sys.argv[1:5]
path = pathlib.Path(file)
text = path.read_text()
begin, end = "# measured: begin\n", "# measured: end\n"
head, rest = text.split(begin)
_, tail = rest.split(end)
body = "".join(f"# {line}\n" for line in [
    f"bash scripts/tone_mapping_choice.sh{' ' + arg if arg else ''} on {adapter}, 320x240:",
    *table.splitlines()])
path.write_text(head + begin + body + end + tail)
PY
printf '%s\n' "$table"
