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
    [ -x "$py" ] && "$py" - "$MITSUBA_VERSION" "$DRJIT_VERSION" <<'PY' 2>/dev/null
import sys
from importlib.metadata import version
sys.exit(0 if (version("mitsuba"), version("drjit")) == tuple(sys.argv[1:3]) else 1)
PY
}

if ! installed; then
    echo "plait: installing mitsuba==$MITSUBA_VERSION drjit==$DRJIT_VERSION into $venv" >&2
    python3 -m venv "$venv"
    "$py" -m pip install -q --disable-pip-version-check \
        "mitsuba==$MITSUBA_VERSION" "drjit==$DRJIT_VERSION" numpy >&2
fi

echo "export PLAIT_MITSUBA_PYTHON='$py'"
echo "export DRJIT_LIBLLVM_PATH='$llvm'"
