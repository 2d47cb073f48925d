#!/usr/bin/env bash
# The benchmark suite (issue 23): eyeadapt against Mitsuba 3 llvm_ad_rgb on the Cornell box and
# matpreview of a mitsuba-data checkout, the built-in interior and three rooms, and a
# 1M-triangle mesh; samples/s and efficiency, render call against render call and whole
# process against whole process (suite.py says how each is timed).
#
#   scripts/bench/suite.sh MITSUBA_DATA_DIR [--size 128] [--spp 64] [--runs 3]
#                          [--samplers multijitter,ldsampler] [--scenes cbox,matpreview,...]
#                          [--ref-spp 2048] [--cache DIR] [--eyeadapt BIN] [--json OUT]
#                          [--markdown docs/benchmarks/suite.md --label TITLE]
#
# Uses the venv of vs-mitsuba.sh ($VENV, default scripts/bench/.venv-bench: `pip install
# mitsuba numpy`) and needs a libLLVM for llvm_ad_rgb (Debian's libllvm19). Builds eyeadapt with
# `cargo build --release` unless --eyeadapt (or $EYEADAPT) names a binary, and benchmarks a
# private copy of it. References and generated scenes are cached in --cache (default
# ~/.cache/eyeadapt-bench), outside the repository.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
if [ $# -lt 1 ] || [ ! -d "$1" ]; then
    echo "usage: $0 MITSUBA_DATA_DIR [--size N] [--spp N] [--runs N] [--samplers LIST] [--scenes LIST] [--ref-spp N] [--eyeadapt BIN] [--markdown FILE --label TITLE]" >&2
    exit 2
fi
DIR="$(cd "$1" && pwd)"
shift
ARGS=()
EYEADAPT="${EYEADAPT:-}"
while [ $# -gt 0 ]; do
    case "$1" in
        --eyeadapt) EYEADAPT="$2"; shift 2 ;;
        *) ARGS+=("$1"); shift ;;
    esac
done
bench_venv
eyeadapt_binary "$EYEADAPT"
# A private copy, so that a rebuild during the benchmark cannot swap the binary midway.
PRIVATE="$(mktemp -d)"
trap 'rm -rf "$PRIVATE"' EXIT
cp "$BIN" "$PRIVATE/eyeadapt"
cd "$REPO"
"$VENV/bin/python" "$HERE/suite.py" "$DIR" --eyeadapt "$PRIVATE/eyeadapt" "${ARGS[@]}"
