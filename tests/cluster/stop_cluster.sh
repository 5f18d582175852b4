#!/usr/bin/env bash
# Stops the private cluster of start_cluster.sh DIR: cancels its jobs, ends slurmd, slurmctld and munged by
# their pid files (TERM, then KILL after 10 s), then removes DIR (unless --keep). Safe to run twice or on a
# half-started cluster; it never touches a daemon it did not start (only the pids in DIR's pid files, and
# only while their command line names DIR's config or socket).
# Usage: stop_cluster.sh DIR [--keep]
set -uo pipefail
dir=$1 keep=${2:-}
[[ -d $dir ]] || exit 0

# Jobs first, so that their steps end with them (bounded: slurmctld may be gone already).
if [[ -f $dir/slurm.conf && -f $dir/slurmctld.pid ]]; then
  SLURM_CONF=$dir/slurm.conf timeout 10 scancel --full --quiet --user=root >/dev/null 2>&1 || true
fi

# ours PIDFILE: the pid in it, if that process is one of ours (its command line names DIR).
ours() {
  local pid
  pid=$(cat "$1" 2>/dev/null) || return 1
  [[ $pid =~ ^[0-9]+$ ]] && [[ -r /proc/$pid/cmdline ]] || return 1
  tr '\0' ' ' < "/proc/$pid/cmdline" | grep -qF -- "$dir" || return 1
  echo "$pid"
}
# stop DAEMON...: SIGTERM to each, then wait for all (each takes 1-2 s to shut down).
stop() {
  local daemon pid pids=()
  for daemon in "$@"; do
    pid=$(ours "$dir/$daemon.pid") && kill -TERM "$pid" 2>/dev/null && pids+=("$daemon:$pid")
  done
  for entry in "${pids[@]}"; do
    pid=${entry#*:}
    for _ in $(seq 1 100); do kill -0 "$pid" 2>/dev/null || break; sleep 0.1; done
    if kill -0 "$pid" 2>/dev/null; then
      echo "stop_cluster: ${entry%%:*} ($pid) ignores SIGTERM for 10 s: SIGKILL" >&2
      kill -KILL "$pid" 2>/dev/null
    fi
  done
}
stop slurmd slurmctld
stop munged  # last: the SLURM daemons use it until they end
# slurmstepd of steps that outlived their job (started by our slurmd: their command line has no DIR, but
# their spool does): ended by the pids slurmd's spool lists.
for sock in "$dir"/spool/*_*.*; do
  [[ -S $sock ]] || continue
  # The spool holds one socket per step (NODE_JOB.STEP); a step's slurmstepd has it open.
  for pid in $(fuser "$sock" 2>/dev/null); do kill -KILL "$pid" 2>/dev/null || true; done
done
[[ $keep == --keep ]] || rm -rf "$dir"
