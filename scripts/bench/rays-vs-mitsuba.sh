#!/usr/bin/env bash
# Ray throughput against Mitsuba 3 (issue 23, goal 2): the closest-hit and shadow queries alone,
# no shading, on the terrain mesh and ray sets of `eyeadapt bench --bvh-triangles N`, with
# Mitsuba's `llvm_ad_rgb` tracing the same mesh and ray sets (rays_mitsuba.py says how).
# eyeadapt's figures are its renderer's own queries (the AVX2 node test where the CPU has it,
# one traversal state reused per worker); both use every core.
#
#   scripts/bench/rays-vs-mitsuba.sh [--triangles 1000,61600,1000000] [--repeats 3]
#                                    [--eyeadapt BIN] [--markdown FILE]
#
# Each size runs eyeadapt then Mitsuba, --repeats times round-robin; the table gives medians in
# M rays/s and their ratio (> 1: eyeadapt faster), with each renderer's share of rays that hit
# (shadow: that are unoccluded) as a check that both trace the same thing. Uses the venv of
# vs-mitsuba.sh ($VENV) and Debian's libllvm19 for llvm_ad_rgb.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
SIZES=1000,61600,1000000 REPEATS=3 BIN="${EYEADAPT:-}" MD=""
while [ $# -gt 0 ]; do
    case "$1" in
        --triangles) SIZES="$2"; shift 2 ;;
        --repeats) REPEATS="$2"; shift 2 ;;
        --eyeadapt) BIN="$2"; shift 2 ;;
        --markdown) MD="$2"; shift 2 ;;
        *) echo "rays-vs-mitsuba.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
bench_venv
eyeadapt_binary "$BIN"
IFS=, read -ra sizes <<<"$SIZES"
RAW="$(mktemp)" OUT="$(mktemp)"
trap 'rm -f "$RAW" "$OUT"' EXIT

for ((rep = 1; rep <= REPEATS; rep++)); do
    for n in "${sizes[@]}"; do
        echo "round $rep/$REPEATS, $n triangles" >&2
        echo "$n eyeadapt $("$BIN" bench --bvh-triangles "$n" --runs 1 | grep '^bvh-bench: ')" >>"$RAW"
        echo "$n mitsuba $("$VENV/bin/python" "$HERE/rays_mitsuba.py" "$n" | grep '^mitsuba-rays: ')" >>"$RAW"
    done
done

"$VENV/bin/python" - "$RAW" >"$OUT" <<'PY'
import statistics, sys
rows = {}
for line in open(sys.argv[1]):
    n, who, _, *kv = line.split()
    kv = dict(x.split("=", 1) for x in kv)
    rows.setdefault((int(n), who), []).append(kv)
mi_version = next(r[0]["version"] for (n, w), r in rows.items() if w == "mitsuba")
print(f"eyeadapt bench --bvh-triangles against Mitsuba {mi_version} llvm_ad_rgb, 2^20 rays a set, "
      f"medians of {len(next(iter(rows.values())))} rounds, both on every core")
print()
print("| triangles | rays | eyeadapt M rays/s | Mitsuba M rays/s | eyeadapt / Mitsuba | hit % eyeadapt / Mitsuba |")
print("|---|---|---|---|---|---|")
for n in sorted({n for n, _ in rows}):
    ea, mi = rows[(n, "eyeadapt")], rows[(n, "mitsuba")]
    for s in ("primary", "inside", "shadow"):
        a = statistics.median(float(r[f"{s}_mrays_per_s"]) for r in ea)
        b = statistics.median(float(r[f"{s}_mrays_per_s"]) for r in mi)
        pct = float(mi[0][f"{s}_percent"])
        label = {"primary": "camera (coherent)", "inside": "inside (incoherent)",
                 "shadow": "shadow, 0.5 long"}[s]
        print(f"| {n} | {label} | {a:.2f} | {b:.2f} | {a / b:.2f} | "
              f"{float(ea[0].get(f'{s}_percent', 'nan')):.1f} / {pct:.1f} |")
PY
cat "$OUT"
if [ -n "$MD" ]; then
    append_markdown "$MD" "Ray throughput against Mitsuba" "scripts/bench/rays-vs-mitsuba.sh --triangles $SIZES --repeats $REPEATS" "$OUT"
fi
