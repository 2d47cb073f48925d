#!/usr/bin/env bash
# Frames per hour of the demo job for two eyeadapt binaries (before / after a change),
# alternating so that load on the shared machine hits both alike.
#
#   scripts/bench/demo-throughput.sh BEFORE_BIN AFTER_BIN [--frames 0-120:4] [--rounds 3]
#                                    [--size WxH] [--spp N] [--markdown FILE]
#
# Each round renders the selected demo frames (wall time of `eyeadapt sequence`, including
# estimators and the report) with each binary into a fresh directory; prints the medians and
# the after/before ratio. --size and --spp override the job's (a 1920x1080 frame at 1 spp
# measures what a frame costs besides its samples: estimators, previews, EXR, checksums).
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
[ $# -ge 2 ] || { echo "usage: demo-throughput.sh BEFORE_BIN AFTER_BIN [--frames SPEC] [--rounds N] [--size WxH] [--spp N] [--markdown FILE]" >&2; exit 2; }
A="$1" B="$2"
shift 2
FRAMES="0-120:4" ROUNDS=3 MD=""
OVERRIDES=() ASKED=""
while [ $# -gt 0 ]; do
    case "$1" in
        --frames) FRAMES="$2"; shift 2 ;;
        --rounds) ROUNDS="$2"; shift 2 ;;
        --markdown) MD="$2"; shift 2 ;;
        --size)
            [[ "$2" =~ ^([0-9]+)x([0-9]+)$ ]] || { echo "demo-throughput.sh: --size wants WxH, got $2" >&2; exit 2; }
            OVERRIDES+=(--width "${BASH_REMATCH[1]}" --height "${BASH_REMATCH[2]}")
            ASKED+=" --size $2"; shift 2 ;;
        --spp)
            [[ "$2" =~ ^[0-9]+$ ]] || { echo "demo-throughput.sh: --spp wants a number, got $2" >&2; exit 2; }
            OVERRIDES+=(--spp "$2")
            ASKED+=" --spp $2"; shift 2 ;;
        *) echo "demo-throughput.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
for r in $(seq "$ROUNDS"); do
    for which in before after; do
        bin=$A
        [ "$which" = after ] && bin=$B
        rm -rf "$WORK/out"
        s=$(date +%s.%N)
        "$bin" sequence --frames "$FRAMES" "${OVERRIDES[@]}" --out "$WORK/out" --log-format plain >/dev/null 2>&1
        e=$(date +%s.%N)
        n=$(awk -F, 'NR > 1 && $3 == "eye" { c++ } END { print c }' "$WORK/out/adaptation.csv")
        echo "$which $n $s $e" >>"$WORK/times"
        echo "round $r $which: $n frames" >&2
    done
done
python3 - "$WORK/times" "$FRAMES" "$ROUNDS" "$ASKED" <<'PY' | tee "$WORK/report.txt"
import statistics, sys
rows = [l.split() for l in open(sys.argv[1])]
fph = {}
for which, n, s, e in rows:
    fph.setdefault(which, []).append(3600 * int(n) / (float(e) - float(s)))
b, a = statistics.median(fph["before"]), statistics.median(fph["after"])
extra = f" with{sys.argv[4]}" if sys.argv[4] else ""
print(f"Demo job{extra}, frames {sys.argv[2]}, {sys.argv[3]} alternating rounds (wall time of the whole sequence command):")
for k in ("before", "after"):
    print(f"  {k:<6} median {statistics.median(fph[k]):7.0f} frames/hour  (runs: {', '.join(f'{x:.0f}' for x in fph[k])})")
print(f"  after / before: {a / b:.3f}")
PY
if [ -n "$MD" ]; then
    append_markdown "$MD" "Demo frames per hour, before and after" \
        "scripts/bench/demo-throughput.sh BEFORE AFTER --frames $FRAMES --rounds $ROUNDS$ASKED" "$WORK/report.txt"
fi
