#!/usr/bin/env bash
# The experiments on a real SLURM cluster: a private one-node cluster (start_cluster.sh) under a temporary
# folder, stopped again however the test ends.
#  1. The explosion's miniature through its Make target, locally and inside an allocation (salloc, every run
#     launched by srun as a step of it): the same tables byte for byte (less the provenance line with its
#     time), the same runs (h5diff without /provenance).
#  2. scripts/slurm/experiment.sbatch in miniature: the job array over seeds, then the analysis after it
#     (--dependency=afterok): the same results again.
#  3. The time limit: experiment.sbatch's task for one seed of a larger disc (a dem-run of about 90 s) as a job
#     of --time=1 --signal=TERM@20; the signal stops the run with a checkpoint, the task requeues itself, the
#     next part continues the run, and the run equals an uninterrupted local one; its provenance lists the one
#     continuation.
# Exit 77 (skip) when the cluster cannot run here.
# Usage: cluster.sh SOURCE_DIR BUILD_DIR WORK_DIR [CELLS]   (CELLS: the time-limit run's disc, default 20000)
set -euo pipefail
src=$1 build=$2 work=$3 cells=${4:-20000}
here=$(cd "$(dirname "$0")" && pwd)
bin=$build/tools
rm -rf "$work" && mkdir -p "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
say() { echo "[${SECONDS}s] $*"; }
for tool in dem-run mesh-gen fragment-count; do [[ -x $bin/$tool ]] || fail "no $bin/$tool"; done
command -v h5diff >/dev/null || fail "h5diff not found (hdf5-tools)"

# Clusters of earlier runs of this test that were killed before their trap ran (the owner is gone).
for old in /tmp/fracture-cluster.*; do
  [[ -f $old/owner.pid ]] || continue
  kill -0 "$(cat "$old/owner.pid")" 2>/dev/null || bash "$here/stop_cluster.sh" "$old"
done

cluster=$(mktemp -d /tmp/fracture-cluster.XXXXXX)
echo $$ > "$cluster/owner.pid"
steps_before=$(pgrep -x slurmstepd | sort || true)
ref_pid=
cleanup() {
  local status=$?
  set +e
  [[ -n $ref_pid ]] && kill -- -"$ref_pid" 2>/dev/null && wait "$ref_pid" 2>/dev/null
  # The daemons' logs, for a failure (the cluster's folder is removed).
  [[ $status -eq 0 || $status -eq 77 ]] || cp -r "$cluster/log" "$work/cluster-logs" 2>/dev/null
  bash "$here/stop_cluster.sh" "$cluster"
  local left
  left=$(pgrep -af -- "$cluster")
  # (A step daemon already dead, a zombie its killed parent left to init, is not a process left running.)
  left+=$(comm -13 <(echo "$steps_before") <(pgrep -x slurmstepd | sort) | xargs -r -n1 ps -o pid=,stat=,args= -p |
          awk '$2 !~ /^Z/')
  if [[ -n $left ]]; then
    echo "FAIL: processes of the cluster left behind: $left" >&2
    status=1
  fi
  exit "$status"
}
trap cleanup EXIT
trap 'exit 130' INT TERM

set +e
bash "$here/start_cluster.sh" "$cluster"
rc=$?
set -e
[[ $rc -eq 77 ]] && exit 77
[[ $rc -eq 0 ]] || fail "start_cluster.sh: exit $rc"
source "$cluster/env.sh"
export STEP_LOG

# job_field JOB FIELD: a field of scontrol's record of the job (finished jobs stay MinJobAge = 10 min).
job_field() { scontrol -o show job "$1" | tr ' ' '\n' | awk -F= -v k="$2" '$1 == k { print substr($0, length(k) + 2); exit }'; }
# wait_gone JOB SECONDS: until the job (every task of an array) has left the queue.
wait_gone() {
  local deadline=$((SECONDS + $2))
  while [[ -n $(squeue -h -j "$1" 2>/dev/null) ]]; do
    ((SECONDS < deadline)) || fail "job $1 still queued after $2 s: $(squeue -j "$1")"
    sleep 1
  done
}

# --- 1 and 2: the explosion's miniature, locally, in an allocation, as the job array ---------------------
# Every variant writes to the same RESULTS path and is then moved aside: the tables name their inputs' paths.
results=$work/results
mini=(-C "$src" -f Makefile.analysis MINI=1 NO_BUILD=1 BUILD="$build" RESULTS="$results" JOBS=1)
launch="srun -n1 -c1 bash $here/record_step.sh"

say "explosion (MINI) locally"
make "${mini[@]}" explosion > "$work/local.log" 2>&1 || { tail -n 20 "$work/local.log"; fail "make explosion (local)"; }
mv "$results" "$work/local"

say "explosion (MINI) in an allocation: salloc -n1 -c1, LAUNCH='srun -n1 -c1'"
STEP_LOG=$work/steps-salloc.txt
salloc -n1 -c1 --time=10 --job-name=salloc-explosion make "${mini[@]}" LAUNCH="$launch" explosion \
  > "$work/salloc.log" 2>&1 || { tail -n 20 "$work/salloc.log"; fail "salloc make explosion"; }
mv "$results" "$work/salloc"

say "scripts/slurm/experiment.sbatch (MINI): array over seeds 1-2, then the analysis"
STEP_LOG=$work/steps-array.txt
sbatch_args=(MINI=1 BUILD="$build" RESULTS="$results" LAUNCH="$launch")
array=$(cd "$src" && sbatch --parsable --array=1-2 --time=10 -o "$work/array-%A_%a.out" \
  scripts/slurm/experiment.sbatch "${sbatch_args[@]}")
analysis=$(cd "$src" && sbatch --parsable --dependency=afterok:"$array" --time=10 -o "$work/analysis-%j.out" \
  scripts/slurm/experiment.sbatch "${sbatch_args[@]}")
wait_gone "$array" 120
for task in 1 2; do
  state=$(job_field "${array}_$task" JobState)
  [[ $state == COMPLETED ]] || { cat "$work/array-${array}_$task.out"; fail "array task $task: $state"; }
done
wait_gone "$analysis" 120
state=$(job_field "$analysis" JobState)
[[ $state == COMPLETED ]] || { cat "$work/analysis-$analysis.out"; fail "analysis job: $state"; }
mv "$results" "$work/array"

# same_results A B: the same files; tables (CSV, text, Markdown) byte for byte but for the '# tool=' line of
# provenance (it holds the time and the inputs' uuids); every HDF5 file equal but for /provenance.
same_results() {
  local a=$1 b=$2 f
  diff <(cd "$a" && find . -type f | sort) <(cd "$b" && find . -type f | sort) || fail "$b: other files than $a"
  local tables=0 runs=0
  while IFS= read -r f; do
    cmp -s <(grep -v '^# tool=' "$a/$f") <(grep -v '^# tool=' "$b/$f") ||
      fail "$f differs: $(diff <(grep -v '^# tool=' "$a/$f") <(grep -v '^# tool=' "$b/$f") | head -n 5)"
    tables=$((tables + 1))
  done < <(cd "$a" && find . -type f \( -name '*.csv' -o -name '*.txt' -o -name '*.md' \) | sort)
  while IFS= read -r f; do
    h5diff -q --exclude-path /provenance "$a/$f" "$b/$f" || fail "$f differs (h5diff without /provenance)"
    runs=$((runs + 1))
  done < <(cd "$a" && find . -type f -name '*.h5' | sort)
  ((tables >= 10 && runs >= 20)) || fail "only $tables tables and $runs HDF5 files in $a"
  say "$b: $tables tables and $runs HDF5 files as $a"
}
same_results "$work/local" "$work/salloc"
same_results "$work/local" "$work/array"

# launched_by STEPS RESULTS JOBS...: every mesh and run of RESULTS was written by a step (srun) of one of
# JOBS, each by a step of its own, and nothing else was launched.
launched_by() {
  local steps=$1 dir=$2; shift 2
  local expected recorded
  expected=$(cd "$dir" && find . -name 'mesh-s*.h5' -o -name '*-s[0-9]*.h5' ! -name '*.frag.h5' ! -name 'frag-*' -o -name pulse.h5 |
    sed 's|^\./||' | sort)
  recorded=$(awk '{ print $4 }' "$steps" | sed "s|^$results/||" | sort)
  [[ $recorded == "$expected" ]] || fail "launched: $(echo $recorded); written: $(echo $expected)"
  awk -v jobs=" $* " '$2 !~ /^[0-9]+$/ || index(jobs, " " $1 " ") == 0 { print "not a step of jobs" jobs ": " $0; bad = 1 }
    END { exit bad }' "$steps" || fail "$steps: runs outside the jobs"
  [[ -z $(awk '{ print $1 "." $2 }' "$steps" | sort | uniq -d) ]] || fail "$steps: a step ran twice"
}
salloc_job=$(awk '{ print $1; exit }' "$work/steps-salloc.txt")
[[ $(job_field "$salloc_job" JobName) == salloc-explosion ]] || fail "job $salloc_job is not the allocation"
launched_by "$work/steps-salloc.txt" "$work/salloc" "$salloc_job"
launched_by "$work/steps-array.txt" "$work/array" "$(job_field "${array}_1" JobId)" "$(job_field "${array}_2" JobId)"
say "srun ran $(wc -l < "$work/steps-salloc.txt") steps in allocation $salloc_job and $(wc -l < "$work/steps-array.txt") in array $array"

# --- 3: the time limit -------------------------------------------------------------------------------
# experiment.sbatch's array task for seed 2 of a larger explosion: one run of about 90 s on one core (Release,
# 20000 cells; cells this fine need dt = auto), in a job of --time=1 --signal=TERM@20. slurmctld looks at
# time limits every 30 s: the signal comes 20-50 s before the end of the minute, 10-40 s into the job, long
# before the run ends. The run writes its checkpoint and ends, the task requeues itself, its next part
# continues the run. --checkpoint-every 0: a checkpoint only when a signal stops the run, so the one that
# exists came from the signal. Seed 2 of EX_SEEDS='1 2' with the scan on seed 1 only: no pulse, no scan runs.
if ! "$bin/dem-run" --help 2>&1 | grep -q -- --checkpoint-every; then
  say "SKIPPED the time-limit case: dem-run has no --checkpoint-every"
  exit 0
fi
tl=$work/timelimit
mkdir -p "$tl"
big=(BUILD="$build" EX_SEEDS="1 2" EX_SCAN_SEEDS=1 EX_PAIRS=3-4 EX_CELLS="$cells"
     EX_RUN_OPTIONS="--integrator.dt auto --stop.t_max 1.6e-3 --checkpoint-every 0")
say "time limit: the reference run locally, beside the job"
# In a session of its own: the trap ends make and its dem-run together.
setsid make -C "$src" -f Makefile.analysis NO_BUILD=1 JOBS=1 RESULTS="$tl/local" "${big[@]}" \
  "$tl/local/explosion/runs/3-4-s2.frag.h5" > "$tl/local.log" 2>&1 &
ref_pid=$!
job=$(cd "$src" && sbatch --parsable --array=2 --time=1 --signal=TERM@20 -o "$tl/job-%A_%a.out" \
  scripts/slurm/experiment.sbatch RESULTS="$tl/cluster" "${big[@]}")
out=$tl/job-${job}_2.out
run=$tl/cluster/explosion/runs/3-4-s2.h5
say "time limit: experiment.sbatch --array=2 --time=1 --signal=TERM@20: job $job"
deadline=$((SECONDS + 120))
until [[ $(job_field "${job}_2" Restarts) == 1 ]]; do
  state=$(job_field "${job}_2" JobState)
  [[ $state =~ ^(COMPLETED|FAILED|CANCELLED|TIMEOUT|NODE_FAIL|OUT_OF_MEMORY|BOOT_FAIL|DEADLINE|PREEMPTED)$ ]] &&
    { cat "$out"; fail "job $job ended ($state) without being requeued: not stopped by the time limit's signal (a run that finished first needs a larger t_max here)"; }
  ((SECONDS < deadline)) || { cat "$out"; fail "job $job not requeued after 120 s"; }
  sleep 1
done
say "time limit: job $job requeued ($(job_field "${job}_2" JobState), $(job_field "${job}_2" Reason))"
[[ -f $run.ckpt ]] || fail "requeued without a checkpoint"
[[ ! -e $run ]] || fail "the run exists before it finished"
# The continuation is to finish in one part (one resumption to check): a longer limit for the requeued job.
scontrol update JobId="${job}_2" TimeLimit=15
wait_gone "$job" 600  # (a loaded machine: the continuation alone takes 1-2 min on an idle core)
[[ $(job_field "${job}_2" JobState) == COMPLETED && $(job_field "${job}_2" ExitCode) == 0:0 ]] ||
  { cat "$out"; fail "job $job: $(job_field "${job}_2" JobState), exit $(job_field "${job}_2" ExitCode)"; }
wait "$ref_pid" || { tail -n 20 "$tl/local.log"; fail "the local reference run failed"; }
ref_pid=

grep '^experiment.sbatch:\|stopped by' "$out"
[[ $(grep -c '^experiment.sbatch: job .* part ' "$out") -eq 2 ]] || fail "$out: not two parts"
stopped=$(grep -o 'stopped by SIGTERM after step [0-9]*' "$out") || fail "$out: no run stopped by SIGTERM"
step=${stopped##* }
after=$(grep -o 'stopped by a signal after [0-9]* s' "$out" | awk '{ print $6 }')
[[ -n $after ]] || fail "$out: the task did not requeue itself"
# Before the limit itself (60 s): the --signal stopped it, not the limit's kill; and after some steps.
((after < 58)) || fail "stopped after $after s: by the time limit, not by its signal"
((step > 0)) || fail "stopped at step 0: nothing to continue"
[[ -f $run && ! -e $run.ckpt ]] || fail "after the run: $run missing or its checkpoint left"
for f in mesh-s2.h5 runs/3-4-s2.h5; do
  h5diff --exclude-path /provenance "$tl/local/explosion/$f" "$tl/cluster/explosion/$f" ||
    fail "$f: stopped and continued, it differs from the uninterrupted run"
done
# The fragments' /parameters name their input's path, which differs here.
h5diff --exclude-path /provenance --exclude-path /parameters "$tl/local/explosion/runs/3-4-s2.frag.h5" \
  "$tl/cluster/explosion/runs/3-4-s2.frag.h5" || fail "runs/3-4-s2.frag.h5: the fragments differ"
segments=$(h5dump -y -w 0 -d /provenance/segments/first_step "$run" | awk '/DATA \{/ { f = 1; next } f && /\}/ { f = 0 } f' | tr -d ' \n')
[[ $segments == "0,$step" ]] || fail "/provenance/segments/first_step is '$segments', expected 0,$step"
say "time limit: signalled $after s into the 1-minute job, at step $step; requeued, continued, equal to the local run"
say "ok"
