#!/usr/bin/env bash
# The eye sensor's cost and noise (issue 10, goal 3).
#
#   scripts/bench/eye-sensor.sh [--eyeadapt BIN] [--frames SPEC | --static-only] [--eye-samples N]
#                               [--rooms "NAME ..."] [--markdown FILE]
#
# 1. Cost: renders the demo job (default all 121 frames; --frames 0-120:10 for a quick look)
#    and reads the sensor's share of each frame's time from the log ("eye sensor … % of the
#    frame"), with the paths it used and its standard error of u′v′ from adaptation.csv.
# 2. Noise floor: a static camera in each of the demo's three rooms and in its two doorways
#    (looking from one room into the next), 49 frames each, eye estimator only, once with
#    common random numbers off (frame-to-frame σ(u′v′) is then the Monte-Carlo noise) and once
#    on (the default: the reading repeats exactly).
# --eye-samples N replaces the default (adaptive) budget with exactly N paths per frame.
# --rooms "doorway1 doorway2 orange" measures only those static cameras (of white, orange, blue,
# doorway1, doorway2), for quicker experiments.
set -euo pipefail
HERE="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
REPO="$(cd "$HERE/../.." && pwd)"
BIN="" FRAMES="" MD="" DEMO=1 EYE_N="" ROOMS="white orange blue doorway1 doorway2"
while [ $# -gt 0 ]; do
    case "$1" in
        --eyeadapt) BIN="$2"; shift 2 ;;
        --frames) FRAMES="$2"; shift 2 ;;
        --markdown) MD="$2"; shift 2 ;;
        --static-only) DEMO=0; shift ;;
        --eye-samples) EYE_N="$2"; shift 2 ;;
        --rooms) ROOMS="$2"; shift 2 ;;
        *) echo "eye-sensor.sh: unknown argument $1" >&2; exit 2 ;;
    esac
done
for name in $ROOMS; do
    case "$name" in
        white | orange | blue | doorway1 | doorway2) ;;
        *) echo "eye-sensor.sh: --rooms: unknown room $name (white, orange, blue, doorway1, doorway2)" >&2; exit 2 ;;
    esac
done
[ -n "${ROOMS// /}" ] || { echo "eye-sensor.sh: --rooms: no room given" >&2; exit 2; }
# shellcheck source=scripts/bench/common.sh
. "$HERE/common.sh"
eyeadapt_binary "$BIN"
WORK="$(mktemp -d)"
trap 'rm -rf "$WORK"' EXIT
OUT="$WORK/report.txt"

start=0 end=0
if [ "$DEMO" = 1 ]; then
    args=(sequence --out "$WORK/demo" --log-format plain)
    [ -n "$FRAMES" ] && args+=(--frames "$FRAMES")
    [ -n "$EYE_N" ] && args+=(--eye-samples "$EYE_N")
    start=$(date +%s.%N)
    "$BIN" "${args[@]}" >"$WORK/demo.log" 2>&1
    end=$(date +%s.%N)
fi

for room in "white 0.6,1.6,-0.6 -0.6,0.9,-4.0" "orange 0.2,1.6,-7.2 0.0,1.5,-12.0" \
    "blue -0.1,1.6,-11.0 0.3,1.45,-14.5" "doorway1 0.0,1.6,-4.4 0.0,1.5,-9.0" \
    "doorway2 0.0,1.6,-9.6 0.0,1.5,-14.0"; do
    read -r name pos look <<<"$room"
    case " $ROOMS " in *" $name "*) ;; *) continue ;; esac
    for crn in false true; do
        cat >"$WORK/static-$name-$crn.toml" <<TOML
name = "static-$name"
scene = "builtin:three-rooms"
seed = 0
[render]
width = 320
height = 180
spp = 1
[estimators]
list = ["eye"]
[estimators.eye]
common_random_numbers = $crn
${EYE_N:+samples = $EYE_N
target_std_err_uv = 0}
[camera_path]
fps = 24
keyframes = [ { time = 0.0, position = [$pos], look_at = [$look] },
              { time = 2.0, position = [$pos], look_at = [$look] } ]
TOML
        "$BIN" sequence "$WORK/static-$name-$crn.toml" --out "$WORK/static-$name-$crn" \
            --log-format plain >/dev/null 2>&1
    done
done

python3 - "$WORK" "$FRAMES" "$start" "$end" "$ROOMS" <<'PY' | tee "$OUT"
import csv, math, os, re, statistics, sys
work, frames = sys.argv[1], sys.argv[2] or "all 121"
wall = float(sys.argv[4]) - float(sys.argv[3])
demo = os.path.exists(os.path.join(work, "demo.log"))
cost = [] if not demo else [float(m.group(1)) for m in re.finditer(r"eye sensor [0-9.]+ s = ([0-9.]+) % of the frame",
                                                open(os.path.join(work, "demo.log")).read())]
rows = [] if not demo else [
    r for r in csv.DictReader(open(os.path.join(work, "demo", "adaptation.csv")))
    if r["estimator"] == "eye"]
se = [math.hypot(float(r["std_err_u"]), float(r["std_err_v"])) for r in rows]
n = [int(r["n_samples"]) for r in rows]
q = lambda xs, p: sorted(xs)[min(len(xs) - 1, int(p * len(xs)))]
if demo:
  print(f"Demo job, frames {frames}: {len(rows)} frames in {wall:.1f} s wall "
      f"({3600 * len(rows) / wall:.0f} frames/hour, rendering, estimators and report)")
  print(f"  eye sensor share of frame time: mean {statistics.mean(cost):.2f} %, median "
      f"{statistics.median(cost):.2f} %, 90th percentile {q(cost, 0.9):.2f} %, max {max(cost):.2f} %")
  print(f"  paths per frame: mean {statistics.mean(n):.0f}, min {min(n)}, max {max(n)}; "
      f"frames at the 16384 cap: {sum(x >= 16384 for x in n)}")
  print(f"  standard error of u'v' (length of (se_u, se_v)): median {statistics.median(se):.2e}, "
      f"90th percentile {q(se, 0.9):.2e}, max {max(se):.2e}; frames <= 2e-4: "
      f"{sum(x <= 2e-4 for x in se)} of {len(se)}")
rooms = [r for r in ("white", "orange", "blue", "doorway1", "doorway2") if r in sys.argv[5].split()]
n_static = sum(r["estimator"] == "eye" for r in csv.DictReader(open(os.path.join(work, f"static-{rooms[0]}-false", "adaptation.csv"))))
print(f"Static camera, {n_static} frames per room (eye only):")
print(f"  {'room':<9} {'CRN':<5} {'paths':>7} {'reported se':>12} {'frame-to-frame sigma(u′v′)':>27}")
for room in rooms:
    for crn in ("false", "true"):
        rs = [r for r in csv.DictReader(open(os.path.join(work, f"static-{room}-{crn}", "adaptation.csv")))
              if r["estimator"] == "eye"]
        u = [float(r["u_prime"]) for r in rs]
        v = [float(r["v_prime"]) for r in rs]
        sigma = math.sqrt(statistics.variance(u) + statistics.variance(v))
        rep = statistics.mean(math.hypot(float(r["std_err_u"]), float(r["std_err_v"])) for r in rs)
        paths = statistics.mean(int(r["n_samples"]) for r in rs)
        print(f"  {room:<9} {crn:<5} {paths:>7.0f} {rep:>12.2e} {sigma:>27.2e}")
PY
if [ -n "$MD" ]; then
    append_markdown "$MD" "Eye sensor cost and noise" \
        "scripts/bench/eye-sensor.sh${FRAMES:+ --frames $FRAMES}$([ "$DEMO" = 1 ] || echo ' --static-only')${EYE_N:+ --eye-samples $EYE_N}$([ "$ROOMS" = "white orange blue doorway1 doorway2" ] || echo " --rooms \"$ROOMS\"")" "$OUT"
fi
