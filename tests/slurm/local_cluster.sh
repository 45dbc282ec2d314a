# A throwaway one-node Slurm cluster in a private folder, for the Slurm test and benchmark (source
# this file, bash). munged runs with a generated key, slurmctld and slurmd in the foreground (as
# children of the caller) with a generated slurm.conf on free ports; SLURM_CONF points at it, so
# the client commands (sbatch, squeue, scancel) talk to this cluster only. Nothing in /etc is read
# or touched.
#
#   local_cluster_missing         prints why no cluster can start here (nothing: it can)
#   local_cluster_start FOLDER    starts the cluster in FOLDER/cluster (FOLDER must exist);
#                                 returns 1, saying why, if the node does not come up
#   local_cluster_stop            cancels every job of the cluster, stops the daemons by the pids
#                                 in their pid files (never by name: other Slurm or munge
#                                 processes may run on the machine) and removes FOLDER/cluster
#   local_cluster_logs            prints the end of the daemons' logs (for a failure)

local_cluster_missing() {
  local c
  for c in munged slurmctld slurmd sbatch squeue scancel scontrol sinfo; do
    command -v $c >/dev/null || { echo "$c is not installed (scripts/setup.sh --tests installs slurm-wlm and munge)"; return; }
  done
  [ "$(id -u)" -eq 0 ] || echo "slurmd needs root to start jobs as their user"
}

_local_cluster_free_port() {
  local p
  for _ in $(seq 100); do
    p=$((20000 + RANDOM % 40000))
    (exec 3<>"/dev/tcp/127.0.0.1/$p") 2>/dev/null || { echo "$p"; return 0; }
  done
  return 1
}

local_cluster_start() {
  LOCAL_CLUSTER=$1/cluster
  local S=$LOCAL_CLUSTER
  mkdir -p "$S/state" "$S/spool" "$S/log" "$S/munge/run"
  # munged wants every folder above its socket searchable by all (mktemp -d makes 0700).
  chmod 755 "$1" "$S" "$S/munge" "$S/munge/run"
  export SLURM_CONF=$S/slurm.conf
  dd if=/dev/urandom of="$S/munge/munge.key" bs=1024 count=1 2>/dev/null
  chmod 600 "$S/munge/munge.key"
  munged --key-file="$S/munge/munge.key" --socket="$S/munge/run/munge.socket" \
    --pid-file="$S/munge/munged.pid" --log-file="$S/munge/munged.log" --seed-file="$S/munge/seed" ||
    { echo "munged did not start" >&2; return 1; }
  local ctld_port slurmd_port host
  ctld_port=$(_local_cluster_free_port) && slurmd_port=$(_local_cluster_free_port) ||
    { echo "no free port" >&2; return 1; }
  [ "$ctld_port" != "$slurmd_port" ] || slurmd_port=$((ctld_port + 1))
  host=$(hostname -s)
  cat >"$S/slurm.conf" <<EOF
ClusterName=limntest
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
AuthType=auth/munge
AuthInfo=socket=$S/munge/run/munge.socket
CredType=cred/munge
StateSaveLocation=$S/state
SlurmdSpoolDir=$S/spool
SlurmctldPidFile=$S/slurmctld.pid
SlurmdPidFile=$S/slurmd.pid
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
SchedulerType=sched/builtin
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
ReturnToService=2
MpiDefault=none
JobAcctGatherType=jobacct_gather/none
SlurmctldLogFile=$S/log/slurmctld.log
SlurmdLogFile=$S/log/slurmd.log
KillWait=5
NodeName=$host NodeAddr=127.0.0.1 CPUs=$(nproc) State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
  slurmctld -D >"$S/log/slurmctld.out" 2>&1 &
  for _ in $(seq 50); do sinfo -h >/dev/null 2>&1 && break; sleep 0.2; done
  slurmd -D >"$S/log/slurmd.out" 2>&1 &
  for _ in $(seq 100); do [ "$(sinfo -h -o %t 2>/dev/null)" = idle ] && break; sleep 0.2; done
  [ "$(sinfo -h -o %t 2>/dev/null)" = idle ] || { echo "the node did not come up: $(sinfo -h 2>&1)" >&2; return 1; }
  echo "local cluster: one node, $(nproc) CPUs, ports $ctld_port and $slurmd_port" >&2
}

local_cluster_logs() {
  local l
  for l in "$LOCAL_CLUSTER"/log/*.log "$LOCAL_CLUSTER"/log/*.out; do
    [ -s "$l" ] && { echo "--- $l (last lines)"; tail -n 15 "$l"; }
  done >&2
}

# Whether process $1 still runs (a daemon started here lingers as a zombie until waited for).
_local_cluster_running() {
  local pid comm state
  { read -r pid comm state _ <"/proc/$1/stat"; } 2>/dev/null || return 1
  [ "$state" != Z ]
}

local_cluster_stop() {
  local S=${LOCAL_CLUSTER:-}
  [ -n "$S" ] && [ -d "$S" ] || return 0
  # Jobs first: their processes (slurmstepd, the tasks) would outlive slurmd. Every job of this
  # private cluster is the caller's.
  if [ -s "$S/slurmctld.pid" ]; then
    squeue -h -o %A 2>/dev/null | sort -u | xargs -r scancel 2>/dev/null || true
    for _ in $(seq 50); do [ -z "$(squeue -h 2>/dev/null)" ] && break; sleep 0.2; done
  fi
  local pids="" f p alive
  for f in "$S/slurmd.pid" "$S/slurmctld.pid" "$S/munge/munged.pid"; do [ -s "$f" ] && pids="$pids $(cat "$f")"; done
  for p in $pids; do kill "$p" 2>/dev/null || true; done
  for _ in $(seq 50); do
    alive=
    for p in $pids; do _local_cluster_running "$p" && alive=1; done
    [ -z "$alive" ] && break
    sleep 0.2
  done
  for p in $pids; do kill -9 "$p" 2>/dev/null || true; done
  for p in $pids; do wait "$p" 2>/dev/null || true; done # the daemons started here, not the caller's other children
  rm -rf "$S"
}
