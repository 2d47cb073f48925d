#!/usr/bin/env bash
# Fetches and converts paper case 4's statue into paper/scenes/meshes/guardian-lion.obj
# (committed; docs/paper.md, "Case 4", has its provenance and licence).
#
#   bash scripts/paper/statue-mesh.sh            # apt-get download libcgal-demo (Debian)
#   bash scripts/paper/statue-mesh.sh FILE.deb   # an already downloaded libcgal-demo package
#
# Needs dpkg-deb, tar, python3 with venv; VENV=DIR reuses a virtual environment (default: a
# temporary one, with fast-simplification 0.2.0 from PyPI). Then prints the red spot's design
# (spot_design.py).
set -euo pipefail
here=$(cd "$(dirname "$0")" && pwd)
root=$(cd "$here/../.." && pwd)
out="$root/paper/scenes/meshes/guardian-lion.obj"
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
deb=${1:-}
if [ -z "$deb" ]; then
  (cd "$work" && apt-get download libcgal-demo=5.5.1-2)
  deb=$(ls "$work"/libcgal-demo_*.deb)
fi
dpkg-deb -x "$deb" "$work/pkg"
member=data/meshes/ChineseDragon-10kv.off
tar -xzf "$work/pkg/usr/share/doc/libcgal-dev/data.tar.gz" -C "$work" "$member"
echo "f633bdfaac7a0f99e0fab668c34862f0c26f341cfdb4665bab282d79b788db02  $work/$member" | sha256sum -c -
venv=${VENV:-$work/venv}
if [ ! -x "$venv/bin/python" ]; then
  python3 -m venv "$venv"
  "$venv/bin/pip" install -q fast-simplification==0.2.0
fi
mkdir -p "$(dirname "$out")"
"$venv/bin/python" "$here/statue_mesh.py" "$work/$member" "$out"
ls -l "$out"
"$venv/bin/python" "$here/spot_design.py" "$out"
