#!/bin/bash
# A real single-node Slurm cluster in a temporary folder (issue 26): writes a munge key and slurm.conf,
# starts munged, slurmctld and slurmd on this machine (as root: SlurmUser root), submits
# deploy/slurm/oitbench-array.sbatch as an array of 4 tasks each running `oitbench run --preset P --shard
# auto`, waits, and checks with tests/fleet/check_shards.py that the 4 CSVs together hold the unsharded
# run's cases, each once, with the same statuses. Everything it started is stopped on exit, failed or not.
# Usage: slurm_cluster.sh OITBENCH_EXE [PRESET] [RUN ARGS...]   Exit 77 (skipped) without slurm/munge or root.
set -euo pipefail
EXE=${1:?usage: slurm_cluster.sh OITBENCH_EXE [PRESET] [RUN ARGS...]}
PRESET=${2:-knowles2014-quick}
shift $(($# >= 2 ? 2 : 1))
ARGS="$*"
HERE=$(cd "$(dirname "$0")" && pwd)
ROOT=$(cd "$HERE/../.." && pwd)
TASKS=4

for tool in munged slurmctld slurmd sbatch sinfo scontrol; do
  command -v "$tool" >/dev/null || { echo "slurm_cluster: $tool not installed (apt-get install slurm-wlm munge): skipped"; exit 77; }
done
[ "$(id -u)" = 0 ] || { echo "slurm_cluster: needs root (slurmd runs jobs as their user): skipped"; exit 77; }

T=$(mktemp -d /tmp/oitbench-slurm.XXXXXX)
PIDS=()
cleanup() {
  local rc=$?
  for pid in "${PIDS[@]}"; do kill "$pid" 2>/dev/null || true; done
  for pid in "${PIDS[@]}"; do
    for _ in $(seq 50); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    kill -9 "$pid" 2>/dev/null || true
  done
  if [ "$rc" != 0 ]; then
    for log in "$T"/*.log "$T"/out/*.log; do [ -f "$log" ] && { echo "== $log"; tail -n 30 "$log"; }; done
  fi
  rm -rf "$T"
  exit "$rc"
}
trap cleanup EXIT
trap 'exit 1' INT TERM

free_port() { python3 -c 'import socket; s=socket.socket(); s.bind(("127.0.0.1",0)); print(s.getsockname()[1])'; }
HOST=$(hostname -s)
mkdir -p "$T/state" "$T/spool" "$T/out" "$T/munge"
chmod 755 "$T" "$T/munge"  # munged: its socket folder executable by all, writable by root only

# munge: its own key, socket and files in the folder (the machine's munged, if any, is left alone).
dd if=/dev/urandom of="$T/munge/munge.key" bs=1024 count=1 status=none
chmod 400 "$T/munge/munge.key"
munged --key-file="$T/munge/munge.key" --socket="$T/munge/munge.socket" --pid-file="$T/munge/munged.pid" \
  --log-file="$T/munged.log" --seed-file="$T/munge/munged.seed" --foreground &
PIDS+=($!)

cat >"$T/slurm.conf" <<CONF
ClusterName=oitbenchtest
SlurmctldHost=$HOST
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$(free_port)
SlurmdPort=$(free_port)
AuthType=auth/munge
AuthInfo=socket=$T/munge/munge.socket
CredType=cred/munge
StateSaveLocation=$T/state
SlurmdSpoolDir=$T/spool
SlurmctldPidFile=$T/slurmctld.pid
SlurmdPidFile=$T/slurmd.pid
SlurmctldLogFile=$T/slurmctld.log
SlurmdLogFile=$T/slurmd.log
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
MpiDefault=none
ReturnToService=2
SlurmdTimeout=60
NodeName=$HOST CPUs=$(nproc) State=UNKNOWN
PartitionName=test Nodes=$HOST Default=YES MaxTime=60 State=UP
CONF
export SLURM_CONF=$T/slurm.conf

for _ in $(seq 50); do [ -S "$T/munge/munge.socket" ] && break; sleep 0.1; done
slurmctld -D -i -f "$SLURM_CONF" >"$T/slurmctld.out" 2>&1 &
PIDS+=($!)
slurmd -D -f "$SLURM_CONF" -N "$HOST" >"$T/slurmd.out" 2>&1 &
PIDS+=($!)

state=""
for _ in $(seq 120); do
  state=$(sinfo -h -N -o %t 2>/dev/null | head -n1 || true)
  case "$state" in idle*|mix*) break ;; down*|drain*) scontrol update nodename="$HOST" state=resume 2>/dev/null || true ;; esac
  sleep 0.5
done
case "$state" in idle*|mix*) ;; *) echo "slurm_cluster: the node never came up (state '$state')"; exit 1 ;; esac
echo "slurm_cluster: node $HOST $state; submitting $TASKS tasks of $PRESET"

start=$(date +%s)
# The array job, as users submit it; each task runs one shard.
(cd "$T/out" && OITBENCH="$EXE" OITBENCH_PRESET="$PRESET" OITBENCH_OUT="$T/out" OITBENCH_ARGS="$ARGS" \
  sbatch --wait --export=ALL --array=0-$((TASKS - 1)) --time=30 "$ROOT/deploy/slurm/oitbench-array.sbatch")
echo "slurm_cluster: array done in $(($(date +%s) - start)) s"

# The whole grid in one run, here, for the comparison.
read -r -a EXTRA <<<"$ARGS"
"$EXE" run --preset "$PRESET" --no-progress --out "$T/whole.csv" "${EXTRA[@]}" 2>"$T/whole.log" || true
python3 "$HERE/check_shards.py" "$T/whole.csv" "$TASKS" "$T"/out/shard-*.csv
