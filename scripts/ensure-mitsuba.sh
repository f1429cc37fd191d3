#!/usr/bin/env bash
# Make sure Mitsuba 3 (the path tracer plait's physical checks compare
# against) is installed, pinned, in a virtual environment inside the build
# folder: ${CARGO_TARGET_DIR:-target}/mitsuba-venv. Its fast variant
# llvm_ad_rgb JIT-compiles through LLVM and needs LLVM >= 16 (Debian 12's
# libllvm15 aborts with "Cannot select fminimum"), so libllvm19 is installed
# when missing. Idempotent: when everything is there it only checks and exits.
# Prints, on stdout, `export` lines for the environment render.py needs, so a
# caller can `eval "$(bash scripts/ensure-mitsuba.sh)"`.
set -euo pipefail

MITSUBA_VERSION=3.9.1
DRJIT_VERSION=1.5.0 # the drjit that mitsuba 3.9.1 requires (its Requires-Dist)
NUMPY_VERSION=2.4.6 # render.py reads the image through numpy

root="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
target="${CARGO_TARGET_DIR:-$root/target}"
venv="$target/mitsuba-venv"

find_llvm() {
    local f
    for f in /usr/lib/llvm-19/lib/libLLVM-19.so /usr/lib/x86_64-linux-gnu/libLLVM-19.so.1 \
        /usr/lib/*-linux-gnu/libLLVM-19.so* /usr/lib/llvm-19/lib/libLLVM.so*; do
        [ -e "$f" ] && { echo "$f"; return 0; }
    done
    return 1
}

if ! llvm="$(find_llvm)"; then
    if [ "$(id -u)" = "0" ] && command -v apt-get >/dev/null; then
        echo "plait: installing libllvm19 (Mitsuba's llvm variant needs LLVM >= 16)" >&2
        apt-get update -qq
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libllvm19 >/dev/null
        llvm="$(find_llvm)" || { echo "plait: libllvm19 installed but libLLVM-19.so not found" >&2; exit 2; }
    else
        echo "plait: Mitsuba needs LLVM >= 16: install it, e.g. 'sudo apt-get install -y libllvm19'" >&2
        exit 2
    fi
fi

py="$venv/bin/python"
installed() {
    [ -x "$py" ] && "$py" - "$MITSUBA_VERSION" "$DRJIT_VERSION" "$NUMPY_VERSION" <<'PY' 2>/dev/null
import sys
from importlib.metadata import version
want = tuple(sys.argv[1:4])
sys.exit(0 if (version("mitsuba"), version("drjit"), version("numpy")) == want else 1)
PY
}

# Tests run in parallel and each makes sure of Mitsuba: one installs while
# the others wait (flock), and an install cut short is started afresh
# (`--clear`), never half-used.
mkdir -p "$target"
exec 9>"$target/mitsuba-venv.lock"
flock 9
if ! installed; then
    echo "plait: installing mitsuba==$MITSUBA_VERSION drjit==$DRJIT_VERSION into $venv" >&2
    python3 -m venv --clear "$venv"
    "$py" -m pip install -q --disable-pip-version-check \
        "mitsuba==$MITSUBA_VERSION" "drjit==$DRJIT_VERSION" "numpy==$NUMPY_VERSION" >&2
fi
flock -u 9

echo "export PLAIT_MITSUBA_PYTHON='$py'"
echo "export DRJIT_LIBLLVM_PATH='$llvm'"
