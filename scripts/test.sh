#!/usr/bin/env bash
# The project's test command (the README's second command; .ci/run calls it).
#
#   1. cargo test, every crate, optimised (rendering tests use tiny images);
#   2. the per-frame CSV loads in pandas with the documented columns and types
#      (a throw-away venv under target/, pandas from PyPI);
#   3. the coherence report in headless Chromium (Debian's package, installed by
#      scripts/install-chromium.sh; required as root, skipped without chromium otherwise
#      unless EYEADAPT_REQUIRE_CHROMIUM=1); screenshots go to target/browser/;
#   4. the same files from one binary on Debian 12's and 13's glibc (scripts/glibc-determinism.sh;
#      their libc6 packages from Debian's archive; required as root, skipped without network
#      otherwise unless EYEADAPT_REQUIRE_GLIBC=1);
#   5. the Slurm end-to-end test on a real single-node Slurm (Debian packages,
#      installed by scripts/slurm/local-cluster.sh; needs root, skipped otherwise
#      unless EYEADAPT_REQUIRE_SLURM=1).
# Prints 'N passed, M failed' for the stages and exits non-zero if any failed.
set -euo pipefail
cd "$(dirname "${BASH_SOURCE[0]}")/.."

passed=0 failed=0
stage() {
  local name=$1
  shift
  echo "==> $name"
  if "$@"; then
    passed=$((passed + 1))
    echo "ok   - $name"
  else
    failed=$((failed + 1))
    echo "FAIL - $name"
  fi
}

# The report's video test needs ffmpeg (Debian's package). As root (CI) it is installed and
# required; elsewhere the test says it skipped the video unless ffmpeg is on PATH.
ensure_ffmpeg() {
  command -v ffmpeg >/dev/null && return 0
  [[ $(id -u) -eq 0 ]] || return 0
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends ffmpeg) >/dev/null
}

# tests/recipes.rs runs the README's Flamenco job compiler in node (Debian's nodejs); as root
# it is installed and required, elsewhere that recipe is skipped without node.
ensure_node() {
  command -v node >/dev/null && return 0
  [[ $(id -u) -eq 0 ]] || return 0
  (apt-get update -qq && DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends nodejs) >/dev/null
}

cargo_tests() {
  ensure_ffmpeg
  ensure_node
  if command -v ffmpeg >/dev/null; then export EYEADAPT_REQUIRE_FFMPEG=1; fi
  if command -v node >/dev/null; then export EYEADAPT_REQUIRE_NODE=1; fi
  cargo build --release --bins
  cargo test --workspace --release
}

pandas_csv() {
  local venv=target/venv-test
  if [[ ! -x $venv/bin/python ]] || ! "$venv/bin/python" -c 'import pandas' 2>/dev/null; then
    python3 -m venv "$venv"
    "$venv/bin/pip" install --quiet --disable-pip-version-check pandas
  fi
  local out
  out=$(mktemp -d)
  target/release/eyeadapt sequence --frames 0-5 --width 32 --height 18 --spp 2 \
    --eye-samples 1024 --out "$out/seq" --no-report --no-progress-bar >/dev/null
  "$venv/bin/python" scripts/check_csv_pandas.py "$out/seq/adaptation.csv"
  rm -rf "$out"
}

# As root (CI) chromium is installed and the test required; elsewhere it runs when chromium is
# on PATH and says it skipped otherwise.
report_in_browser() {
  if ! bash scripts/install-chromium.sh >/dev/null; then
    if [[ $(id -u) -eq 0 || ${EYEADAPT_REQUIRE_CHROMIUM:-0} == 1 ]]; then
      return 1
    fi
    echo "skipped: no chromium on PATH (set EYEADAPT_REQUIRE_CHROMIUM=1 to fail instead)"
    return 0
  fi
  EYEADAPT=$PWD/target/release/eyeadapt bash tests/browser/report.sh
}

glibc_versions() {
  local rc=0
  bash scripts/glibc-determinism.sh target/release/eyeadapt || rc=$?
  if [[ $rc == 3 && $(id -u) -ne 0 && ${EYEADAPT_REQUIRE_GLIBC:-0} != 1 ]]; then
    echo "skipped: Debian's archive is out of reach (set EYEADAPT_REQUIRE_GLIBC=1 to fail instead)"
    return 0
  fi
  return $rc
}

slurm_e2e() {
  if [[ $(id -u) -ne 0 && ${EYEADAPT_REQUIRE_SLURM:-0} != 1 ]]; then
    echo "skipped: the Slurm end-to-end test needs root (set EYEADAPT_REQUIRE_SLURM=1 to fail instead)"
    return 0
  fi
  EYEADAPT=$PWD/target/release/eyeadapt bash tests/slurm/e2e.sh
}

stage "cargo tests" cargo_tests
stage "adaptation.csv in pandas" pandas_csv
stage "report in headless Chromium" report_in_browser
stage "same bits on Debian 12's and 13's glibc" glibc_versions
stage "Slurm end-to-end" slurm_e2e
echo "test.sh: $passed passed, $failed failed"
((failed == 0))
