#!/usr/bin/env bash
# Submit an eyeadapt sequence to Slurm: one array task per chunk of frames, then
# one dependent job that merges the chunks and writes the report.
#
# Two Slurm traps shape this script (details in shared/design/farm.md):
# - the merge depends on every task by id (afterok:A_0:A_1:...), never on the
#   whole array (afterok:A): Slurm remembers a failed attempt of a task forever,
#   so a task that exits 75, is requeued and then succeeds would still make a
#   whole-array afterok dependency fail;
# - success is read from JobState (scontrol show job -o), never from the exit
#   code of 'sbatch --wait', which is 0 for a job cancelled before it ran.
set -euo pipefail

readonly PROG=${0##*/}
SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
readonly SCRIPT_DIR
readonly REPO_DIR=${SCRIPT_DIR%/scripts/slurm}

usage() {
  cat <<EOF
Usage: $PROG JOB|--demo [options] [-- WORKER-ARGS...]

Renders the eyeadapt job file JOB (or, with --demo, the built-in demo job) on
Slurm. 'eyeadapt plan' gives the number of chunks K; then
  1. an array job --array=0-(K-1): task i runs
       eyeadapt sequence JOB --chunk-size N --chunk-index i --out OUT/chunks/i ...
     logging to OUT/logs/render_<arrayjob>_<task>.log (appended across retries);
  2. a merge job that waits for every task (afterok:A_0:A_1:...) and runs
       eyeadapt merge OUT/chunks/0 ... OUT/chunks/K-1 --out OUT/merged
       eyeadapt report OUT/merged
     after checking that every chunk directory is complete.
A task that exits 75 (transient failure) is requeued by Slurm if the cluster
has RequeueExit=75 in slurm.conf (scripts/slurm/local-cluster.sh sets it); the
worker resumes, skipping frames already done.

Options:
  --demo               render the built-in demo job instead of a JOB file
  --frames SPEC        frame selection passed to plan and sequence (e.g. 0-99)
  --chunk-size N       frames per array task (default 10)
  --out DIR            output directory, on a file system all nodes share
                       (default: out/<job name>)
  --exe PATH           eyeadapt binary or wrapper (default: \$EYEADAPT, else
                       $REPO_DIR/target/release/eyeadapt, else eyeadapt on PATH)
  --threads T          worker threads per task; also --cpus-per-task (default 1)
  --width W, --height H, --spp N
                       passed to 'eyeadapt sequence'
  --partition P        Slurm partition for both jobs
  --time T             time limit for each task and for the merge (sbatch --time)
  --name NAME          Slurm job name (default: eyeadapt-<job name>)
  --max-parallel N     run at most N tasks at once (--array=0-(K-1)%N)
  --extra-sbatch ARGS  more sbatch options for both jobs, split on white space
                       (e.g. "--account=vis --qos=low"); may be repeated
  --max-retries N      requeues allowed per task after exit 75 (default 3); the
                       next exit 75 is turned into exit 1, a permanent failure.
                       Slurm 22.05 itself requeues on RequeueExit without limit.
  --no-kill-on-invalid-dep
                       submit the merge with --kill-on-invalid-dep=no instead of
                       =yes (for sites that ask users not to use the flag); if
                       a task fails the merge then pends in
                       DependencyNeverSatisfied until --wait (or you) scancel it.
                       (--extra-sbatch cannot do this: when sbatch 22.05 gets
                       both =yes and =no, =yes wins whatever the order.)
  --wait               block until both jobs ended; exit 0 only if every task
                       and the merge are COMPLETED
  --timeout SECONDS    limit for --wait (default 3600); jobs keep running after it
  --dry-run            write the batch scripts and print the sbatch commands only
  -h, --help           this text
  -- WORKER-ARGS       everything after -- is appended to 'eyeadapt sequence'

Prints the job ids (also as EYEADAPT_ARRAY_JOB=... / EYEADAPT_MERGE_JOB=...
lines on stdout and in OUT/slurm/jobs.env) and how to follow them.
Exit status: 0 submitted (with --wait: all COMPLETED), 1 failure,
2 usage error or bad job input, 124 --wait timed out.
Slurm clients need a config: on the local test cluster export the SLURM_CONF
line printed by 'scripts/slurm/local-cluster.sh up'.
EOF
}

log() { printf '%s: %s\n' "$PROG" "$*" >&2; }
die() { log "error: $*"; exit 1; }
usage_error() { log "$*"; echo "Try '$PROG --help'." >&2; exit 2; }

need_value() { (($2 >= 2)) || usage_error "$1 needs a value"; }
positive_int() { [[ $2 =~ ^[1-9][0-9]*$ ]] || usage_error "$1 must be a positive integer, got '$2'"; }

# --- arguments --------------------------------------------------------------

JOB="" DEMO=0 FRAMES="" CHUNK_SIZE=10 OUT="" EXE="" THREADS=1 PARTITION="" TIME_LIMIT=""
NAME="" MAX_PARALLEL="" WAIT=0 TIMEOUT=3600 DRY_RUN=0 KILL_INVALID_DEP=yes MAX_RETRIES=3
RENDER_OPTS=() EXTRA_SBATCH=() WORKER_ARGS=()

parse_args() {
  local words
  while (($#)); do
    case $1 in
      -h | --help) usage; exit 0 ;;
      --demo) DEMO=1; shift ;;
      --frames) need_value "$1" $#; FRAMES=$2; shift 2 ;;
      --chunk-size) need_value "$1" $#; positive_int "$1" "$2"; CHUNK_SIZE=$2; shift 2 ;;
      --out) need_value "$1" $#; OUT=$2; shift 2 ;;
      --exe) need_value "$1" $#; EXE=$2; shift 2 ;;
      --threads) need_value "$1" $#; positive_int "$1" "$2"; THREADS=$2; shift 2 ;;
      --width | --height | --spp)
        need_value "$1" $#; positive_int "$1" "$2"; RENDER_OPTS+=("$1" "$2"); shift 2 ;;
      --partition) need_value "$1" $#; PARTITION=$2; shift 2 ;;
      --time) need_value "$1" $#; TIME_LIMIT=$2; shift 2 ;;
      --name) need_value "$1" $#; NAME=$2; shift 2 ;;
      --max-parallel) need_value "$1" $#; positive_int "$1" "$2"; MAX_PARALLEL=$2; shift 2 ;;
      --extra-sbatch)
        need_value "$1" $#
        read -r -a words <<<"$2"
        EXTRA_SBATCH+=("${words[@]}")
        shift 2 ;;
      --max-retries) need_value "$1" $#; [[ $2 =~ ^[0-9]+$ ]] || usage_error "--max-retries must be a number"; MAX_RETRIES=$2; shift 2 ;;
      --no-kill-on-invalid-dep) KILL_INVALID_DEP=no; shift ;;
      --wait) WAIT=1; shift ;;
      --timeout) need_value "$1" $#; positive_int "$1" "$2"; TIMEOUT=$2; shift 2 ;;
      --dry-run) DRY_RUN=1; shift ;;
      --) shift; WORKER_ARGS=("$@"); break ;;
      -*) usage_error "unknown option '$1'" ;;
      *) [[ -z $JOB ]] || usage_error "more than one JOB given ('$JOB', '$1')"; JOB=$1; shift ;;
    esac
  done
  if ((DEMO)) && [[ -n $JOB ]]; then usage_error "give either JOB or --demo, not both"; fi
  if ((!DEMO)) && [[ -z $JOB ]]; then usage_error "missing JOB file (or --demo for the built-in demo job)"; fi
}

abspath() { if [[ $1 == /* ]]; then printf '%s\n' "$1"; else printf '%s\n' "$PWD/$1"; fi; }

resolve_inputs() {
  local base
  if ((DEMO)); then
    base=demo
  else
    [[ -f $JOB ]] || usage_error "job file '$JOB' not found"
    JOB=$(abspath "$JOB")
    base=${JOB##*/}
    base=${base%.toml}
  fi
  [[ -n $OUT ]] || OUT=out/$base
  OUT=$(abspath "$OUT")
  OUT=${OUT%/}
  [[ -n $NAME ]] || NAME=eyeadapt-$base

  if [[ -z $EXE ]]; then
    if [[ -n ${EYEADAPT:-} ]]; then EXE=$EYEADAPT
    elif [[ -x $REPO_DIR/target/release/eyeadapt ]]; then EXE=$REPO_DIR/target/release/eyeadapt
    elif EXE=$(command -v eyeadapt); then :
    else die "no eyeadapt binary: build it (cargo build --release), or pass --exe PATH or set EYEADAPT"
    fi
  fi
  [[ $EXE == */* ]] || EXE=$(command -v "$EXE") || die "'$EXE' not found on PATH"
  EXE=$(abspath "$EXE")
  [[ -f $EXE && -x $EXE ]] || die "'$EXE' is not an executable file"

  if ((!DRY_RUN)); then
    command -v sbatch >/dev/null 2>&1 || die "sbatch not found: this machine is not a Slurm submit host (try scripts/slurm/local-cluster.sh up)"
  fi
}

# --- plan -------------------------------------------------------------------

# run_plan: asks the worker how many chunks there are; sets FRAMES_N, CHUNKS,
# FIRST, LAST. The output is parsed, not eval'ed.
run_plan() {
  local args=(plan) out rc=0 line
  ((DEMO)) || args+=("$JOB")
  [[ -z $FRAMES ]] || args+=(--frames "$FRAMES")
  args+=(--chunk-size "$CHUNK_SIZE")
  out=$("$EXE" "${args[@]}") || rc=$?
  if ((rc == 2)); then
    log "error: '$EXE ${args[*]}' rejected the job (exit 2)"
    exit 2
  elif ((rc != 0)); then
    die "'$EXE ${args[*]}' failed with exit $rc"
  fi
  FRAMES_N="" CHUNKS="" FIRST="" LAST=""
  local v
  while IFS= read -r line; do
    # Values are single-quoted (EYEADAPT_FRAMES='97'); the numbers hold no quote inside.
    v=${line#*=} v=${v#\'} v=${v%\'}
    case $line in
      EYEADAPT_FRAMES=*) FRAMES_N=$v ;;
      EYEADAPT_CHUNKS=*) CHUNKS=$v ;;
      EYEADAPT_FIRST=*) FIRST=$v ;;
      EYEADAPT_LAST=*) LAST=$v ;;
    esac
  done <<<"$out"
  [[ $CHUNKS =~ ^[0-9]+$ && $FRAMES_N =~ ^[0-9]+$ ]] \
    || die "could not read EYEADAPT_CHUNKS/EYEADAPT_FRAMES from '$EXE ${args[*]}'; it printed: $out"
  ((CHUNKS >= 1)) || usage_error "the frame selection is empty (EYEADAPT_CHUNKS=$CHUNKS)"
}

# --- batch scripts ------------------------------------------------------------

# quoted WORD...: the words, shell-quoted, separated by spaces.
quoted() {
  local out="" w
  for w in "$@"; do out+=" $(printf '%q' "$w")"; done
  printf '%s' "${out# }"
}

write_scripts() {
  local head=(sequence) tail=(--threads "$THREADS")
  ((DEMO)) || head+=("$JOB")
  [[ -z $FRAMES ]] || tail+=(--frames "$FRAMES")
  tail+=("${RENDER_OPTS[@]}" "${WORKER_ARGS[@]}")
  mkdir -p "$OUT/slurm" "$OUT/logs" "$OUT/chunks"

  RENDER_SCRIPT=$OUT/slurm/render.sh
  cat >"$RENDER_SCRIPT" <<EOF
#!/bin/bash
# Generated by scripts/slurm/submit.sh on $(date -u +%Y-%m-%dT%H:%M:%SZ).
# One Slurm array task renders one chunk of $CHUNK_SIZE frames into OUT/chunks/<task id>.
# Exit 75 asks for a retry (RequeueExit=75); rerunning resumes the chunk.
set -uo pipefail
exe=$(quoted "$EXE")
out=$(quoted "$OUT")
head=($(quoted "${head[@]}"))
tail=($(quoted "${tail[@]}"))
task=\${SLURM_ARRAY_TASK_ID:?this script runs as a Slurm array task}
echo "eyeadapt-slurm: chunk \$task of array job \${SLURM_ARRAY_JOB_ID:-?}, attempt \$((\${SLURM_RESTART_COUNT:-0} + 1)), host \$(hostname -s), \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
mkdir -p "\$out/chunks"
"\$exe" "\${head[@]}" --chunk-size $CHUNK_SIZE --chunk-index "\$task" --out "\$out/chunks/\$task" "\${tail[@]}"
rc=\$?
restarts=\${SLURM_RESTART_COUNT:-0}
if ((rc == 75 && restarts >= $MAX_RETRIES)); then
  # Slurm would requeue on every exit 75 forever (retry limit here: $MAX_RETRIES).
  echo "eyeadapt-slurm: chunk \$task exit 75 again after \$restarts retries (limit $MAX_RETRIES); failing for good" >&2
  rc=1
fi
case \$rc in
  0) what="done" ;;
  75) what="transient failure, asking Slurm for a retry (needs RequeueExit=75)" ;;
  2) what="bad input or usage" ;;
  *) what="failed" ;;
esac
echo "eyeadapt-slurm: chunk \$task exit \$rc (\$what) at \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
exit \$rc
EOF

  MERGE_SCRIPT=$OUT/slurm/merge.sh
  cat >"$MERGE_SCRIPT" <<EOF
#!/bin/bash
# Generated by scripts/slurm/submit.sh on $(date -u +%Y-%m-%dT%H:%M:%SZ).
# Runs after every array task succeeded: checks all $CHUNKS chunk directories,
# merges them into OUT/merged and writes the report. The result is built in a
# temporary directory and renamed, so OUT/merged is either complete or absent.
set -euo pipefail
exe=$(quoted "$EXE")
out=$(quoted "$OUT")
chunks=$CHUNKS
dirs=() missing=()
for ((i = 0; i < chunks; i++)); do
  if [[ -f \$out/chunks/\$i/manifest.json ]]; then dirs+=("\$out/chunks/\$i"); else missing+=("\$i"); fi
done
if ((\${#missing[@]})); then
  echo "eyeadapt-slurm: not merging: chunk(s) \${missing[*]} of \$chunks missing (no \$out/chunks/<i>/manifest.json)" >&2
  exit 1
fi
tmp=\$out/merged.tmp.\${SLURM_JOB_ID:-\$\$}
rm -rf "\$tmp"
echo "eyeadapt-slurm: merging \$chunks chunks at \$(date -u +%Y-%m-%dT%H:%M:%SZ)"
# The chunks cover the --frames selection given to submit.sh (else the job's own frames).
frames=($([[ -z $FRAMES ]] || quoted --frames "$FRAMES"))
"\$exe" merge "\${dirs[@]}" --out "\$tmp" "\${frames[@]}"
note="report: \$out/merged/report.html"
if "\$exe" report --help >/dev/null 2>&1; then
  "\$exe" report "\$tmp"
else
  note="no report: this eyeadapt has no 'report' command"
  echo "eyeadapt-slurm: WARNING: \$exe has no 'report' command; merged without coherence.csv/report.html" >&2
fi
rm -rf "\$out/merged"
mv "\$tmp" "\$out/merged"
echo "eyeadapt-slurm: merged into \$out/merged (\$note)"
EOF
  chmod +x "$RENDER_SCRIPT" "$MERGE_SCRIPT"
}

warn_stale_chunks() {
  local d i
  for d in "$OUT"/chunks/*; do
    [[ -d $d ]] || continue
    i=${d##*/}
    if ! [[ $i =~ ^[0-9]+$ ]] || ((i >= CHUNKS)); then
      log "warning: $d is not one of this run's $CHUNKS chunks; it is ignored by the merge"
    fi
  done
}

# --- submission ---------------------------------------------------------------

common_sbatch_opts() {
  COMMON=(--parsable)
  [[ -z $PARTITION ]] || COMMON+=(--partition "$PARTITION")
  [[ -z $TIME_LIMIT ]] || COMMON+=(--time "$TIME_LIMIT")
}

# job_id SBATCH-PARSABLE-OUTPUT: "123" or "123;cluster" -> 123
job_id() { local id=${1%%;*}; [[ $id =~ ^[0-9]+$ ]] || return 1; printf '%s\n' "$id"; }

submit() {
  local array_spec="0-$((CHUNKS - 1))" dep="afterok" i out
  [[ -z $MAX_PARALLEL ]] || array_spec+="%$MAX_PARALLEL"
  common_sbatch_opts
  RENDER_CMD=(sbatch "${COMMON[@]}" --job-name "$NAME" --array "$array_spec" --requeue
    --open-mode=append --output "$OUT/logs/render_%A_%a.log" --cpus-per-task "$THREADS"
    "${EXTRA_SBATCH[@]}" "$RENDER_SCRIPT")
  if ((DRY_RUN)); then
    log "dry run; would submit:"
    quoted "${RENDER_CMD[@]}"
    echo
    quoted sbatch "${COMMON[@]}" --job-name "$NAME-merge" --dependency "afterok:<A>_0:...:<A>_$((CHUNKS - 1))" \
      "--kill-on-invalid-dep=$KILL_INVALID_DEP" --open-mode=append --output "$OUT/logs/merge_%j.log" "${EXTRA_SBATCH[@]}" "$MERGE_SCRIPT"
    echo
    exit 0
  fi

  out=$("${RENDER_CMD[@]}") || die "sbatch of the render array failed (is SLURM_CONF set, is the partition right?)"
  ARRAY_JOB=$(job_id "$out") || die "unexpected sbatch output: $out"

  # Per-task afterok: see the comment at the top of this file.
  for ((i = 0; i < CHUNKS; i++)); do dep+=":${ARRAY_JOB}_$i"; done
  MERGE_CMD=(sbatch "${COMMON[@]}" --job-name "$NAME-merge" --dependency "$dep"
    "--kill-on-invalid-dep=$KILL_INVALID_DEP" --open-mode=append --output "$OUT/logs/merge_%j.log"
    "${EXTRA_SBATCH[@]}" "$MERGE_SCRIPT")
  if ! out=$("${MERGE_CMD[@]}") || ! MERGE_JOB=$(job_id "$out"); then
    log "error: sbatch of the merge job failed; cancelling render array $ARRAY_JOB"
    scancel "$ARRAY_JOB" || true
    exit 1
  fi

  printf 'EYEADAPT_ARRAY_JOB=%s\nEYEADAPT_MERGE_JOB=%s\nEYEADAPT_CHUNKS=%s\nEYEADAPT_OUT=%s\n' \
    "$ARRAY_JOB" "$MERGE_JOB" "$CHUNKS" "$(printf '%q' "$OUT")" >"$OUT/slurm/jobs.env"

  cat >&2 <<EOF
$PROG: submitted $NAME: $FRAMES_N frames ${FIRST:+($FIRST-$LAST) }in $CHUNKS chunk(s) of up to $CHUNK_SIZE
  render array job  $ARRAY_JOB  (tasks 0-$((CHUNKS - 1)), requeued on exit 75)
  merge job         $MERGE_JOB  (afterok on each of the $CHUNKS tasks)
Follow it with:
  squeue -j $ARRAY_JOB,$MERGE_JOB
  tail -f $OUT/logs/render_${ARRAY_JOB}_<task>.log   $OUT/logs/merge_$MERGE_JOB.log
  scontrol show job $ARRAY_JOB      scontrol show job $MERGE_JOB
Result: $OUT/merged (report.html); cancel with: scancel $ARRAY_JOB $MERGE_JOB
EOF
  printf 'EYEADAPT_ARRAY_JOB=%s\nEYEADAPT_MERGE_JOB=%s\n' "$ARRAY_JOB" "$MERGE_JOB"
}

# --- --wait -------------------------------------------------------------------

# Task states by array index, filled by poll_array; the last known state is
# kept when Slurm forgets a finished job (after MinJobAge).
declare -A T_STATE=() T_REASON=() T_RESTARTS=() T_EXIT=()
M_STATE="" M_REASON=""

field() { # field LINE NAME -> value of NAME=... in a one-line scontrol record
  local re="(^| )$2=([^ ]*)"
  [[ $1 =~ $re ]] && printf '%s\n' "${BASH_REMATCH[2]}"
}

# expand_ids "1-3,5%2" -> 1 2 3 5
expand_ids() {
  local spec=${1%%\%*} part a b
  local -a parts
  IFS=, read -r -a parts <<<"$spec"
  for part in "${parts[@]}"; do
    if [[ $part =~ ^([0-9]+)-([0-9]+)(:([0-9]+))?$ ]]; then
      for ((a = BASH_REMATCH[1], b = BASH_REMATCH[2]; a <= b; a += ${BASH_REMATCH[4]:-1})); do echo "$a"; done
    elif [[ $part =~ ^[0-9]+$ ]]; then
      echo "$part"
    fi
  done
}

poll_array() {
  local out line ids id st
  out=$(scontrol show job -o "$ARRAY_JOB" 2>&1) || return 0 # forgotten: keep what we know
  while IFS= read -r line; do
    [[ $line == *JobState=* ]] || continue
    ids=$(field "$line" ArrayTaskId) || continue
    st=$(field "$line" JobState) || continue
    for id in $(expand_ids "$ids"); do
      T_STATE[$id]=$st
      T_REASON[$id]=$(field "$line" Reason || true)
      T_RESTARTS[$id]=$(field "$line" Restarts || echo 0)
      T_EXIT[$id]=$(field "$line" ExitCode || true)
    done
  done <<<"$out"
}

poll_merge() {
  local out
  out=$(scontrol show job -o "$MERGE_JOB" 2>&1) || return 0
  M_STATE=$(field "$out" JobState || true)
  M_REASON=$(field "$out" Reason || true)
}

is_final() {
  case $1 in
    COMPLETED | FAILED | CANCELLED | TIMEOUT | NODE_FAIL | OUT_OF_MEMORY | BOOT_FAIL | DEADLINE | PREEMPTED) return 0 ;;
    *) return 1 ;;
  esac
}

# is_stuck STATE REASON: the task will not run again without a human
# (RequeueExitHold, or Slurm's max_batch_requeue limit turning retries into a hold).
is_stuck() {
  case $1 in SPECIAL_EXIT | REQUEUE_HOLD) return 0 ;; esac
  [[ $1 == PENDING && $2 == *Held* ]]
}

# summarize: sets COUNTS ("2 COMPLETED, 1 RUNNING"), N_DONE (final or stuck), N_STUCK.
summarize() {
  local i st
  local -A n=()
  N_DONE=0 N_STUCK=0
  for ((i = 0; i < CHUNKS; i++)); do
    st=${T_STATE[$i]:-UNKNOWN}
    if is_stuck "$st" "${T_REASON[$i]:-}"; then st=HELD; N_STUCK=$((N_STUCK + 1)); N_DONE=$((N_DONE + 1))
    elif is_final "$st"; then N_DONE=$((N_DONE + 1)); fi
    n[$st]=$((${n[$st]:-0} + 1))
  done
  COUNTS=""
  for st in "${!n[@]}"; do COUNTS+="${COUNTS:+, }${n[$st]} $st"; done
}

wait_for_jobs() {
  local deadline=$((SECONDS + TIMEOUT)) status="" last="" i ok=1 cancelled_merge=0
  local -A seen_restarts=()
  log "waiting for jobs $ARRAY_JOB and $MERGE_JOB (timeout ${TIMEOUT}s)"
  while :; do
    poll_array
    poll_merge
    summarize
    for ((i = 0; i < CHUNKS; i++)); do
      if [[ ${T_RESTARTS[$i]:-0} != "${seen_restarts[$i]:-0}" && ${T_RESTARTS[$i]:-0} != 0 ]]; then
        log "task $i was requeued (restart ${T_RESTARTS[$i]}); Slurm will run it again"
        seen_restarts[$i]=${T_RESTARTS[$i]}
      fi
    done
    status="tasks: $COUNTS; merge: ${M_STATE:-UNKNOWN}${M_REASON:+ ($M_REASON)}"
    [[ $status == "$last" ]] || log "$status"
    last=$status

    if ((N_DONE == CHUNKS)); then
      is_final "$M_STATE" && break
      if [[ $M_STATE == PENDING && $M_REASON == DependencyNeverSatisfied ]]; then
        # The cluster did not cancel it (no kill_invalid_depend, or the flag was
        # ignored): do it here, so nothing is left pending forever.
        log "merge job $MERGE_JOB can never run (a task failed); cancelling it"
        scancel "$MERGE_JOB" || true
        cancelled_merge=1
      elif ((N_STUCK > 0)); then
        break # a held task blocks the merge; nothing will change by waiting
      fi
    fi
    if ((SECONDS >= deadline)); then
      log "error: timed out after ${TIMEOUT}s ($status); the jobs keep running (scancel $ARRAY_JOB $MERGE_JOB)"
      exit 124
    fi
    sleep 2
  done

  for ((i = 0; i < CHUNKS; i++)); do
    if [[ ${T_STATE[$i]:-UNKNOWN} != COMPLETED ]]; then
      ok=0
      log "task $i: ${T_STATE[$i]:-UNKNOWN} exit ${T_EXIT[$i]:-?} reason ${T_REASON[$i]:-?} restarts ${T_RESTARTS[$i]:-0}; log $OUT/logs/render_${ARRAY_JOB}_$i.log"
      if is_stuck "${T_STATE[$i]:-}" "${T_REASON[$i]:-}"; then
        log "  task ${ARRAY_JOB}_$i is held: fix the cause, then 'scontrol release ${ARRAY_JOB}_$i' (or scancel $ARRAY_JOB $MERGE_JOB)"
      fi
    elif [[ ${T_RESTARTS[$i]:-0} != 0 ]]; then
      log "task $i: COMPLETED after ${T_RESTARTS[$i]} requeue(s)"
    fi
  done
  if [[ $M_STATE != COMPLETED ]]; then
    ok=0
    if ((cancelled_merge)); then
      log "merge job $MERGE_JOB: cancelled by $PROG (dependency never satisfied)"
    else
      log "merge job $MERGE_JOB: ${M_STATE:-UNKNOWN}${M_REASON:+ ($M_REASON)}; log $OUT/logs/merge_$MERGE_JOB.log"
    fi
  fi
  if ((ok)); then
    log "all $CHUNKS tasks and the merge COMPLETED; result in $OUT/merged"
    return 0
  fi
  log "error: the render did not complete (see above)"
  exit 1
}

main() {
  parse_args "$@"
  resolve_inputs
  run_plan
  write_scripts
  warn_stale_chunks
  submit
  ((WAIT)) || return 0
  wait_for_jobs
}

main "$@"
