#!/usr/bin/env bash
# The coherence report in a real browser: renders a tiny sequence with its report, opens
# report.html in headless Chromium and requires that every image and plot has loaded, that the
# sortable table sorts, and that the page raised no error (script errors, failed resources,
# console errors and warnings). Stores screenshots of the first screen and of the whole page
# under target/browser/ (the CI artefacts).
#
# Usage: tests/browser/report.sh [--keep]
# Needs chromium on PATH (scripts/install-chromium.sh) and the binary $EYEADAPT (default:
# target/release/eyeadapt). Prints 'N passed, M failed'; exits 1 on any failure.
set -euo pipefail

REPO_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")/../.." && pwd)
readonly REPO_DIR
readonly EYEADAPT=${EYEADAPT:-$REPO_DIR/target/release/eyeadapt}
readonly ARTEFACTS=$REPO_DIR/target/browser
KEEP=0
[[ ${1:-} == --keep ]] && KEEP=1

command -v chromium >/dev/null || {
  echo "report.sh: chromium is not on PATH (run scripts/install-chromium.sh)" >&2
  exit 1
}
[[ -x $EYEADAPT ]] || {
  echo "report.sh: no binary at $EYEADAPT (cargo build --release)" >&2
  exit 1
}

scratch=$(mktemp -d "${TMPDIR:-/tmp}/eyeadapt-browser.XXXXXX")
passed=0 failed=0
cleanup() {
  if ((KEEP || failed)); then
    echo "report.sh: scratch directory kept: $scratch"
  else
    rm -rf "$scratch"
  fi
}
trap cleanup EXIT
check() {
  local what=$1
  shift
  if "$@"; then
    passed=$((passed + 1))
    echo "ok   - $what"
  else
    failed=$((failed + 1))
    echo "FAIL - $what"
  fi
}

# Headless, offline and quiet: no first-run UI, no background fetches, a fresh profile.
browser() {
  local profile
  profile=$(mktemp -d "$scratch/profile.XXXXXX")
  timeout 180 chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run \
    --disable-background-networking --disable-component-update --disable-sync \
    --user-data-dir="$profile" --hide-scrollbars "$@" 2>>"$scratch/chromium.log"
}

# Sixteen frames of the demo walkthrough with its filters: every plot of the report exists.
"$EYEADAPT" sequence --frames 0-15 --width 48 --height 27 --spp 1 --eye-samples 512 \
  --out "$scratch/seq" --no-progress-bar >"$scratch/sequence.log" 2>&1
page=$scratch/seq/report.html
check "the sequence wrote report.html" test -s "$page"

# A copy of the page with the probe as the first thing in <head>, so it sees every error.
probed=$scratch/seq/report-probed.html
awk -v probe="$REPO_DIR/tests/browser/probe.js" '
  BEGIN { while ((getline line < probe) > 0) js = js line "\n" }
  !done && (i = index($0, "<head>")) {
    print substr($0, 1, i + 5); printf "<script>\n%s</script>\n", js; print substr($0, i + 6)
    done = 1; next
  }
  { print }' "$page" >"$probed"
browser --virtual-time-budget=10000 --dump-dom "file://$probed" >"$scratch/dom.html" || true
# The probe's lines start the line; its own source text in the dump does not.
result=$(sed -n '/<pre id="probe-result">/,/<\/pre>/p' "$scratch/dom.html" | grep -o '^PROBE[^<]*' || true)
echo "${result:-no probe result (see $scratch/chromium.log)}"
summary=$(grep '^PROBE ' <<<"$result" || true)
field() { sed -n "s/.* $1=\([0-9]*\).*/\1/p" <<<"$summary"; }
check "the page loaded and the probe ran" test -n "$summary"
check "no script, resource or console error" test "$(field errors)" = 0
check "every plot is drawn ($(field svgs) SVGs, $(field empty) empty)" \
  test "$(field svgs)" -gt 0 -a "$(field empty)" = 0
check "every image loaded ($(field images) images, $(field broken) broken)" test "$(field broken)" = 0
check "the metrics table sorts when its heading is clicked" \
  test "$(field sortable)" -gt 0 -a "$(field sorted)" = "$(field sortable)"

mkdir -p "$ARTEFACTS"
browser --window-size=1280,900 --screenshot="$ARTEFACTS/report-first-screen.png" "file://$page" >/dev/null
browser --window-size=1280,7000 --screenshot="$ARTEFACTS/report-full.png" "file://$page" >/dev/null
check "screenshots in target/browser/" test -s "$ARTEFACTS/report-first-screen.png" -a -s "$ARTEFACTS/report-full.png"

echo "report.sh: $passed passed, $failed failed"
((failed == 0))
