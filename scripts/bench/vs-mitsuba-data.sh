#!/usr/bin/env bash
# eyeadapt against Mitsuba 3 (llvm_ad_rgb) on scenes of a mitsuba-data checkout: channel means
# and per-pixel difference relative to noise, one table row per scene (vs_mitsuba_data.py).
#
#   scripts/bench/vs-mitsuba-data.sh DIR --scenes a.xml,b.xml [--size 64] [--spp 256]
#                                    [--ref-spp 1024] [--eyeadapt BIN]
#
# Uses the venv of vs-mitsuba.sh (scripts/bench/.venv-bench, `pip install mitsuba numpy`) and
# needs a libLLVM for llvm_ad_rgb (Debian's libllvm19; vs-mitsuba.sh installs it as root).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
if [ $# -lt 1 ] || [ ! -d "$1" ]; then
    echo "usage: $0 MITSUBA_DATA_DIR --scenes LIST [--size N] [--spp N] [--ref-spp N] [--eyeadapt BIN]" >&2
    exit 2
fi
DIR="$1"
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
"$VENV/bin/python" "$HERE/vs_mitsuba_data.py" "$DIR" --eyeadapt "$BIN" "${ARGS[@]}"
