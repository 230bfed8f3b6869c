#!/bin/bash
# A one-node Slurm on this machine, for tests and trials of the scripts beside this one:
# munged, slurmctld and slurmd from Debian's packages (slurm-wlm, munge), run as the current
# user (root: Slurm's daemons need it), every file under DIR, no cgroups.
#
#   tools/slurm/local_cluster.sh start DIR   starts the daemons and waits until the node is idle;
#                                            then `export SLURM_CONF=DIR/slurm.conf` for sbatch
#   tools/slurm/local_cluster.sh stop DIR    stops them (and is safe to run twice)
#
# Exits non-zero with the reason (and the daemons' logs) when a daemon does not come up.
set -euo pipefail

command=${1:-}
dir=${2:-}
if [[ -z "$command" || -z "$dir" ]]; then
  echo "usage: $0 start|stop DIR" >&2
  exit 2
fi

stop() {
  for pid_file in "$dir"/slurmd.pid "$dir"/slurmctld.pid "$dir"/munged.pid; do
    if [[ -s "$pid_file" ]]; then
      pid=$(cat "$pid_file")
      kill "$pid" 2>/dev/null || true
      for _ in $(seq 50); do
        kill -0 "$pid" 2>/dev/null || break
        sleep 0.1
      done
      kill -9 "$pid" 2>/dev/null || true
      rm -f "$pid_file"
    fi
  done
}

fail() {
  echo "local_cluster: $1" >&2
  for log in "$dir"/munged.log "$dir"/slurmctld.log "$dir"/slurmd.log; do
    [[ -f "$log" ]] && { echo "--- $log (last lines)" >&2; tail -n 15 "$log" >&2; }
  done
  stop
  exit 1
}

# A TCP port nothing listens on, from the ephemeral range's lower neighbour.
free_port() {
  python3 -c 'import socket; s = socket.socket(); s.bind(("127.0.0.1", 0)); print(s.getsockname()[1]); s.close()'
}

if [[ "$command" == stop ]]; then
  stop
  exit 0
fi
[[ "$command" == start ]] || { echo "usage: $0 start|stop DIR" >&2; exit 2; }
for program in munged mungekey slurmctld slurmd sinfo; do
  command -v "$program" >/dev/null || fail "$program is not installed (Debian: slurm-wlm, munge)"
done
[[ "$(id -u)" == 0 ]] || fail "Slurm's daemons run as root here; this is uid $(id -u)"

mkdir -p "$dir/state" "$dir/spool" "$dir/munge"
chmod 700 "$dir/munge"
mungekey --create --keyfile="$dir/munge/munge.key" --force 2>/dev/null \
  || fail "mungekey could not create a key"
chmod 400 "$dir/munge/munge.key"
munged --force --socket="$dir/munge/munge.socket" --key-file="$dir/munge/munge.key" \
  --pid-file="$dir/munged.pid" --log-file="$dir/munged.log" --seed-file="$dir/munge/seed" \
  || fail "munged did not start"

host=$(hostname -s)
cpus=$(nproc)
cat > "$dir/slurm.conf" <<CONF
ClusterName=relief-local
SlurmctldHost=$host
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
CredType=cred/munge
AuthInfo=socket=$dir/munge/munge.socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/slurmctld.log
SlurmdLogFile=$dir/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
MpiDefault=none
ReturnToService=2
SchedulerType=sched/backfill
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
NodeName=$host CPUs=$cpus State=UNKNOWN
PartitionName=relief Nodes=$host Default=YES MaxTime=INFINITE State=UP OverSubscribe=YES
CONF
export SLURM_CONF="$dir/slurm.conf"
slurmctld -i -f "$SLURM_CONF" || fail "slurmctld did not start"
slurmd -f "$SLURM_CONF" || fail "slurmd did not start"
for _ in $(seq 300); do
  state=$(sinfo -h -o %T 2>/dev/null || true)
  if [[ "$state" == idle* ]]; then
    echo "local_cluster: node $host idle (SLURM_CONF=$SLURM_CONF)"
    exit 0
  fi
  sleep 0.2
done
fail "the node did not become idle within 60 s (sinfo: ${state:-no answer})"
