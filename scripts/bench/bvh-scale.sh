#!/usr/bin/env bash
# BVH build scale (issue 10, goal 4): build time, memory and ray throughput of the renderer's
# Accel::build (obvhs CWBVH + the copy into BVH order) on a generated terrain mesh, for each
# obvhs preset, each thread count and each mesh size (default: 1M triangles and the Cornell
# box's 36), through `eyeadapt bench --bvh-triangles`.
#
#   scripts/bench/bvh-scale.sh [--triangles 1000000,36] [--presets fastest,very_fast,fast,medium,default]
#                              [--threads 1,2] [--runs 5] [--repeats 3] [--eyeadapt BIN]
#                              [--json OUT] [--markdown FILE]
#
# Preset `default` is the renderer's own choice for the size (accel.rs, build_params); the
# table names the preset it picked. Each cell is the median over --repeats processes of
# (build: the median of --runs builds; rays: one pass of 2^20 rays per set). The processes
# run round-robin over the configurations, so load from others on the shared machine falls on
# all of them alike; the load average before and after is printed with the table. Columns:
#   build s       median seconds per Accel::build_with        Mtris/s    triangles / build s
#   min s         the fastest of the builds (least disturbed by other load)
#   obvhs s       median seconds of obvhs's build_cwbvh_from_tris alone on the same triangles
#   MB/Mtris      Accel::memory_bytes() per million triangles (10^6 bytes)
#   RSS MB/Mtris  peak-RSS (VmHWM) increase of the first build per million triangles (not
#                 shown below 100k triangles, where it is fixed overhead)
#   prim, inside  closest-hit M rays/s: 1024² pinhole rays from outside the mesh, and uniform
#                 random rays from inside its bounds; shadow: M rays/s of 0.5-long segments
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
# shellcheck disable=SC2034 # common.sh builds the binary of REPO
REPO="$(cd "$HERE/../.." && pwd)"
SIZES=1000000,36 PRESETS=fastest,very_fast,fast,medium,default THREADS=1,2
RUNS=5 REPEATS=3 BIN="" JSON="" MD=""
while [ $# -gt 0 ]; do
    case "$1" in
        --triangles) SIZES="$2"; shift 2 ;;
        --presets) PRESETS="$2"; shift 2 ;;
        --threads) THREADS="$2"; shift 2 ;;
        --runs) RUNS="$2"; shift 2 ;;
        --repeats) REPEATS="$2"; shift 2 ;;
        --eyeadapt) BIN="$2"; shift 2 ;;
        --json) JSON="$2"; shift 2 ;;
        --markdown) MD="$2"; shift 2 ;;
        *) echo "bvh-scale.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
eyeadapt_binary "$BIN"
IFS=, read -ra sizes <<<"$SIZES"
IFS=, read -ra presets <<<"$PRESETS"
IFS=, read -ra threads <<<"$THREADS"
RAW="$(mktemp)" OUT="$(mktemp)"
trap 'rm -f "$RAW" "$OUT"' EXIT

load_before="$(uptime)"
# One line per process: "size label threads key=value ...", from the bench's last line.
for ((rep = 1; rep <= REPEATS; rep++)); do
    for n in "${sizes[@]}"; do
        for p in "${presets[@]}"; do
            for t in "${threads[@]}"; do
                args=(--threads "$t" bench --bvh-triangles "$n" --runs "$RUNS")
                [ "$p" = default ] || args+=(--bvh-preset "$p")
                line="$("$BIN" "${args[@]}" | grep '^bvh-bench: ')"
                echo "$n $p $t ${line#bvh-bench: }" >>"$RAW"
                echo "repeat $rep/$REPEATS: $n triangles, $p, $t threads: ${line#bvh-bench: }" >&2
            done
        done
    done
done
load_after="$(uptime)"

# Medians per (size, label, threads), in the order of the loops above.
medians() {
    awk -v n="$1" -v p="$2" -v t="$3" '
        $1 == n && $2 == p && $3 == t {
            for (i = 4; i <= NF; i++) { split($i, kv, "="); v[kv[1], ++c[kv[1]]] = kv[2] }
        }
        function median(k,   m, i, j, a, tmp) {
            m = c[k]; for (i = 1; i <= m; i++) a[i] = v[k, i]
            for (i = 1; i <= m; i++) for (j = i + 1; j <= m; j++)
                if (a[j] + 0 < a[i] + 0) { tmp = a[i]; a[i] = a[j]; a[j] = tmp }
            return m % 2 ? a[(m + 1) / 2] : (a[m / 2] + a[m / 2 + 1]) / 2
        }
        END {
            # Below 100k triangles the RSS increase is fixed overhead, not a per-triangle cost.
            rss = v["triangles", 1] < 100000 ? "-" : sprintf("%.1f", median("build_rss_bytes_per_mtri") / 1e6)
            printf "%s %s %s %d %.6f %.6f %.6f %.3f %.1f %s %.2f %.2f %.2f %.2f\n", v["triangles", 1],
                v["preset", 1], t, c["build_s"], median("build_s"), median("build_min_s"),
                median("obvhs_s"), median("mtris_per_s"),
                median("memory_bytes_per_mtri") / 1e6, rss,
                median("primary_mrays_per_s"), median("inside_mrays_per_s"),
                median("closest_mrays_per_s"), median("shadow_mrays_per_s")
        }' "$RAW"
}

{
    echo "BVH scale: generated terrain meshes, eyeadapt $("$BIN" --version | cut -d' ' -f2)" \
        "($BIN), $(nproc) cores; medians of $REPEATS processes, each the median of $RUNS builds."
    echo "before: $load_before"
    echo "after:  $load_after"
    echo
    printf '%-9s %-16s %3s %10s %10s %10s %8s %9s %12s %6s %7s %7s %7s\n' triangles preset thr \
        "build s" "min s" "obvhs s" Mtris/s MB/Mtris "RSS MB/Mtris" prim inside closest shadow
    [ -z "$JSON" ] || echo "[" >"$JSON"
    first=1
    for n in "${sizes[@]}"; do
        for p in "${presets[@]}"; do
            for t in "${threads[@]}"; do
                read -r tris preset thr reps build bmin obvhs rate mem rss prim inside closest shadow \
                    <<<"$(medians "$n" "$p" "$t")"
                label=$preset
                [ "$p" = default ] && label="default=$preset"
                printf '%-9s %-16s %3s %10s %10s %10s %8s %9s %12s %6s %7s %7s %7s\n' "$tris" \
                    "$label" "$thr" "$build" "$bmin" "$obvhs" "$rate" "$mem" "$rss" "$prim" \
                    "$inside" "$closest" "$shadow"
                if [ -n "$JSON" ]; then
                    [ $first = 1 ] || echo "," >>"$JSON"
                    first=0
                    printf '  {"triangles": %s, "preset": "%s", "renderer_default": %s, "threads": %s, "processes": %s, "build_s": %s, "build_min_s": %s, "obvhs_s": %s, "mtris_per_s": %s, "memory_mb_per_mtri": %s, "build_rss_mb_per_mtri": %s, "primary_mrays_per_s": %s, "inside_mrays_per_s": %s, "closest_mrays_per_s": %s, "shadow_mrays_per_s": %s}' \
                        "$tris" "$preset" "$([ "$p" = default ] && echo true || echo false)" \
                        "$thr" "$reps" "$build" "$bmin" "$obvhs" "$rate" "$mem" "${rss/#-/null}" "$prim" "$inside" \
                        "$closest" "$shadow" >>"$JSON"
                fi
            done
        done
    done
    [ -z "$JSON" ] || printf '\n]\n' >>"$JSON"
} | tee "$OUT"
[ -z "$JSON" ] || echo "wrote $JSON" >&2
if [ -n "$MD" ]; then
    append_markdown "$MD" "BVH scale" "scripts/bench/bvh-scale.sh --triangles $SIZES --presets $PRESETS --threads $THREADS --runs $RUNS --repeats $REPEATS" "$OUT"
fi
