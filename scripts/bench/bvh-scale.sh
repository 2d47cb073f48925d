#!/usr/bin/env bash
# BVH build scale (issue 10, goal 4): build time, memory and ray throughput for a generated
# mesh of N triangles (default 1M), with 1 and 2 threads, for the renderer's own preset choice
# and for obvhs's medium preset (the choice below 256k triangles) for comparison.
#
#   scripts/bench/bvh-scale.sh [--triangles N] [--runs R] [--eyeadapt BIN] [--markdown FILE]
#
# Prints the machine's load average with the table: these machines are shared, so compare the
# presets within one run rather than absolute times across runs.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
N=1000000 RUNS=5 BIN="" MD=""
while [ $# -gt 0 ]; do
    case "$1" in
        --triangles) N="$2"; shift 2 ;;
        --runs) RUNS="$2"; shift 2 ;;
        --eyeadapt) BIN="$2"; shift 2 ;;
        --markdown) MD="$2"; shift 2 ;;
        *) echo "bvh-scale.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
eyeadapt_binary "$BIN"
OUT="$(mktemp)"
trap 'rm -f "$OUT"' EXIT
{
    echo "BVH scale: $N generated triangles (displaced terrain), median of $RUNS builds;"
    echo "load average before: $(cut -d' ' -f1-3 /proc/loadavg), $(nproc) cores."
    echo
    printf '%-8s %-8s %9s %10s %12s %14s %12s %12s\n' threads preset "build s" "Mtris/s" \
        "MiB/Mtris" "peak RSS/Mtris" "closest Mr/s" "shadow Mr/s"
    for threads in 1 2; do
        for preset in default medium; do
            args=(--threads "$threads" bench --bvh-triangles "$N" --runs "$RUNS")
            [ "$preset" = default ] || args+=(--bvh-preset "$preset")
            r="$("$BIN" "${args[@]}")"
            build=$(grep -o 'build median [0-9.]*' <<<"$r" | awk '{print $3}')
            rate=$(grep -o '= [0-9.]* M triangles/s' <<<"$r" | awk '{print $2}')
            mem=$(grep -o '= [0-9.]* MiB per million triangles (BVH' <<<"$r" | awk '{print $2}')
            rss=$(grep -o 'build +[0-9.]* MiB = [0-9.]* MiB per' <<<"$r" | awk '{print $5}')
            cl=$(grep -o 'closest hit [0-9.]*' <<<"$r" | awk '{print $3}')
            sh=$(grep -o 'shadow [0-9.]* M rays' <<<"$r" | awk '{print $2}')
            name=$preset
            [ "$preset" = default ] && name=$(grep -o 'preset [^)]*' <<<"$r" | head -1 | cut -d' ' -f2-)
            printf '%-8s %-8s %9s %10s %12s %14s %12s %12s\n' "$threads" "${name:0:8}" "$build" \
                "$rate" "$mem" "$rss" "$cl" "$sh"
        done
    done
    echo
    echo "load average after: $(cut -d' ' -f1-3 /proc/loadavg)."
    echo "preset 'default' = eyeadapt's choice for the size (crates/tracer/src/accel.rs, build_params)."
} | tee "$OUT"
if [ -n "$MD" ]; then
    append_markdown "$MD" "BVH scale" "scripts/bench/bvh-scale.sh --triangles $N --runs $RUNS" "$OUT"
fi
