#!/usr/bin/env bash
# Render efficiency of two eyeadapt binaries (before / after a change) on one scene, against a
# high-spp reference both of them rendered: RMSE, render seconds and 1/(RMSE²·seconds).
#
#   scripts/bench/render-efficiency.sh BEFORE_BIN AFTER_BIN [--scene scenes/three-rooms/scene.toml]
#                                      [--spp 16,64] [--seeds 3] [--ref-spp 2048] [--markdown FILE]
#
# Uses scripts/bench/.venv-bench (numpy, and Mitsuba's EXR reader), set up as by vs-mitsuba.sh.
# The rules (alternation, reference, timing) are in render_efficiency.py.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
[ $# -ge 2 ] || { echo "usage: render-efficiency.sh BEFORE_BIN AFTER_BIN [--scene PATH] [--spp LIST] [--seeds N] [--ref-spp N] [--markdown FILE]" >&2; exit 2; }
A="$1" B="$2"
shift 2
MD="" ARGS=()
while [ $# -gt 0 ]; do
    case "$1" in
        --markdown) MD="$2"; shift 2 ;;
        --scene | --spp | --seeds | --ref-spp) ARGS+=("$1" "$2"); shift 2 ;;
        *) echo "render-efficiency.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
bench_venv
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
"$VENV/bin/python" "$HERE/render_efficiency.py" "$A" "$B" --work "$WORK" ${ARGS[@]+"${ARGS[@]}"} | tee "$WORK/report.txt"
if [ -n "$MD" ]; then
    append_markdown "$MD" "Render efficiency, before vs after" \
        "scripts/bench/render-efficiency.sh $A $B${ARGS[*]:+ ${ARGS[*]}}" "$WORK/report.txt"
fi
