#!/usr/bin/env bash
# Starts a private one-node SLURM cluster (munged, slurmctld, slurmd, all as root) entirely under DIR: its own
# munge key and socket, slurm.conf, state, spool, logs and pid files, on two free ports; nothing of the
# system's SLURM or munge is used or touched. Clients find it through DIR/env.sh (SLURM_CONF).
# Ends when the node answers `srun hostname` (at most 60 s). Stop it with stop_cluster.sh DIR.
# Exit 77 (CTest's skip code, printed reason) when the cluster cannot run here: not root, binaries missing,
# a daemon that does not start; what was started by then is stopped again.
# Usage: start_cluster.sh DIR   (DIR: a short path, e.g. from mktemp -d /tmp/…: a unix socket path is
# limited to 107 characters)
set -euo pipefail
dir=$1
here=$(cd "$(dirname "$0")" && pwd)
skip() {
  echo "SKIP: $*" >&2
  bash "$here/stop_cluster.sh" "$dir" --keep >/dev/null 2>&1 || true
  exit 77
}
[[ $(id -u) -eq 0 ]] || skip "the private SLURM cluster runs its daemons as root (uid $(id -u))"
for b in munged mungekey munge unmunge slurmctld slurmd sinfo srun salloc sbatch scontrol squeue ss free; do
  command -v "$b" >/dev/null || skip "$b not found (apt-get install slurm-wlm munge)"
done
mkdir -p "$dir"
dir=$(cd "$dir" && pwd)
[[ ${#dir} -le 80 ]] || skip "$dir: too long a path for the daemons' unix sockets"
mkdir -p "$dir/state" "$dir/spool" "$dir/log"
# munged refuses a socket directory that other users cannot reach, or that they can write to.
chmod 0755 "$dir"

# --- munge: a fresh key, a daemon of our own on its own socket ----------------------------------------
mungekey --create --keyfile "$dir/munge.key" 2>/dev/null ||
  dd if=/dev/urandom of="$dir/munge.key" bs=1024 count=1 status=none
chown root:root "$dir/munge.key" && chmod 0400 "$dir/munge.key"
munge_socket=$dir/munge.socket
munged --socket="$munge_socket" --key-file="$dir/munge.key" --pid-file="$dir/munged.pid" \
  --log-file="$dir/log/munged.log" --seed-file="$dir/munged.seed" 2>"$dir/log/munged.err" ||
  skip "munged does not start: $(cat "$dir/log/munged.err" "$dir/log/munged.log" 2>/dev/null | tail -n 5)"
munge --socket="$munge_socket" -n | unmunge --socket="$munge_socket" >/dev/null 2>&1 ||
  skip "the private munged does not validate its own credential"

# --- two free TCP ports in a high range ---------------------------------------------------------------
port_free() { ! ss -Htln "sport = :$1" 2>/dev/null | grep -q .; }
ctld_port=
for _ in $(seq 1 50); do
  p=$((20000 + RANDOM % 30000))
  if port_free "$p" && port_free $((p + 1)); then ctld_port=$p; break; fi
done
[[ -n $ctld_port ]] || skip "no two free ports found in 20000-50000"
slurmd_port=$((ctld_port + 1))

# --- slurm.conf: one node, one partition, no cgroups, no accounting, short timers ---------------------
host=$(hostname -s)
# nproc alone counts OMP_NUM_THREADS (1 in the tests' environment).
cpus=$(env -u OMP_NUM_THREADS -u OMP_THREAD_LIMIT nproc)
# What the jobs may use: the free memory less a margin for the daemons and the rest of the machine.
mem=$(free -m | awk '/^Mem:/ { m = int($7 * 0.8); print (m > 100 ? m : 100) }')
: > "$dir/plugstack.conf"  # no SPANK plugins (the system's plugstack.conf is not ours to read)
cat > "$dir/slurm.conf" <<EOF
# Written by tests/cluster/start_cluster.sh: a private one-node cluster under $dir.
ClusterName=fracture-test
SlurmctldHost=$host(127.0.0.1)
SlurmUser=root
SlurmdUser=root
SlurmctldPort=$ctld_port
SlurmdPort=$slurmd_port
AuthType=auth/munge
CredType=cred/munge
# cred_expire: also how long a requeued job waits before it may start again (default 120 s).
AuthInfo=cred_expire=10,socket=$munge_socket
StateSaveLocation=$dir/state
SlurmdSpoolDir=$dir/spool
SlurmctldPidFile=$dir/slurmctld.pid
SlurmdPidFile=$dir/slurmd.pid
SlurmctldLogFile=$dir/log/slurmctld.log
SlurmdLogFile=$dir/log/slurmd.log
SlurmctldDebug=info
SlurmdDebug=info
PlugStackConfig=$dir/plugstack.conf
# No cgroups: processes tracked through /proc, tasks not bound.
ProctrackType=proctrack/linuxproc
TaskPlugin=task/none
JobAcctGatherType=jobacct_gather/none
AccountingStorageType=accounting_storage/none
JobCompType=jobcomp/none
MpiDefault=none
SwitchType=switch/none
SelectType=select/cons_tres
SelectTypeParameters=CR_Core
# The node's line below is the truth (not what slurmd detects): it never drains for a topology mismatch.
SlurmdParameters=config_overrides
# First in, first out, started on submission (no backfill pass to wait for); the full queue every 2 s
# (default 60 s): what starts a requeued job once its begin time (cred_expire above) has passed.
SchedulerType=sched/builtin
SchedulerParameters=sched_interval=2
ReturnToService=2
# Time limits: no grace beyond the limit, SIGKILL 5 s after the SIGTERM of the limit. slurmctld looks at
# time limits every 30 s (compiled in, not a setting): --signal=SIG@N arrives N to N + 30 s before the limit,
# the limit's own SIGTERM up to 30 s after it.
OverTimeLimit=0
KillWait=5
MessageTimeout=10
InactiveLimit=0
# Finished jobs stay visible to scontrol for 10 minutes (the test reads their state and exit code).
MinJobAge=600
NodeName=$host NodeAddr=127.0.0.1 CPUs=$cpus RealMemory=$mem State=UNKNOWN
PartitionName=debug Nodes=$host Default=YES MaxTime=INFINITE State=UP
EOF
export SLURM_CONF=$dir/slurm.conf
printf 'export SLURM_CONF=%q\n' "$SLURM_CONF" > "$dir/env.sh"

# --- the daemons: each forks, writes its pid file, logs under DIR/log -----------------------------------
slurmctld -c -i -f "$SLURM_CONF" 2>"$dir/log/slurmctld.err" ||
  skip "slurmctld does not start: $(tail -n 5 "$dir/log/slurmctld.err" "$dir/log/slurmctld.log" 2>/dev/null)"
slurmd -f "$SLURM_CONF" 2>"$dir/log/slurmd.err" ||
  skip "slurmd does not start: $(tail -n 5 "$dir/log/slurmd.err" "$dir/log/slurmd.log" 2>/dev/null)"

# --- ready: the node idle and a step that runs (bounded: 60 s) ----------------------------------------
deadline=$((SECONDS + 60))
until [[ $(sinfo -h -n "$host" -o %t 2>/dev/null) == idle ]]; do
  ((SECONDS < deadline)) || skip "the node is not idle after 60 s: $(sinfo -h -o '%t %E' 2>&1 | head -n 1);
  slurmctld: $(tail -n 3 "$dir/log/slurmctld.log" 2>/dev/null); slurmd: $(tail -n 3 "$dir/log/slurmd.log" 2>/dev/null)"
  sleep 0.5
done
answer=$(timeout $((deadline - SECONDS > 5 ? deadline - SECONDS : 5)) srun -n1 -c1 hostname 2>"$dir/log/srun.err") ||
  skip "srun -n1 -c1 hostname fails: $(tail -n 3 "$dir/log/srun.err"); slurmd: $(tail -n 3 "$dir/log/slurmd.log" 2>/dev/null)"
echo "cluster up under $dir: node $answer, $cpus CPUs, ${mem} MB, slurmctld port $ctld_port, slurmd port $slurmd_port"
