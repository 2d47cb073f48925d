#!/usr/bin/env bash
# Path guiding's efficiency per scene: `render --guiding on` against `--guiding off`, RMSE and
# relMSE against a high-spp unguided reference, wall and CPU seconds, 1/(MSE·t) and its gain.
#
#   scripts/bench/guiding.sh [--bin BIN] [--scenes builtin:interior,builtin:three-rooms,...]
#                            [--size 160x90] [--spp 16,64,256] [--seeds 2] [--ref-spp 2048]
#                            [--markdown docs/benchmarks/guiding.md]
#
# Uses $VENV (default scripts/bench/.venv-bench; numpy and Mitsuba's EXR reader). The rules
# (alternation, reference, timing) are in guiding.py.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
ORIG="$*"
SCENES="builtin:interior,builtin:three-rooms,$HERE/guiding-two-rooms.toml"
MD="" BINARG="" ARGS=()
while [ $# -gt 0 ]; do
    case "$1" in
        --markdown) MD="$2"; shift 2 ;;
        --bin) BINARG="$2"; shift 2 ;;
        --scenes) SCENES="$2"; shift 2 ;;
        --size | --spp | --seeds | --ref-spp) ARGS+=("$1" "$2"); shift 2 ;;
        *) echo "guiding.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
eyeadapt_binary "$BINARG"
bench_venv
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
IFS=',' read -r -a LIST <<<"$SCENES"
for s in "${LIST[@]}"; do
    mkdir -p "$WORK/$(basename "$s")"
    "$VENV/bin/python" "$HERE/guiding.py" "$BIN" --scene "$s" --work "$WORK/$(basename "$s")" \
        ${ARGS[@]+"${ARGS[@]}"} | tee -a "$WORK/report.txt"
    echo | tee -a "$WORK/report.txt"
done
if [ -n "$MD" ]; then
    append_markdown "$MD" "Path guiding, guided against unguided" "scripts/bench/guiding.sh $ORIG" "$WORK/report.txt"
fi
