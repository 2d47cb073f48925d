#!/usr/bin/env bash
# Installs Blender as a Python module (PyPI's `bpy`) into a venv and prints the venv's python.
#
#   bash scripts/blender/install.sh [VENV]      default VENV: target/venv-blender
#
# Exits 3 (and says why on stderr) when bpy cannot be installed here: the tests that need
# Blender skip with that message unless EYEADAPT_REQUIRE_BLENDER=1.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/../.."
venv=${1:-target/venv-blender}
if [[ -x $venv/bin/python ]] && "$venv/bin/python" -c 'import bpy' 2>/dev/null; then
  echo "$PWD/$venv/bin/python"
  exit 0
fi
# bpy 5.x is built for CPython 3.11 only.
if ! python3 -c 'import sys; sys.exit(sys.version_info[:2] != (3, 11))'; then
  echo "install.sh: bpy needs CPython 3.11; this python3 is $(python3 -V 2>&1)" >&2
  exit 3
fi
python3 -m venv "$venv" >&2
if ! "$venv/bin/pip" install --quiet --disable-pip-version-check 'bpy>=4.2,<6' >&2; then
  echo "install.sh: pip could not install bpy" >&2
  exit 3
fi
echo "$PWD/$venv/bin/python"
