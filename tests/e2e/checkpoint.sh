#!/usr/bin/env bash
# End-to-end checks of checkpoints and resume (dem-run, rubber-run): a run killed with SIGKILL at a random step
# and continued, killed again and continued on other thread counts, ends in the uninterrupted run's output
# (h5diff outside /provenance), its provenance listing the segments; SIGTERM and SIGINT write a checkpoint and end
# the run by the signal; a checkpoint of another run is refused (--resume) or replaced (found by itself).
# Usage: checkpoint.sh BIN_DIR SCENES_DIR WORK_DIR CASE [SEED]
set -euo pipefail
bin=$1 scenes=$2 work=$3 case=$4
RANDOM=${5:-$(date +%s)}  # the kill steps: random, reproducible from the seed printed here
echo "seed $RANDOM"
source "$(dirname "$0")/lib.sh"
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# Waits (up to 60 s), while `pid` lives, until `file` exists as another file than inode `old`.
wait_for() {
  local file=$1 pid=$2 old=${3:-none}
  for _ in $(seq 600); do
    [[ -e $file && $(stat -c %i "$file") != "$old" ]] && return 0
    kill -0 "$pid" 2>/dev/null || return 1
    sleep 0.1
  done
  return 1
}

# Waits until the run `pid` writing `output` is in its time loop: its temporary output exists (a stop signal
# before that ends the run at once, with nothing to save), and a moment more.
in_time_loop() {
  local pid=$1 output=$2
  for _ in $(seq 600); do
    compgen -G ".$output.tmp-*" >/dev/null && { sleep 0.3; return 0; }
    kill -0 "$pid" 2>/dev/null || fail "the run ended before its time loop"
    sleep 0.1
  done
  fail "the run did not reach its time loop in 60 s"
}

# Runs "$@ -o part.h5 --checkpoint-every K" (K random) until its first checkpoint exists, waits a random
# while longer and kills it with SIGKILL: the run is left at a random step past a random checkpoint.
kill_at_random_step() {
  local every=$((50 + RANDOM % 200)) pause old=none
  pause=$(printf '0.%02d' $((RANDOM % 15)))
  [[ -e part.h5.ckpt ]] && old=$(stat -c %i part.h5.ckpt)
  "$@" -o part.h5 --checkpoint-every "$every" -q 2>/dev/null &
  local pid=$!
  wait_for part.h5.ckpt "$pid" "$old" || fail "no checkpoint appeared: $*"
  sleep "$pause"
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  [[ ! -e part.h5 ]] || fail "the killed run finished before it was killed; make the run longer"
  local step
  step=$(h5dump -a /step part.h5.ckpt | awk '/\(0\):/ { print $2 }')
  echo "killed ($*) ${pause} s after its first new checkpoint (every $every steps); the checkpoint is at step $step"
}

# Kills the run twice at random steps and continues it each time on another thread count; the output must be
# the uninterrupted run's, with three segments in its provenance.
kill_twice_and_compare() {
  "$@" -o full.h5 -q
  kill_at_random_step "$@" --threads 2
  kill_at_random_step "$@" --threads 3
  "$@" -o part.h5 --threads 1 -q
  [[ -s part.h5 ]] || fail "the continued run left no output"
  [[ ! -e part.h5.ckpt ]] || fail "the checkpoint outlived the finished run"
  [[ -z $(ls -A | grep '\.tmp-' || true) ]] || fail "temporary files left: $(ls -A)"
  h5diff --exclude-path /provenance full.h5 part.h5 || fail "the continued run differs from the uninterrupted one"
  local segments
  segments=$(h5dump -d /provenance/segments/first_step part.h5 | awk '/\(0\):/ { print NF - 1 }')
  [[ $segments -eq 3 ]] || fail "provenance lists $segments segments, expected 3"
  h5dump -d /provenance/segments/first_step part.h5 | grep '(0):'
}

mesh_gen=$bin/mesh-gen dem=$bin/dem-run rubber=$bin/rubber-run
case $case in
  explosion)
    "$mesh_gen" voronoi --shape disc --diameter 0.4 --cells 400 --seed 3 -q -o disc.h5
    kill_twice_and_compare "$dem" --scene "$scenes/explosion.ini" disc.h5 --stop.t_max 1.2e-2 \
      --stop.steps_without_breaking 0 --output.frame_interval 5e-4
    ;;
  impact)
    "$mesh_gen" voronoi --shape rect --size 0.40x0.20 --cells 20x10 --seed 2 -q -o block.h5
    kill_twice_and_compare "$dem" --scene "$scenes/impact.ini" block.h5 --stop.t_max 2e-2 \
      --stop.steps_without_breaking 0 --output.frame_interval 1e-3
    ;;
  uniaxial)
    # Moving boundary layers (prescribed coordinates), contacts and damping.
    "$mesh_gen" voronoi --shape rect --size 0.25x0.40 --cells 10x16 --seed 4 -q -o rect.h5
    kill_twice_and_compare "$dem" --scene "$scenes/uniaxial.ini" rect.h5 --stop.t_max 0.1 \
      --output.frame_interval 5e-3
    ;;
  rubber-toughening)
    "$mesh_gen" triangular --nodes 80x30 --spacing 1e-3 -q -o sheet.h5
    kill_twice_and_compare "$rubber" --scene "$scenes/stretch.ini" sheet.h5 --physics.irreversible on \
      --physics.toughening on --crack.seed_length 0.02 --stop.t_max 1.5e-3 --output.frame_interval 1e-4
    h5dump -d /observables/toughened_bonds/value part.h5 | grep -qE '\(0\):' || fail "no toughening observed"
    ;;
  signals)
    # SIGTERM (a batch job's time limit) and SIGINT: a checkpoint, a message naming it, death by the signal, no
    # temporary left; the same command line then continues to the uninterrupted run's output.
    "$mesh_gen" voronoi --shape disc --diameter 0.4 --cells 400 --seed 3 -q -o disc.h5
    base=("$dem" --scene "$scenes/explosion.ini" disc.h5 --stop.steps_without_breaking 0)
    run=("${base[@]}" --stop.t_max 2e-2)
    "${run[@]}" -o full.h5 -q
    for sig in TERM INT; do
      rm -f part.h5.ckpt
      "${run[@]}" -o part.h5 --checkpoint-every 1000000 2>err.txt &
      pid=$!
      in_time_loop "$pid" part.h5
      kill -"$sig" "$pid"
      set +e; wait "$pid"; rc=$?; set -e
      cat err.txt
      [[ $rc -eq $((128 + $(kill -l "$sig"))) ]] || fail "SIG$sig: exit $rc, expected death by the signal"
      [[ -s part.h5.ckpt ]] || fail "SIG$sig: no checkpoint written"
      grep -q "stopped by SIG$sig after step [0-9]*.*checkpoint part.h5.ckpt written" err.txt ||
        fail "SIG$sig: the message does not name the step and the checkpoint"
      [[ ! -e part.h5 && -z $(ls -A | grep '\.tmp-' || true) ]] || fail "SIG$sig: output or temporaries left: $(ls -A)"
    done
    "${run[@]}" -o part.h5 2>err.txt
    grep -q "continuing from part.h5.ckpt at step" err.txt || fail "the same command line did not continue the run"
    h5diff --exclude-path /provenance full.h5 part.h5 || fail "the continued run differs"
    # Standard output has no checkpoint: SIGTERM still ends the run by the signal, leaving nothing.
    "${base[@]}" --stop.t_max 0.05 -o - > piped.h5 2>err.txt &
    pid=$!
    sleep 1
    kill -TERM "$pid"
    set +e; wait "$pid"; rc=$?; set -e
    [[ $rc -eq 143 ]] || fail "-o -: exit $rc after SIGTERM"
    grep -q "no checkpoint" err.txt || fail "-o -: the message does not say that no checkpoint was written"
    ;;
  other-run)
    # A checkpoint is this run's only if tool, version, seed, every parameter and the inputs match.
    "$mesh_gen" voronoi --shape disc --diameter 0.4 --cells 400 --seed 3 -q -o disc.h5
    run=("$dem" --scene "$scenes/explosion.ini" disc.h5 --stop.t_max 2e-3 --stop.steps_without_breaking 0)
    "${run[@]}" -o full.h5 -q
    "${run[@]}" --material.t_eps 0.05 -o other.h5 --checkpoint-every 50 2>/dev/null &
    pid=$!
    wait_for other.h5.ckpt "$pid" || fail "no checkpoint of the other run"
    kill -KILL "$pid"
    wait "$pid" || true
    refusal_outputs=(part.h5)
    refusal_inputs=(disc.h5 full.h5 other.h5.ckpt "\.other\.h5\.tmp-")
    expect_refusal "material.t_eps" "${run[@]}" --resume other.h5.ckpt -o part.h5
    expect_refusal "no such file" "${run[@]}" --resume missing.ckpt -o part.h5
    # Found by itself under the default name: a warning, a fresh start, the checkpoint replaced and removed.
    cp other.h5.ckpt part.h5.ckpt
    "${run[@]}" -o part.h5 2>err.txt
    grep -q "a checkpoint of another run.*starting afresh" err.txt || fail "no warning for another run's checkpoint"
    h5diff --exclude-path /provenance full.h5 part.h5 || fail "the fresh run differs"
    [[ ! -e part.h5.ckpt ]] || fail "the other run's checkpoint was left"
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case"
