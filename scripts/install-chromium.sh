#!/usr/bin/env bash
# Makes Debian's `chromium` available for tests/browser/report.sh (the report page in a real,
# headless browser). Already on PATH: prints its path. As root: installs it with apt-get (the
# same way scripts/test.sh installs ffmpeg), with a font so screenshots have readable text.
# Otherwise it says why it cannot and exits 1; the caller decides whether that is a skip.
set -euo pipefail

if command -v chromium >/dev/null; then
  command -v chromium
  exit 0
fi
if [[ $(id -u) -ne 0 ]]; then
  echo "install-chromium: chromium is not on PATH and installing it needs root (apt-get install chromium)" >&2
  exit 1
fi
if ! command -v apt-get >/dev/null; then
  echo "install-chromium: chromium is not on PATH and there is no apt-get to install it" >&2
  exit 1
fi
echo "install-chromium: apt-get install chromium fonts-dejavu-core" >&2
apt-get update -qq >/dev/null
DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends \
  chromium fonts-dejavu-core >/dev/null
command -v chromium
