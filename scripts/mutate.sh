#!/usr/bin/env bash
# A mutation score for every technique (book: Reliability, "Mutation score"):
#
#   bash scripts/mutate.sh [TECHNIQUE…] [--max N] [--seed S] [--only ID…] [--list]
#
# Mutates each technique's WGSL one change at a time (tests/mutation.toml says
# which files and which tests) and runs that technique's own golden, claims and
# unit tests against each mutant. Writes target/mutate/mutation.md (the table,
# with the commit it was measured at) and target/mutate/mutation.json (every
# mutant with its diff and outcome). Long — a command to run before resolving
# an issue, not CI. Mutants are written over the checkout's files and put back
# (content and mtime) after each; commit nothing while it runs.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

bash scripts/ensure-vulkan.sh
# The goldens were made with lavapipe (scripts/test.sh pins it the same way).
if [ -z "${VK_ICD_FILENAMES:-}" ] && [ -z "${VK_DRIVER_FILES:-}" ]; then
    lvp=$(compgen -G "/usr/share/vulkan/icd.d/lvp_icd*.json" | head -n 1 || true)
    if [ -n "$lvp" ]; then
        export VK_ICD_FILENAMES="$lvp"
    fi
fi
export NODEVICE_SELECT=1
# Mutants must reach the tests through the checkout, not a search path.
unset PLAIT_PATH

cargo build --locked -p plait-mutate
exec "${CARGO_TARGET_DIR:-target}/debug/plait-mutate" "$@"
