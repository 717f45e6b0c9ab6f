#!/usr/bin/env bash
# End-to-end test of examples/slurm/sweep.sbatch on a throw-away one-node Slurm
# cluster: the sharded job array, merged with `mechgraph merge`, must give the
# very same bytes as the same sweep run in one process.
#
# Runs as root on Debian 12, also in a container without systemd. It installs
# slurm-wlm and munge when missing, starts munged, slurmctld and slurmd itself
# and stops them again on exit. It does not build mechgraph: run it after the
# build (MECHGRAPH=/path/to/mechgraph to test another binary).
#
# Environment:
#   MECHGRAPH          the binary to test        (default: build/bin/mechgraph)
#   TEST_CLUSTER_DIR   config, state, logs, parts (default: /tmp/mechgraph-test-cluster;
#                      wiped at the start, removed after a pass unless KEEP=1;
#                      DIR.lock beside it keeps a second run from starting)
#   SLURMCTLD_PORT, SLURMD_PORT   (default 16817, 16818: not Slurm's usual
#                      ports, so an installed Slurm on the machine is left alone)
#   JOB_TIMEOUT        seconds to wait for the job array (default 600)
set -euo pipefail

ROOT=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
MECHGRAPH=${MECHGRAPH:-$ROOT/build/bin/mechgraph}
WORK=${TEST_CLUSTER_DIR:-${TMPDIR:-/tmp}/mechgraph-test-cluster}
SLURMCTLD_PORT=${SLURMCTLD_PORT:-16817}
SLURMD_PORT=${SLURMD_PORT:-16818}
JOB_TIMEOUT=${JOB_TIMEOUT:-600}
NODE_TIMEOUT=60

# The sweep under test: 36 cases, split over 4 array tasks (9 each).
SCENE=$ROOT/scenes/valvetrain_cams.yaml
SWEEP_ARGS="--vary rpm=3000rpm:7000rpm:12 --vary lift=7mm:9mm:3 --outputs ta_arc.time_area,v_kurz.max_acceleration"
TASKS=(0 1 2 3)

log() { printf '[test-cluster] %s\n' "$*"; }
fail() { printf '[test-cluster] error: %s\n' "$*" >&2; exit 1; }

[[ $(id -u) -eq 0 ]] || fail "run as root: it installs packages and starts munged and the Slurm daemons"
[[ -x $MECHGRAPH ]] || fail "no mechgraph binary at $MECHGRAPH (build the project first, or set MECHGRAPH)"
MECHGRAPH=$(cd "$(dirname "$MECHGRAPH")" && pwd)/$(basename "$MECHGRAPH")
started=$SECONDS
node=$(hostname -s)

# ---------------------------------------------------------------- packages
missing=()
for p in slurm-wlm munge; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q "install ok installed" || missing+=("$p")
done
if ((${#missing[@]})); then
  log "installing ${missing[*]}"
  apt-get update -qq
  DEBIAN_FRONTEND=noninteractive apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi

# ---------------------------------------------------------- daemon handling
# pid files under $WORK/run name every daemon this script started. A run that
# was killed (SIGKILL, lost session) cannot stop its daemons; the next run finds
# them here and stops them before it wipes $WORK.
stop_pid() { # NAME PID: TERM, wait up to 10 s, then KILL
  local name=$1 pid=$2 i
  [[ -n $pid ]] && kill -0 "$pid" 2>/dev/null || return 0
  # Only a process that still runs the program we started (pids are reused).
  [[ $(cat "/proc/$pid/comm" 2>/dev/null) == "$name" ]] || return 0
  kill -TERM "$pid" 2>/dev/null || true
  for ((i = 0; i < 100; i++)); do
    kill -0 "$pid" 2>/dev/null || return 0
    sleep 0.1
  done
  log "$name ($pid) ignored SIGTERM; killing it"
  kill -KILL "$pid" 2>/dev/null || true
}

stop_daemons() {
  local name
  for name in slurmd slurmctld munged; do
    [[ -f $WORK/run/$name.pid ]] || continue
    stop_pid "$name" "$(cat "$WORK/run/$name.pid")"
    rm -f "$WORK/run/$name.pid"
  done
}

ctld_alive() {
  [[ -f $WORK/run/slurmctld.pid ]] && kill -0 "$(cat "$WORK/run/slurmctld.pid")" 2>/dev/null
}

show_logs() {
  local f
  if ctld_alive; then
    echo "----- squeue, sinfo"
    squeue -a -r -t all -o '%i %j %T %r %M' 2>&1
    sinfo -N -o '%N %T %c %m %E' 2>&1
  fi
  for f in "$WORK"/log/*; do
    # With -D a daemon writes its log file and the same lines on stderr
    # (*.out); the latter only matters when it died before opening the log.
    [[ $f == *.out && -s ${f%.out}.log ]] && continue
    [[ -f $f ]] || continue
    echo "----- $f (last 60 lines)"
    tail -n 60 "$f"
  done
  echo "-----"
}

jobid=""
on_exit() {
  local rc=$? i
  set +e
  ((rc == 0)) || show_logs
  # A job cut short by a failure must not outlive the test in slurmstepd.
  if [[ -n $jobid ]] && ctld_alive; then
    scancel "$jobid" 2>/dev/null
    for ((i = 0; i < 20; i++)); do
      [[ -z $(squeue -h -j "$jobid" -t PENDING,RUNNING,COMPLETING 2>/dev/null) ]] && break
      sleep 0.5
    done
  fi
  # Each job step has a slurmstepd of its own that outlives slurmd; wait for the
  # last ones to finish (each keeps a socket NODE_JOB.STEP in the spool folder).
  for ((i = 0; i < 40; i++)); do
    compgen -G "$WORK/spool/${node}_*" >/dev/null || break
    sleep 0.25
  done
  [[ -d $WORK/run ]] && stop_daemons
  if ((rc == 0)); then
    [[ ${KEEP:-0} == 1 ]] || rm -rf "$WORK"
    log "PASS ($((SECONDS - started)) s)"
  else
    log "FAIL (exit $rc; files kept in $WORK)"
  fi
  exit "$rc"
}

# One run at a time: a second one would stop the first one's daemons. The
# daemons are started without fd 9, so the lock goes with this shell.
exec 9>"$WORK.lock"
flock -w 10 9 || fail "another run holds $WORK.lock"

# $WORK is wiped, so it must be a folder this script made (or none at all).
if [[ -e $WORK && ! -e $WORK/.test-cluster ]] && [[ -n $(ls -A "$WORK" 2>/dev/null) ]]; then
  fail "$WORK exists and was not made by this script; remove it or set TEST_CLUSTER_DIR"
fi
[[ -d $WORK/run ]] && stop_daemons
rm -rf "$WORK"
mkdir -p "$WORK"/{run,log,state,spool,out}
touch "$WORK/.test-cluster"
trap on_exit EXIT
trap 'exit 130' INT TERM

# ------------------------------------------------------------------- munge
# Slurm signs every message with munge, against the machine's munged on its
# usual socket. A munged that already answers is used as it is.
if munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1; then
  log "munged is running already; using it"
else
  if [[ ! -s /etc/munge/munge.key ]]; then
    log "creating /etc/munge/munge.key"
    install -d -o munge -g munge -m 700 /etc/munge
    dd if=/dev/urandom of=/etc/munge/munge.key bs=1024 count=1 status=none
  fi
  chown munge:munge /etc/munge/munge.key
  chmod 400 /etc/munge/munge.key
  # /run is often a fresh tmpfs in a container: the package's folders are gone.
  install -d -o munge -g munge -m 755 /run/munge
  install -d -o munge -g munge -m 700 /var/lib/munge /var/log/munge
  runuser -u munge -- /usr/sbin/munged 9>&-
  for ((i = 0; i < 50; i++)); do
    munge -n </dev/null 2>/dev/null | unmunge >/dev/null 2>&1 && break
    sleep 0.1
  done
  munge -n </dev/null | unmunge >/dev/null || fail "munged does not answer"
  if cp /run/munge/munged.pid "$WORK/run/munged.pid" 2>/dev/null; then
    log "munged started"
  else
    log "munged started, but without /run/munge/munged.pid it will be left running"
  fi
fi

# ------------------------------------------------------------- slurm.conf
# The node is described as slurmd sees it; a node that reports less than its
# configuration says would be drained. Memory is not scheduled (CR_CPU), so a
# small RealMemory that any machine has is enough.
hw=$(SLURM_CONF=/dev/null slurmd -C 2>/dev/null | head -n 1 || true)
field() { sed -n "s/.* $1=\([0-9]*\).*/\1/p" <<<"$hw"; }
cpus=$(field CPUs)
if [[ -n $cpus ]]; then
  topology="CPUs=$cpus Boards=$(field Boards) SocketsPerBoard=$(field SocketsPerBoard)"
  topology+=" CoresPerSocket=$(field CoresPerSocket) ThreadsPerCore=$(field ThreadsPerCore)"
else
  topology="CPUs=$(nproc)"
fi
mem=$(field RealMemory)
mem=$(( ${mem:-0} > 0 && ${mem:-0} < 1000 ? mem : 1000 ))

export SLURM_CONF=$WORK/slurm.conf
cat >"$SLURM_CONF" <<EOF
# Written by scripts/test-cluster.sh for one test run; not for real use.
ClusterName=mechgraph-test
# The node name with a fixed address, so that no name lookup is needed.
SlurmctldHost=$node(127.0.0.1)
SlurmctldPort=$SLURMCTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
StateSaveLocation=$WORK/state
SlurmdSpoolDir=$WORK/spool
SlurmctldPidFile=$WORK/run/slurmctld.daemon.pid
SlurmdPidFile=$WORK/run/slurmd.daemon.pid
SlurmctldLogFile=$WORK/log/slurmctld.log
SlurmdLogFile=$WORK/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
# No cgroups, no accounting: neither is there in a plain container.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
MailProg=/bin/true
SelectType=select/cons_tres
SelectTypeParameters=CR_CPU
ReturnToService=2
# Finished jobs stay visible to squeue -t all for the whole test.
MinJobAge=3600
NodeName=$node NodeAddr=127.0.0.1 $topology RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=ALL Default=YES MaxTime=INFINITE State=UP
EOF

# ---------------------------------------------------------- Slurm daemons
log "starting slurmctld and slurmd (node $node: $topology RealMemory=$mem)"
slurmctld -D -f "$SLURM_CONF" >"$WORK/log/slurmctld.out" 2>&1 9>&- &
echo $! >"$WORK/run/slurmctld.pid"
slurmd -D -f "$SLURM_CONF" -N "$node" >"$WORK/log/slurmd.out" 2>&1 9>&- &
echo $! >"$WORK/run/slurmd.pid"

state=""
for ((i = 0; i < NODE_TIMEOUT * 2; i++)); do
  for name in slurmctld slurmd; do
    kill -0 "$(cat "$WORK/run/$name.pid")" 2>/dev/null || fail "$name exited right after its start"
  done
  state=$(sinfo -h -n "$node" -o %T 2>/dev/null || true)
  [[ $state == idle ]] && break
  sleep 0.5
done
[[ $state == idle ]] || fail "node $node not idle after ${NODE_TIMEOUT} s (state: '${state:-no answer}')"
log "node $node is idle"

# ------------------------------------------------------------- job array
export MECHGRAPH SCENE SWEEP_ARGS OUTDIR=$WORK/out

submit() { # the test's own settings on top of the #SBATCH lines in the file
  sbatch --parsable --array=0-$((${#TASKS[@]} - 1)) --cpus-per-task=1 \
    --job-name=mechgraph-test --chdir="$WORK" --output="$WORK/log/job-%A_%a.out" \
    "$ROOT/examples/slurm/sweep.sbatch" | cut -d';' -f1
}

wait_job() { # JOBID: until no task is pending or running; all must be COMPLETED
  local id=$1 deadline=$((SECONDS + JOB_TIMEOUT)) states
  while :; do
    ctld_alive || fail "slurmctld died"
    states=$(squeue -h -r -j "$id" -t all -o %T) || fail "squeue failed"
    [[ -n $states ]] || fail "squeue does not know job $id"
    grep -Eqv '^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE|PREEMPTED)$' \
      <<<"$states" || break
    ((SECONDS < deadline)) || fail "job $id not finished after $JOB_TIMEOUT s"
    sleep 1
  done
  if grep -qv '^COMPLETED$' <<<"$states"; then fail "not every task of job $id completed"; fi
}

jobid=$(submit) || fail "sbatch failed"
log "submitted job array $jobid (${#TASKS[@]} tasks)"
t0=$SECONDS
wait_job "$jobid"
log "job $jobid finished in $((SECONDS - t0)) s"

parts=()
for t in "${TASKS[@]}"; do
  part=$OUTDIR/part-$t.csv
  [[ -s $part ]] || fail "missing $part"
  [[ ! -e $part.part ]] || fail "$part.part left behind"
  grep -Eq '"complete" *: *true' "$part.json" 2>/dev/null || fail "$part.json missing or not complete"
  parts+=("$part")
done

# Submitting again must keep the finished parts as they are.
sum_before=$(cat "${parts[@]}" | md5sum)
jobid=$(submit) || fail "sbatch failed"
log "submitted job array $jobid again (every task must find its part done)"
wait_job "$jobid"
[[ $(cat "${parts[@]}" | md5sum) == "$sum_before" ]] || fail "re-submitting changed the parts"
for t in "${TASKS[@]}"; do
  grep -q "complete already" "$WORK/log/job-${jobid}_$t.out" || fail "task $t of job $jobid did not skip its part"
done
jobid=""

# ------------------------------------------------------- merge and compare
read -r -a sweep_args <<<"$SWEEP_ARGS"
"$MECHGRAPH" -q merge "${parts[@]}" >"$WORK/merged.csv" || fail "mechgraph merge failed"
"$MECHGRAPH" -q sweep "$SCENE" "${sweep_args[@]}" --threads 1 >"$WORK/single.csv" \
  || fail "the sweep in one process failed"
rows=$(($(wc -l <"$WORK/single.csv") - 1))
cmp "$WORK/merged.csv" "$WORK/single.csv" || fail "merged shards differ from the sweep in one process"
log "merged ${#parts[@]} shards = the sweep in one process ($rows rows, byte for byte)"
