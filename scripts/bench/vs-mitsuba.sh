#!/usr/bin/env bash
# eyeadapt against Mitsuba 3, side by side on one scene (default: the Cornell box).
#
#   scripts/bench/vs-mitsuba.sh [--samplers independent,multijitter,ldsampler|all]
#                               [--spp 16,64,256] [--runs 3] [--ref-spp 4096]
#                               [--scene scenes/cornell-box/cornell.xml]
#                               [--eyeadapt-scene PATH] [--eyeadapt BIN] [--json OUT]
#
# Sets up scripts/bench/.venv-bench (git-ignored) with `pip install mitsuba numpy` when they
# are missing, and tries to provide LLVM for Mitsuba's llvm_ad_rgb variant (Debian's
# libllvm19, via apt-get when run as root); without it Mitsuba runs as scalar_rgb only and
# the report says so. Builds eyeadapt with `cargo build --release` unless --eyeadapt (or
# $EYEADAPT) names a binary. Everything else, including the timing rules and the
# reference image, is in vs_mitsuba.py. Reference images are cached in scripts/bench/.cache.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
bench_venv

# LLVM for Dr.Jit's llvm backend: any libLLVM the dynamic loader knows about will do.
if ! ldconfig -p 2>/dev/null | grep -q 'libLLVM'; then
    if [ "$(id -u)" = 0 ] && command -v apt-get >/dev/null; then
        echo "installing libllvm19 for Mitsuba's llvm_ad_rgb variant" >&2
        DEBIAN_FRONTEND=noninteractive apt-get install -y -qq libllvm19 >&2 \
            || echo "could not install libllvm19: Mitsuba will run as scalar_rgb only" >&2
    else
        echo "no libLLVM found and cannot apt-get it: Mitsuba will run as scalar_rgb only" >&2
    fi
fi

EYEADAPT="${EYEADAPT:-}"
for ((i = 1; i <= $#; i++)); do
    if [ "${!i}" = "--eyeadapt" ]; then
        j=$((i + 1))
        EYEADAPT="${!j}"
    fi
done
ARGS=("$@")
if [ -z "$EYEADAPT" ]; then
    (cd "$REPO" && cargo build --release --bin eyeadapt >&2)
    EYEADAPT="$REPO/target/release/eyeadapt"
    ARGS+=(--eyeadapt "$EYEADAPT")
elif [[ ! " $* " =~ " --eyeadapt " ]]; then
    ARGS+=(--eyeadapt "$EYEADAPT")
fi
# A private copy, so that a rebuild during the benchmark cannot swap the binary midway.
BIN="$(mktemp -d)/eyeadapt"
cp "$EYEADAPT" "$BIN"
trap 'rm -rf "$(dirname "$BIN")"' EXIT
for ((i = 0; i < ${#ARGS[@]}; i++)); do
    if [ "${ARGS[$i]}" = "--eyeadapt" ]; then ARGS[$((i + 1))]="$BIN"; fi
done

cd "$REPO"
"$VENV/bin/python" "$HERE/vs_mitsuba.py" "${ARGS[@]}"
