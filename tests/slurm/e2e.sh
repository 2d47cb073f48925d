#!/usr/bin/env bash
# End-to-end test of the Slurm integration against a real single-node Slurm.
#
# Brings up scripts/slurm/local-cluster.sh, renders the demo job once locally
# and once through scripts/slurm/submit.sh in 4 chunks, and requires the merged
# farm output to be byte-identical to the local one: plainly, then with an
# injected transient failure (exit 75 -> requeue), and checks that a permanent
# failure makes 'submit.sh --wait' fail. The cluster is always taken down.
set -euo pipefail

readonly PROG=${0##*/}
SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
readonly SCRIPT_DIR
readonly REPO_DIR=${SCRIPT_DIR%/tests/slurm}
readonly CLUSTER=$REPO_DIR/scripts/slurm/local-cluster.sh
readonly SUBMIT=$REPO_DIR/scripts/slurm/submit.sh

usage() {
  cat <<EOF
Usage: $PROG [--keep]

End-to-end test of scripts/slurm/ on a real single-node Slurm (Debian 12,
run as root; installs slurm-wlm/munge with apt-get if missing). It builds
nothing: the binary comes from \$EYEADAPT (default:
$REPO_DIR/target/release/eyeadapt).

  --keep      keep the scratch directory even when every check passed
  -h, --help  this text

Environment: EYEADAPT (binary), E2E_PORT_BASE (slurmctld port, default 6817;
slurmd uses the next one), TMPDIR (where the scratch directory goes).
Prints 'N passed, M failed' and the wall time; exits 1 on any failure.
EOF
}

KEEP=0
while (($#)); do
  case $1 in
    -h | --help) usage; exit 0 ;;
    --keep) KEEP=1; shift ;;
    *) echo "$PROG: unknown argument '$1'" >&2; echo "Try '$PROG --help'." >&2; exit 2 ;;
  esac
done

# --- reporting ----------------------------------------------------------------

PASSED=0 FAILED=0 T="" CLUSTER_ROOT="" CHILD=""
readonly START=$SECONDS

say() { printf '%s: %s\n' "$PROG" "$*" >&2; }
pass() { PASSED=$((PASSED + 1)); printf 'ok   - %s\n' "$1"; }
fail() { FAILED=$((FAILED + 1)); printf 'FAIL - %s\n' "$1"; shift; local l; for l in "$@"; do printf '       %s\n' "$l"; done; }
# fatal MSG: a failure after which the remaining steps make no sense.
fatal() { fail "$@"; exit 1; }

finish() {
  local rc=$?
  trap - EXIT
  if [[ -n $CHILD ]] && kill -0 "$CHILD" 2>/dev/null; then
    kill -TERM "$CHILD" 2>/dev/null || true
  fi
  if ((rc != 0 && FAILED == 0)); then
    FAILED=1
    echo "FAIL - $PROG stopped early (exit $rc)"
  fi
  if [[ -n $CLUSTER_ROOT ]]; then
    "$CLUSTER" down --root "$CLUSTER_ROOT" || say "warning: local-cluster.sh down failed"
  fi
  if [[ -n $T ]]; then
    if ((FAILED == 0 && KEEP == 0)); then
      rm -rf "$T"
    else
      say "scratch directory kept: $T (cluster logs in $CLUSTER_ROOT/log, job logs in $T/*/logs)"
    fi
  fi
  echo "$PASSED passed, $FAILED failed"
  echo "wall time: $((SECONDS - START)) s"
  ((FAILED == 0)) || exit 1
  exit 0
}
trap finish EXIT
trap 'exit 130' INT TERM

# --- helpers --------------------------------------------------------------------

# child OUTFILE ERRFILE CMD...: runs CMD in the background with stdout to
# OUTFILE and stderr to ERRFILE (/dev/stderr: unchanged) and waits for it, so that a signal
# reaches our trap at once instead of after a long 'submit.sh --wait'. The
# redirection must not be on the function call: the EXIT trap would inherit it.
child() {
  local out=$1 err=$2 rc=0
  shift 2
  if [[ $err == /dev/stderr ]]; then "$@" >"$out" & else "$@" >"$out" 2>"$err" & fi
  CHILD=$!
  wait "$CHILD" || rc=$?
  CHILD=""
  return "$rc"
}

# same_output REF DIR: adaptation.csv and every frame file byte-identical, and
# the same set of frame files on both sides. Prints the differences.
same_output() {
  local ref=$1 dir=$2 f bad=0 listing_ref listing_dir
  if ! cmp "$ref/adaptation.csv" "$dir/adaptation.csv"; then bad=1; fi
  listing_ref=$(cd "$ref" && find frames -type f | LC_ALL=C sort)
  listing_dir=$(cd "$dir" 2>/dev/null && find frames -type f | LC_ALL=C sort) || listing_dir=""
  if [[ $listing_ref != "$listing_dir" ]]; then
    echo "frame files differ:"
    diff <(echo "$listing_ref") <(echo "$listing_dir") | head -20 || true
    bad=1
  fi
  while IFS= read -r f; do
    [[ -n $f && -f $dir/$f ]] || continue
    cmp "$ref/$f" "$dir/$f" || bad=1
  done <<<"$listing_ref"
  return "$bad"
}

# job_field JOB NAME: NAME=... of 'scontrol show job -o JOB' (first record).
job_field() {
  local re="(^| )$2=([^ ]*)" line
  line=$(scontrol show job -o "$1" 2>/dev/null | head -1) || return 1
  [[ $line =~ $re ]] && printf '%s\n' "${BASH_REMATCH[2]}"
}

# --- preconditions ----------------------------------------------------------------

EYEADAPT=${EYEADAPT:-$REPO_DIR/target/release/eyeadapt}
[[ $EYEADAPT == /* ]] || EYEADAPT=$PWD/$EYEADAPT
if [[ ! -f $EYEADAPT || ! -x $EYEADAPT ]]; then
  fatal "eyeadapt binary present" "no executable at $EYEADAPT" \
    "build it first (cargo build --release) or set EYEADAPT=/path/to/eyeadapt"
fi
((EUID == 0)) || fatal "running as root" "local-cluster.sh needs root (apt-get, daemons)"

T=$(mktemp -d "${TMPDIR:-/tmp}/eyeadapt-e2e.XXXXXX")
chmod 755 "$T" # mktemp makes it 0700; slurmctld runs as user 'slurm' and must reach $T/cluster
CLUSTER_ROOT=$T/cluster
say "binary $EYEADAPT, scratch $T"

RENDER=(--frames 0-11 --width 48 --height 27 --spp 2)

# --- cluster ----------------------------------------------------------------------

t0=$SECONDS
if up_out=$("$CLUSTER" up --root "$CLUSTER_ROOT" --port-base "${E2E_PORT_BASE:-6817}"); then
  export SLURM_CONF=$CLUSTER_ROOT/etc/slurm.conf
  [[ $up_out == *"SLURM_CONF=$SLURM_CONF"* ]] || fatal "local-cluster.sh up prints SLURM_CONF" "got: $up_out"
  pass "local cluster up ($((SECONDS - t0)) s)"
else
  fatal "local cluster up" "see $CLUSTER_ROOT/log/"
fi

# --- (a) local reference ------------------------------------------------------------

t0=$SECONDS
if child "$T/local.log" "$T/local.err" "$EYEADAPT" sequence "${RENDER[@]}" --out "$T/local" \
  && [[ -f $T/local/adaptation.csv ]]; then
  pass "local reference render, 12 frames ($((SECONDS - t0)) s)"
else
  tail -n 20 "$T/local.err" >&2 || true
  fatal "local reference render" "eyeadapt sequence failed; output in $T/local.log and $T/local.err"
fi
missing=()
for ((f = 0; f <= 11; f++)); do
  printf -v name 'frame_%06d.exr' "$f"
  [[ -f $T/local/frames/raw/$name ]] || missing+=("$name")
done
if ((${#missing[@]} == 0)); then pass "local reference has frames/raw/frame_000000..000011.exr"
else fail "local reference has all raw frames" "missing: ${missing[*]}"; fi

# --- (b) farm render in 4 chunks --------------------------------------------------------

t0=$SECONDS
if child "$T/farm.ids" /dev/stderr "$SUBMIT" --demo "${RENDER[@]}" --chunk-size 3 --out "$T/farm" --exe "$EYEADAPT" \
  --wait --timeout 600; then
  pass "submit.sh --wait: 4 chunks + merge COMPLETED ($((SECONDS - t0)) s)"
  if diffs=$(same_output "$T/local" "$T/farm/merged" 2>&1); then
    pass "farm merge byte-identical to the local render (adaptation.csv + $(find "$T/local/frames" -type f | wc -l) frame files)"
  else
    fail "farm merge byte-identical to the local render" "$diffs"
  fi
  if [[ -f $T/farm/merged/report.html ]]; then pass "report.html written"; else fail "report.html written" "no $T/farm/merged/report.html"; fi
else
  fail "submit.sh --wait (plain run)" "see $T/farm/logs/ and $CLUSTER_ROOT/log/"
fi

# --- (c) transient failure: task 2 exits 75 once, is requeued ------------------------------

WRAP75=$T/eyeadapt-fail-task2-once
cat >"$WRAP75" <<EOF
#!/bin/bash
# e2e: the first 'sequence' run of array task 2 fails with exit 75, then the real binary runs.
if [[ \${1:-} == sequence && \${SLURM_ARRAY_TASK_ID:-} == 2 && ! -e $(printf '%q' "$T/task2.failed-once") ]]; then
  : >$(printf '%q' "$T/task2.failed-once")
  echo "e2e: injected transient failure, exit 75" >&2
  exit 75
fi
exec $(printf '%q' "$EYEADAPT") "\$@"
EOF
chmod +x "$WRAP75"

t0=$SECONDS
if child "$T/retry.ids" /dev/stderr "$SUBMIT" --demo "${RENDER[@]}" --chunk-size 3 --out "$T/retry" --exe "$WRAP75" \
  --wait --timeout 600; then
  pass "submit.sh --wait with one exit-75 task: COMPLETED ($((SECONDS - t0)) s)"
else
  fail "submit.sh --wait with one exit-75 task" "see $T/retry/logs/ and $CLUSTER_ROOT/log/"
fi
if [[ -e $T/task2.failed-once ]]; then pass "failure was injected into task 2"
else fail "failure was injected into task 2" "marker $T/task2.failed-once missing"; fi
A=$(sed -n 's/^EYEADAPT_ARRAY_JOB=//p' "$T/retry.ids")
if [[ -n $A ]]; then
  restarts=$(job_field "${A}_2" Restarts || echo "?")
  state=$(job_field "${A}_2" JobState || echo "?")
  if [[ $restarts == 1 && $state == COMPLETED ]]; then pass "task ${A}_2 requeued once (scontrol: Restarts=1, JobState=COMPLETED)"
  else fail "task ${A}_2 requeued once" "scontrol: Restarts=$restarts JobState=$state"; fi
  # jobcomp/filetxt writes one line per attempt; the first attempt shows ExitCode=75:0.
  attempts=$(grep -c " ArrayJobId=$A ArrayTaskId=2 " "$CLUSTER_ROOT/log/jobcomp.txt" || true)
  first_exit=$(grep " ArrayJobId=$A ArrayTaskId=2 " "$CLUSTER_ROOT/log/jobcomp.txt" | head -1 | grep -o ' ExitCode=[0-9:]*' | tr -d ' ' || true)
  if [[ $attempts == 2 && $first_exit == ExitCode=75:0 ]]; then pass "jobcomp.txt: 2 attempts of task 2, the first with ExitCode=75:0"
  else fail "jobcomp.txt: 2 attempts of task 2" "attempts=$attempts first=$first_exit"; fi
else
  fail "array job id of the retry run" "no EYEADAPT_ARRAY_JOB in $T/retry.ids"
fi
if diffs=$(same_output "$T/local" "$T/retry/merged" 2>&1); then
  pass "merge after the requeue byte-identical to the local render"
else
  fail "merge after the requeue byte-identical to the local render" "$diffs"
fi

# --- (d) permanent failure: task 1 exits 3 -> submit.sh --wait must fail --------------------

WRAPFAIL=$T/eyeadapt-fail-task1
cat >"$WRAPFAIL" <<EOF
#!/bin/bash
# e2e: array task 1 always fails permanently.
if [[ \${1:-} == sequence && \${SLURM_ARRAY_TASK_ID:-} == 1 ]]; then
  echo "e2e: injected permanent failure, exit 3" >&2
  exit 3
fi
exec $(printf '%q' "$EYEADAPT") "\$@"
EOF
chmod +x "$WRAPFAIL"

t0=$SECONDS
rc=0
child "$T/broken.ids" /dev/stderr "$SUBMIT" --demo "${RENDER[@]}" --chunk-size 3 --out "$T/broken" --exe "$WRAPFAIL" \
  --wait --timeout 600 || rc=$?
if ((rc == 1)); then pass "submit.sh --wait exits 1 when a task fails for good ($((SECONDS - t0)) s)"
else fail "submit.sh --wait exits 1 when a task fails for good" "exit $rc"; fi
M=$(sed -n 's/^EYEADAPT_MERGE_JOB=//p' "$T/broken.ids")
mstate=$( [[ -n $M ]] && job_field "$M" JobState || echo "?")
if [[ $mstate == CANCELLED && ! -e $T/broken/merged ]]; then pass "merge job $M CANCELLED, nothing merged"
else fail "merge job cancelled after a failed task" "JobState=$mstate; merged dir exists: $([[ -e $T/broken/merged ]] && echo yes || echo no)"; fi
