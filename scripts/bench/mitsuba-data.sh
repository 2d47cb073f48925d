#!/usr/bin/env bash
# Every in-scope scene of a mitsuba-data checkout through eyeadapt: a table of
# scene / loads / renders / first error, and the totals.
#
#   scripts/bench/mitsuba-data.sh DIR [--eyeadapt BIN] [--spp 1] [--size 16] [--timeout 300] [--list]
#
# DIR is a checkout of github.com/mitsuba-renderer/mitsuba-data (never committed here). The
# scene list and what is out of scope are in mitsuba_data.py. Builds eyeadapt with
# `cargo build --release` unless --eyeadapt (or $EYEADAPT) names a binary. Each scene renders
# once at 16×16, 1 spp, one thread: a load-and-run check, not a benchmark.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"

if [ $# -lt 1 ] || [ ! -d "$1" ]; then
    echo "usage: $0 MITSUBA_DATA_DIR [--eyeadapt BIN] [--spp N] [--size N] [--timeout S] [--list]" >&2
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
eyeadapt_binary "$EYEADAPT"
python3 "$HERE/mitsuba_data.py" "$DIR" --eyeadapt "$BIN" "${ARGS[@]}"
