#!/usr/bin/env bash
# A single-node Slurm on localhost for the sweep tests: munged + slurmctld + slurmd from
# Debian's packages, every file under one directory ($ASTER_NL_SLURM_DIR, default
# /tmp/aster-nl-slurm), nothing written to /etc, its own ports and munge socket, so it
# neither needs nor disturbs a Slurm or munge already on the machine.
#
#   .ci/slurm-setup.sh          install if needed, start what is not running, wait until
#                               the node takes jobs; prints SLURM_CONF=... last
#   .ci/slurm-setup.sh --stop   stop the daemons this script started (by their pid files)
#
# Clients (sbatch, squeue, aster-nl sweep) find this cluster through
# SLURM_CONF=$ASTER_NL_SLURM_DIR/slurm.conf. Idempotent: a second call checks the running
# cluster and returns. On any failure it prints the daemons' logs and exits non-zero.
# Runs as root (CI does); the jobs run as root too.
set -euo pipefail

DIR=${ASTER_NL_SLURM_DIR:-/tmp/aster-nl-slurm}
WAIT=${ASTER_NL_SLURM_WAIT:-60}        # seconds to wait for each daemon
CTLD_PORT=${ASTER_NL_SLURM_CTLD_PORT:-16817}
SLURMD_PORT=${ASTER_NL_SLURM_SLURMD_PORT:-16818}
CONF=$DIR/slurm.conf
MUNGE_SOCKET=$DIR/munge-socket/munge.socket.2
NODE=localhost

log() { echo "slurm-setup: $*" >&2; }

dump_logs() {
  for f in "$DIR"/log/*.log; do
    [ -f "$f" ] || continue
    echo "----- $f (last 40 lines)" >&2
    tail -n 40 "$f" >&2 || true
  done
}

die() {
  log "FAILED: $*"
  dump_logs
  exit 1
}

alive() { # pidfile: the process exists and is not a zombie (a container's init may not
          # reap the daemons it inherits, and kill -0 succeeds on a zombie)
  local pid state
  [ -f "$1" ] || return 1
  pid=$(cat "$1")
  [ -r "/proc/$pid/stat" ] || return 1
  state=$(sed 's/.*) //' "/proc/$pid/stat" | cut -d' ' -f1)
  [ "$state" != "Z" ]
}

stop() {
  for d in slurmd slurmctld munged; do
    local pf=$DIR/run/$d.pid
    if alive "$pf"; then
      # Read once: a daemon removes its own pid file as it exits.
      local pid
      pid=$(cat "$pf" 2>/dev/null) || continue
      log "stopping $d (pid $pid)"
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 1 50); do [ -d "/proc/$pid" ] || break; sleep 0.1; done
    fi
    rm -f "$pf"
  done
}

if [ "${1:-}" = "--stop" ]; then
  stop
  exit 0
fi

# 1. Packages (Debian's; the versions of the distribution).
if ! command -v slurmctld >/dev/null || ! command -v slurmd >/dev/null \
   || ! command -v sbatch >/dev/null || ! command -v munged >/dev/null; then
  log "installing slurmctld, slurmd, slurm-client and munge"
  export DEBIAN_FRONTEND=noninteractive
  timeout 600 apt-get update -qq || die "apt-get update failed"
  timeout 900 apt-get install -y -qq --no-install-recommends \
    slurmctld slurmd slurm-client munge >/dev/null || die "apt-get install failed"
fi

mkdir -p "$DIR"/{munge,munge-socket,state,spool,log,run}
chmod 700 "$DIR/munge"        # the key
chmod 755 "$DIR/munge-socket" # the socket: clients need to reach it

# 2. munge: a key and a daemon of our own.
if ! alive "$DIR/run/munged.pid"; then
  if [ ! -s "$DIR/munge/munge.key" ]; then
    dd if=/dev/urandom of="$DIR/munge/munge.key" bs=1024 count=1 status=none
  fi
  chmod 400 "$DIR/munge/munge.key"
  rm -f "$MUNGE_SOCKET" "$MUNGE_SOCKET.lock"
  log "starting munged"
  # --force: the socket lives under /tmp, whose permissions munged would otherwise query.
  munged --force --socket="$MUNGE_SOCKET" --key-file="$DIR/munge/munge.key" \
    --pid-file="$DIR/run/munged.pid" --log-file="$DIR/log/munged.log" \
    --seed-file="$DIR/munge/munged.seed" \
    || die "munged did not start"
fi
for _ in $(seq 1 "$((WAIT * 10))"); do
  [ -S "$MUNGE_SOCKET" ] && break
  sleep 0.1
done
munge -n --socket="$MUNGE_SOCKET" | unmunge --socket="$MUNGE_SOCKET" >/dev/null \
  || die "munge does not answer on $MUNGE_SOCKET"

# 3. The cluster's configuration: one node (this machine, as 'localhost'), one partition.
# slurmctld only runs on the host SlurmctldHost names, hence the real short host name.
HOST=$(hostname -s)
CPUS=$(nproc)
MEM_MB=$(awk '/MemTotal/ {print int($2 / 1024 * 0.8)}' /proc/meminfo)
NEW_CONF=$(cat <<EOF
# Written by aster-nl's .ci/slurm-setup.sh: a single-node cluster for tests.
ClusterName=asternl
SlurmctldHost=$HOST(127.0.0.1)
SlurmctldPort=$CTLD_PORT
SlurmdPort=$SLURMD_PORT
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$MUNGE_SOCKET
StateSaveLocation=$DIR/state
SlurmdSpoolDir=$DIR/spool
SlurmctldPidFile=$DIR/run/slurmctld.pid
SlurmdPidFile=$DIR/run/slurmd.pid
SlurmctldLogFile=$DIR/log/slurmctld.log
SlurmdLogFile=$DIR/log/slurmd.log
# No cgroups, no accounting: nothing a container or a CI machine may lack.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MaxArraySize=1001
MinJobAge=300
SlurmctldTimeout=30
SlurmdTimeout=30
NodeName=$NODE NodeAddr=127.0.0.1 CPUs=$CPUS RealMemory=$MEM_MB State=UNKNOWN
PartitionName=debug Nodes=$NODE Default=YES MaxTime=INFINITE State=UP
EOF
)
if alive "$DIR/run/slurmctld.pid" && [ -f "$CONF" ] && [ "$(cat "$CONF")" != "$NEW_CONF" ]; then
  log "the configuration changed: restarting the daemons"
  stop
  exec bash "$0" "$@"
fi
printf '%s\n' "$NEW_CONF" > "$CONF"
export SLURM_CONF=$CONF

# 4. The daemons.
if ! alive "$DIR/run/slurmctld.pid"; then
  log "starting slurmctld"
  # -i: ignore state files a previous run left that this one cannot read.
  slurmctld -f "$CONF" -i || die "slurmctld did not start"
fi
ok=""
for _ in $(seq 1 "$WAIT"); do
  if timeout 10 scontrol ping 2>/dev/null | grep -q "is UP"; then ok=1; break; fi
  sleep 1
done
[ -n "$ok" ] || die "slurmctld does not answer (scontrol ping)"

if ! alive "$DIR/run/slurmd.pid"; then
  log "starting slurmd"
  slurmd -f "$CONF" -N "$NODE" || die "slurmd did not start"
fi
ok=""
for _ in $(seq 1 "$WAIT"); do
  state=$(timeout 10 sinfo -h -n "$NODE" -o %T 2>/dev/null || true)
  case "$state" in
    idle*|mixed*|allocated*|completing*) ok=1; break ;;
    down*|drain*) timeout 10 scontrol update nodename="$NODE" state=resume 2>/dev/null || true ;;
  esac
  sleep 1
done
[ -n "$ok" ] || die "node $NODE did not become idle (state: ${state:-none})"

# 5. A real job through it, end to end.
out=$(timeout "$WAIT" srun -N1 -n1 -t 1 echo slurm-ok 2>&1) || die "srun failed: $out"
[ "$out" = "slurm-ok" ] || die "srun printed '$out', expected slurm-ok"
log "single-node Slurm ready ($(sinfo -h -o '%P %D %T %c CPUs'))"
echo "SLURM_CONF=$CONF"
