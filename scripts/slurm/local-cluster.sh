#!/usr/bin/env bash
# Start, stop or inspect a throw-away single-node Slurm cluster on this machine.
#
# Meant for trying out scripts/slurm/submit.sh and for tests/slurm/e2e.sh on a
# fresh Debian 12 machine where we are root and there is no systemd: the daemons
# (munged, slurmctld, slurmd) are started by hand with a slurm.conf generated
# under the root directory. See shared/design/farm.md for why each setting is
# there; the short version is in the comments of write_conf below.
set -euo pipefail

readonly PROG=${0##*/}
readonly MUNGE_PIDFILE=/run/munge/munged.pid
readonly PACKAGES=(slurmctld slurmd slurm-client munge)

usage() {
  cat <<EOF
Usage: $PROG up|down|status [--root DIR] [--port-base N]

Runs a single-node Slurm cluster (Debian slurm-wlm 22.05 + munge) by hand,
without systemd. Must run as root.

Commands:
  up       install the packages if missing (apt-get), start munged, slurmctld
           and slurmd from an empty state, wait until the node is idle, and
           print the line 'export SLURM_CONF=DIR/etc/slurm.conf' on stdout
           (so  eval "\$($PROG up)"  works). Already up: says so, prints it again.
  down     cancel all jobs of this cluster, stop slurmd, slurmctld and (if this
           script started it) munged by their PID files: SIGTERM, bounded wait,
           then SIGKILL. Safe to call twice or when nothing runs.
  status   show which daemons run, sinfo and squeue; exit 0 when up, 1 if not.

Options:
  --root DIR      where config, state, spool, logs and PID files live
                  (default: \${TMPDIR:-/tmp}/eyeadapt-slurm). 'up' wipes the
                  state/, spool/, log/ and run/ subdirectories of it.
  --port-base N   slurmctld listens on N, slurmd on N+1 (default 6817).
  -h, --help      this text.

Every Slurm client call needs the printed SLURM_CONF (without it Slurm tries a
DNS SRV "configless" lookup and fails). Job completion records are appended to
DIR/log/jobcomp.txt (there is no accounting database, so sacct does not work).
EOF
}

log() { printf '%s: %s\n' "$PROG" "$*" >&2; }
die() { log "error: $*"; exit 1; }
usage_error() { log "$*"; echo "Try '$PROG --help'." >&2; exit 2; }

# --- process helpers ---------------------------------------------------------

# alive PID: true if PID runs and is not a zombie. The sandbox's PID 1 does not
# reap orphans, so a daemon that exited can linger as <defunct>, and kill -0
# would still succeed on it.
alive() {
  local pid=$1 state
  [[ $pid =~ ^[0-9]+$ ]] || return 1
  [[ -r /proc/$pid/stat ]] || return 1
  state=$(sed -E 's/^.*\) ([A-Za-z]).*$/\1/' "/proc/$pid/stat" 2>/dev/null) || return 1
  [[ $state != Z && $state != X ]]
}

# pid_from FILE NAME: prints the PID stored in FILE if that process is alive and
# its command name is NAME (guards against PID reuse); fails otherwise.
pid_from() {
  local file=$1 name=$2 pid comm
  [[ -r $file ]] || return 1
  pid=$(tr -dc '0-9' <"$file")
  alive "$pid" || return 1
  comm=$(cat "/proc/$pid/comm" 2>/dev/null) || return 1
  [[ $comm == "$name" ]] || return 1
  printf '%s\n' "$pid"
}

# stop_pid PID NAME: SIGTERM, wait up to 15 s, then SIGKILL and wait up to 5 s.
stop_pid() {
  local pid=$1 name=$2 i
  log "stopping $name (pid $pid)"
  kill -TERM "$pid" 2>/dev/null || true
  for ((i = 0; i < 150; i++)); do
    alive "$pid" || return 0
    sleep 0.1
  done
  log "$name (pid $pid) ignored SIGTERM for 15 s; sending SIGKILL"
  kill -KILL "$pid" 2>/dev/null || true
  for ((i = 0; i < 50; i++)); do
    alive "$pid" || return 0
    sleep 0.1
  done
  log "warning: $name (pid $pid) is still alive after SIGKILL"
  return 1
}

# port_busy PORT: something already listens on 127.0.0.1:PORT.
port_busy() {
  (exec 3<>"/dev/tcp/127.0.0.1/$1") 2>/dev/null
}

# --- paths ------------------------------------------------------------------

set_paths() {
  CONF=$ROOT/etc/slurm.conf
  CTLD_PIDFILE=$ROOT/run/slurmctld.pid
  SLURMD_PIDFILE=$ROOT/run/slurmd-$NODE.pid
  MUNGE_MARKER=$ROOT/run/munged.started-here
}

ctld_pid() { pid_from "$CTLD_PIDFILE" slurmctld; }
slurmd_pid() { pid_from "$SLURMD_PIDFILE" slurmd; }
munged_pid() { pid_from "$MUNGE_PIDFILE" munged; }

# --- up ---------------------------------------------------------------------

install_packages() {
  local missing=0 c apt_log
  for c in slurmctld slurmd sbatch scontrol sinfo munged munge unmunge; do
    command -v "$c" >/dev/null 2>&1 || missing=1
  done
  ((missing)) || return 0
  command -v apt-get >/dev/null 2>&1 || die "Slurm/munge are not installed and apt-get is not available; install ${PACKAGES[*]} yourself"
  log "installing ${PACKAGES[*]} with apt-get (nothing gets started by the packages: no systemd)"
  apt_log=$(mktemp)
  if ! { apt-get update && DEBIAN_FRONTEND=noninteractive apt-get install -y --no-install-recommends "${PACKAGES[@]}"; } >"$apt_log" 2>&1; then
    tail -n 30 "$apt_log" >&2
    rm -f "$apt_log"
    die "apt-get update/install of ${PACKAGES[*]} failed (output above)"
  fi
  rm -f "$apt_log"
  for c in slurmctld slurmd sbatch munged; do
    command -v "$c" >/dev/null 2>&1 || die "'$c' still missing after installing ${PACKAGES[*]}"
  done
}

start_munge() {
  local pid i
  if pid=$(munged_pid); then
    log "munged already runs (pid $pid); using it"
  else
    getent passwd munge >/dev/null || die "user 'munge' does not exist (is the munge package installed?)"
    install -d -o munge -g munge -m 755 /run/munge
    if [[ ! -s /etc/munge/munge.key ]]; then
      log "creating /etc/munge/munge.key"
      install -d -o munge -g munge -m 700 /etc/munge
      (umask 077 && dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none)
      chown munge:munge /etc/munge/munge.key
      chmod 600 /etc/munge/munge.key
    fi
    log "starting munged as user munge"
    runuser -u munge -- /usr/sbin/munged || die "munged failed to start (see /var/log/munge/munged.log)"
    for ((i = 0; i < 50; i++)); do
      pid=$(munged_pid) && break
      sleep 0.1
    done
    [[ -n ${pid:-} ]] || die "munged did not write $MUNGE_PIDFILE"
    echo "$pid" >"$MUNGE_MARKER"
  fi
  munge -n | unmunge >/dev/null 2>&1 || die "munge self-test failed (munge -n | unmunge)"
}

# node_line: the NodeName line slurmd measures, with NodeName forced to the short
# host name (that is how slurmd finds its own entry), RealMemory lowered to 90 %
# (more than slurmd measures at registration drains the node) and NodeAddr set.
node_line() {
  local line mem
  line=$(SLURM_CONF=/dev/null slurmd -C 2>/dev/null | grep -m1 '^NodeName=') \
    || die "'slurmd -C' printed no NodeName line"
  mem=$(sed -nE 's/.*RealMemory=([0-9]+).*/\1/p' <<<"$line")
  [[ -n $mem ]] || die "no RealMemory in: $line"
  line=$(sed -E "s/^NodeName=[^ ]+/NodeName=$NODE/; s/RealMemory=[0-9]+/RealMemory=$((mem * 9 / 10))/" <<<"$line")
  printf '%s NodeAddr=127.0.0.1 State=UNKNOWN\n' "$line"
}

write_conf() {
  local nodeline
  nodeline=$(node_line)
  cat >"$CONF" <<EOF
# Generated by scripts/slurm/local-cluster.sh on $(date -u +%Y-%m-%dT%H:%M:%SZ); do not edit by hand.
ClusterName=eyeadapt
SlurmctldHost=$NODE(127.0.0.1)
SlurmUser=slurm
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
SlurmctldPort=$PORT_BASE
SlurmdPort=$((PORT_BASE + 1))
StateSaveLocation=$ROOT/state
SlurmdSpoolDir=$ROOT/spool/slurmd-%n
SlurmctldPidFile=$ROOT/run/slurmctld.pid
SlurmdPidFile=$ROOT/run/slurmd-%n.pid
SlurmctldLogFile=$ROOT/log/slurmctld.log
SlurmdLogFile=$ROOT/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups: plain /proc process tracking, no task containment, no accounting.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
# One line per finished job attempt (JobState, ExitCode, ArrayJobId/ArrayTaskId).
JobCompType=jobcomp/filetxt
JobCompLoc=$ROOT/log/jobcomp.txt
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
SwitchType=switch/none
MailProg=/bin/true
ReturnToService=2
# Finished jobs stay visible to 'scontrol show job' for 10 minutes.
MinJobAge=600
KillWait=5
SlurmdTimeout=30
InactiveLimit=0
Waittime=0
# A requeued job waits cred_expire+1 s (default 121 s) before it may start again.
AuthInfo=cred_expire=10
# Main scheduler pass every 5 s (default 60 s), backfill every 5 s (default 30 s).
SchedulerParameters=sched_interval=5,bf_interval=5
# Cancel jobs whose dependency can never be satisfied (default: pend forever).
DependencyParameters=kill_invalid_depend
# Exit code 75 (EX_TEMPFAIL) from the worker => automatic requeue.
RequeueExit=75
JobRequeue=1
$nodeline
PartitionName=batch Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
}

# wait_idle: poll sinfo for up to 60 s until the node reports idle.
wait_idle() {
  local i state=""
  for ((i = 0; i < 120; i++)); do
    state=$(SLURM_CONF=$CONF sinfo -h -N -n "$NODE" -o '%T' 2>/dev/null | head -1) || state=""
    case $state in
      idle) return 0 ;;
      drain* | down* | fail*)
        if ((i > 20)); then
          SLURM_CONF=$CONF sinfo -R >&2 || true
          die "node $NODE is '$state'; see $ROOT/log/slurmctld.log and $ROOT/log/slurmd.log"
        fi ;;
    esac
    ctld_pid >/dev/null || { tail -n 20 "$ROOT/log/slurmctld.log" >&2 || true; die "slurmctld died; log above ($ROOT/log/slurmctld.log)"; }
    slurmd_pid >/dev/null || { tail -n 20 "$ROOT/log/slurmd.log" >&2 || true; die "slurmd died; log above ($ROOT/log/slurmd.log)"; }
    sleep 0.5
  done
  die "node $NODE not idle after 60 s (last state '${state:-none}'); see $ROOT/log/"
}

cmd_up() {
  local d i pid
  if ctld_pid >/dev/null && slurmd_pid >/dev/null; then
    log "already up (root $ROOT)"
    echo "export SLURM_CONF=$CONF"
    return 0
  fi
  if ctld_pid >/dev/null || slurmd_pid >/dev/null; then
    log "only part of the cluster runs; restarting it"
    cmd_down
  fi
  if port_busy "$PORT_BASE" || port_busy "$((PORT_BASE + 1))"; then
    die "port $PORT_BASE or $((PORT_BASE + 1)) is already in use (another slurmctld/slurmd?); pick other ports with --port-base N"
  fi
  install_packages
  getent passwd slurm >/dev/null || die "user 'slurm' does not exist (is slurmctld installed?)"

  # Start from an empty StateSaveLocation: old state would bring back old jobs
  # and job ids. Logs go too, so jobcomp.txt describes this run only.
  mkdir -p "$ROOT"
  chmod 755 "$ROOT"
  for d in state spool log run; do rm -rf "${ROOT:?}/$d"; done
  mkdir -p "$ROOT"/{etc,state,spool,log,run}
  chown slurm:slurm "$ROOT/state" "$ROOT/log"
  touch "$ROOT/log/jobcomp.txt"
  chown slurm:slurm "$ROOT/log/jobcomp.txt"
  runuser -u slurm -- test -w "$ROOT/state" \
    || die "user slurm cannot write $ROOT/state (is a parent of $ROOT private, e.g. made by mktemp -d? chmod 755 it)"

  start_munge
  write_conf
  log "wrote $CONF"

  log "starting slurmctld"
  SLURM_CONF=$CONF slurmctld -i || die "slurmctld failed to start; see $ROOT/log/slurmctld.log"
  for ((i = 0; i < 100; i++)); do
    SLURM_CONF=$CONF scontrol ping >/dev/null 2>&1 && break
    sleep 0.1
  done
  log "starting slurmd"
  SLURM_CONF=$CONF slurmd || die "slurmd failed to start; see $ROOT/log/slurmd.log"
  wait_idle
  pid=$(ctld_pid)
  log "up: node $NODE idle, slurmctld pid $pid, slurmd pid $(slurmd_pid), partition 'batch'"
  log "logs in $ROOT/log/, job completions in $ROOT/log/jobcomp.txt"
  echo "export SLURM_CONF=$CONF"
}

# --- down -------------------------------------------------------------------

cancel_jobs() {
  local ids i
  [[ -r $CONF ]] || return 0
  ctld_pid >/dev/null || return 0
  ids=$(SLURM_CONF=$CONF squeue -h -o '%A' 2>/dev/null | sort -u | tr '\n' ' ') || return 0
  [[ -n ${ids// /} ]] || return 0
  log "cancelling jobs still in the queue: $ids"
  # shellcheck disable=SC2086 # ids is a list of numeric job ids
  SLURM_CONF=$CONF scancel $ids 2>/dev/null || true
  for ((i = 0; i < 100; i++)); do
    [[ -z $(SLURM_CONF=$CONF squeue -h -o '%A' 2>/dev/null) ]] && return 0
    sleep 0.2
  done
  log "warning: jobs still listed 20 s after scancel"
}

cmd_down() {
  local pid f stopped=0
  cancel_jobs
  # slurmd first (so it does not try to re-register), then slurmctld.
  for f in "$ROOT"/run/slurmd-*.pid; do
    [[ -e $f ]] || continue
    if pid=$(pid_from "$f" slurmd); then stop_pid "$pid" slurmd && stopped=1; fi
  done
  if pid=$(ctld_pid); then stop_pid "$pid" slurmctld && stopped=1; fi
  if [[ -e $MUNGE_MARKER ]]; then
    if pid=$(munged_pid); then
      if [[ $pid == "$(tr -dc '0-9' <"$MUNGE_MARKER")" ]]; then
        stop_pid "$pid" munged && stopped=1
      else
        log "munged (pid $pid) was not started by this script; leaving it"
      fi
    fi
    rm -f "$MUNGE_MARKER"
  elif pid=$(munged_pid); then
    log "munged (pid $pid) was not started by this script; leaving it"
  fi
  if ((stopped)); then log "down (logs kept in $ROOT/log/)"; else log "nothing was running (root $ROOT)"; fi
}

# --- status -----------------------------------------------------------------

cmd_status() {
  local pid up=1
  if pid=$(munged_pid); then log "munged:    running (pid $pid)"; else log "munged:    not running"; up=0; fi
  if pid=$(ctld_pid); then log "slurmctld: running (pid $pid)"; else log "slurmctld: not running"; up=0; fi
  if pid=$(slurmd_pid); then log "slurmd:    running (pid $pid)"; else log "slurmd:    not running"; up=0; fi
  if ((up)); then
    SLURM_CONF=$CONF sinfo >&2 || true
    SLURM_CONF=$CONF squeue >&2 || true
    echo "export SLURM_CONF=$CONF"
    return 0
  fi
  log "cluster is not (fully) up (root $ROOT)"
  return 1
}

# --- main -------------------------------------------------------------------

main() {
  local cmd=""
  ROOT=${TMPDIR:-/tmp}/eyeadapt-slurm
  PORT_BASE=6817
  while (($#)); do
    case $1 in
      -h | --help) usage; exit 0 ;;
      --root) (($# >= 2)) || usage_error "--root needs a directory"; ROOT=$2; shift 2 ;;
      --root=*) ROOT=${1#*=}; shift ;;
      --port-base) (($# >= 2)) || usage_error "--port-base needs a number"; PORT_BASE=$2; shift 2 ;;
      --port-base=*) PORT_BASE=${1#*=}; shift ;;
      up | down | status) [[ -z $cmd ]] || usage_error "only one command allowed"; cmd=$1; shift ;;
      *) usage_error "unknown argument '$1'" ;;
    esac
  done
  [[ -n $cmd ]] || usage_error "missing command (up, down or status)"
  [[ -n $ROOT ]] || usage_error "--root must not be empty"
  if ! [[ $PORT_BASE =~ ^[0-9]+$ ]] || ((PORT_BASE < 1 || PORT_BASE > 65534)); then
    usage_error "--port-base must be a port number (1-65534)"
  fi
  ((EUID == 0)) || die "must run as root (it installs packages and starts daemons)"
  [[ $ROOT == /* ]] || ROOT=$PWD/$ROOT
  ROOT=${ROOT%/}
  NODE=$(hostname -s)
  set_paths
  "cmd_$cmd"
}

main "$@"
