#!/usr/bin/env bash
# Renders frames 0-24 of the built-in three-rooms scene twice (as it is, and with its bench
# marked by a diffuse colour) and reports the bench's brightest pixel against the image's 99th
# percentile per frame (issue 22's audit; docs/paper.md, "The audit's numbers").
#
#   VENV=/work/venv/mitsuba bash scripts/paper/bench-highlight.sh [EYEADAPT] [WIDTH HEIGHT SPP]
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
bin=${1:-$root/target/release/eyeadapt}
w=${2:-160} h=${3:-90} spp=${4:-4}
venv=${VENV:-/work/venv/mitsuba}
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
cp "$root/scenes/three-rooms/scene.toml" "$work/normal.toml"
python3 - "$work" <<'EOF'
import sys
d = sys.argv[1]
s = open(f"{d}/normal.toml").read()
i = s.index('name = "bench"')
j = s.index("[[materials]]", i)
mark = 'name = "bench"\ntype = "diffuse"\nreflectance = [0.123, 0.456, 0.789]\n\n'
open(f"{d}/mask.toml", "w").write(s[:i] + mark + s[j:])
EOF
for n in normal mask; do
  cat > "$work/$n.job.toml" <<EOF
name = "$n"
scene = "$n.toml"
seed = 0
[render]
width = $w
height = $h
spp = $spp
max_depth = 8
rr_depth = 5
[estimators]
list = ["wcam"]
EOF
  "$bin" sequence "$work/$n.job.toml" --frames 0-24 --out "$work/out-$n" --log-format plain >/dev/null
done
"$venv/bin/python" "$here/bench-highlight.py" "$work/out-normal" "$work/out-mask"
