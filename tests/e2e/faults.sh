#!/usr/bin/env bash
# Faults while writing: every writer on a full disk, standard output on a full device, a run killed
# outright, a run stopped by SIGTERM. Each must end with exit 1 and the reason, no file, no temporary.
# Usage: faults.sh SOURCE_DIR BIN_DIR WORK_DIR CASE
#   full-disk     every tool's output to a 300 KiB tmpfs (mounted in a private mount namespace: needs root
#                 or unprivileged user namespaces; skipped with a message otherwise)
#   full-stdout   every tool writing standard output to /dev/full
#   killed        dem-run and rubber-run killed with SIGKILL: the next run of the same target removes the
#                 temporary; a live writer's temporary is left alone
#   terminated    SIGTERM and SIGINT remove the temporary at once
set -euo pipefail
src=$1 bin=$2 work=$3 case=$4
scenes=$src/data/scenes
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# Small inputs: a 60-cell disc, a short run of it, its fragments, a rubber strip and a short wave run.
inputs() {
  "$bin/mesh-gen" voronoi --shape disc --diameter 0.06 --cells 60 --seed 3 -q -o mesh.h5
  "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 1e-4 --output.frame_interval 2e-6 -q -o run.h5
  "$bin/fragment-count" run.h5 -q -o fragments.h5
  "$bin/mesh-gen" triangular --nodes 12x6 --spacing 1e-3 -q -o strip.h5
  "$bin/mesh-gen" triangular --nodes 100x4 --spacing 1e-3 -q |
    "$bin/rubber-run" --scene "$scenes/wave.ini" - --stop.t_max 5e-4 --output.frame_interval 2e-5 -q -o wave.h5
}

# Every tool, writing to the folder $1 (or to standard output when $1 is "-"), each output larger than
# the 300 KiB disk once the disk is nearly full.
writers() {
  local d=$1 o
  o() { [[ $d == - ]] && echo - || echo "$d/$1"; }
  echo "$bin/mesh-gen voronoi --cells 200x100 -q -o $(o m.h5)"
  echo "$bin/mesh-gen triangular --nodes 300x100 --spacing 1e-3 -q -o $(o t.h5)"
  echo "$bin/dem-run --scene $scenes/explosion.ini mesh.h5 --stop.t_max 2e-5 --output.frame_interval 1e-7 -q -o $(o r.h5)"
  echo "$bin/rubber-run --scene $scenes/stretch.ini strip.h5 --crack.seed_length 0 --stop.t_max 1e-3 --output.frame_interval 1e-6 -q -o $(o r.h5)"
  echo "$bin/fragment-count run.h5 --time-series -q -o $(o f.h5)"
  echo "$bin/powerlaw-fit fragments.h5 --bootstrap 0 --gof-samples 0 -q -o $(o p.h5)"
  echo "$bin/powerlaw-fit fragments.h5 --bootstrap 0 --gof-samples 0 --format text -q -o $(o p.txt)"
  echo "$bin/wave-speed wave.h5 -q -o $(o w.h5)"
  echo "$bin/wave-speed wave.h5 --format text -q -o $(o w.txt)"
  echo "$bin/render run.h5 --width 2000 -q -o $(o a.png)"
  echo "$bin/render run.h5 --width 2000 --format svg -q -o $(o a.svg)"
  echo "$bin/h5-xdmf run.h5 -q -o $(o a.xmf)"
  echo "$bin/observables run.h5 -q"
  echo "$bin/mesh-gen check mesh.h5"
}

# fails_cleanly DIR COMMAND...: exit 1, a message naming the reason, nothing left in DIR.
fails_cleanly() {
  local dir=$1; shift
  set +e; "$@" > "${stdout:-/dev/null}" 2>stderr.txt; local rc=$?; set -e
  [[ $rc -eq 1 ]] || fail "exit $rc, expected 1: $* ($(cat stderr.txt))"
  grep -qE "disk is full|No space left" stderr.txt || fail "the message does not say the disk is full: $* ($(cat stderr.txt))"
  # (the file standard output was redirected to is the shell's, not the tool's)
  [[ -z $(ls -A "$dir" | grep -v -e '^fill$' -e "^$(basename "${stdout:-none}")\$" || true) ]] ||
    fail "left in $dir: $(ls -A "$dir" | tr '\n' ' '): $*"
}

case $case in
  full-disk)
    inputs
    if [[ ${FAULTS_IN_NAMESPACE:-} != 1 ]]; then
      # A private mount namespace: the tmpfs disappears with the test, whatever happens.
      for enter in "unshare --mount --propagation private" "unshare --user --map-root-user --mount"; do
        if $enter true 2>/dev/null; then
          FAULTS_IN_NAMESPACE=1 exec $enter bash "$0" "$@"
        fi
      done
      echo "SKIP: cannot make a mount namespace here (needs root or user namespaces): full-disk case not run"
      exit 0
    fi
    mkdir disk
    mount -t tmpfs -o size=300k tmpfs disk || { echo "SKIP: cannot mount a tmpfs here"; exit 0; }
    while read -r line; do
      read -ra cmd <<< "$line"
      case $line in
        *" -o -"* | *observables* | *"mesh-gen check"*) continue ;;
      esac
      # The outputs of the runs and of mesh-gen outgrow the disk; the others meet a full disk.
      rm -f disk/fill
      case $line in *mesh-gen* | *dem-run* | *rubber-run*) ;; *) head -c 1M /dev/zero > disk/fill 2>/dev/null || true ;; esac
      fails_cleanly disk "${cmd[@]}"
    done < <(writers disk)
    # Standard output redirected to the full disk.
    head -c 1M /dev/zero > disk/fill 2>/dev/null || true
    for tool in "observables run.h5 -q" "mesh-gen check mesh.h5" "h5-xdmf run.h5 -q -o -"; do
      read -ra cmd <<< "$bin/$tool"
      stdout=disk/out.txt fails_cleanly disk "${cmd[@]}"
      rm -f disk/out.txt
    done
    umount disk
    ;;
  full-stdout)
    inputs
    while read -r line; do
      read -ra cmd <<< "$line"
      [[ $line == *" -o -"* || $line == *observables* || $line == *"mesh-gen check"* ]] || continue
      set +e; "${cmd[@]}" > /dev/full 2>stderr.txt; rc=$?; set -e
      [[ $rc -eq 1 ]] || fail "exit $rc, expected 1, writing to /dev/full: $line ($(cat stderr.txt))"
      grep -q "cannot write to standard output" stderr.txt || fail "no message about standard output: $line"
    done < <(writers -)
    ;;
  killed)
    "$bin/mesh-gen" voronoi --shape disc --diameter 0.209 --cells 2000 --seed 1 -q -o mesh.h5
    "$bin/mesh-gen" triangular --nodes 200x100 --spacing 1e-3 -q -o strip.h5
    for run in "dem-run --scene $scenes/explosion.ini mesh.h5 --integrator.dt auto" \
               "rubber-run --scene $scenes/stretch.ini strip.h5"; do
      read -ra cmd <<< "$bin/$run"
      "${cmd[@]}" --stop.t_max 1 -q -o out.h5 & pid=$!
      for _ in $(seq 100); do [[ -n $(ls -A | grep '^\.out\.h5\.tmp-' || true) ]] && break; sleep 0.1; done
      sleep 1
      kill -9 $pid; wait $pid 2>/dev/null || true
      killed=$(ls -A | grep '^\.out\.h5\.tmp-' || true)
      [[ $(wc -w <<< "$killed") == 1 ]] || fail "$run: expected one temporary after kill -9, found '$killed'"
      # The next writer of the target removes it; a third leaves the second's (live) temporary alone.
      "${cmd[@]}" --stop.t_max 1 -q -o out.h5 & live=$!
      for _ in $(seq 100); do [[ -e $killed ]] || break; sleep 0.1; done
      [[ ! -e $killed ]] || fail "$run: the killed run's temporary $killed outlives the next run"
      for _ in $(seq 100); do [[ -n $(ls -A | grep '^\.out\.h5\.tmp-' || true) ]] && break; sleep 0.1; done
      alive=$(ls -A | grep '^\.out\.h5\.tmp-' || true)
      [[ -n $alive ]] || fail "$run: the live writer has no temporary"
      "${cmd[@]}" --stop.t_max 1e-6 -q -o out.h5
      [[ -e $alive ]] || fail "$run: a live writer's temporary was removed"
      kill -TERM $live; wait $live 2>/dev/null || true
      [[ -z $(ls -A | grep '^\.out\.h5\.tmp-' || true) ]] || fail "$run: temporaries left: $(ls -A)"
      rm -f out.h5
    done
    ;;
  terminated)
    "$bin/mesh-gen" triangular --nodes 200x100 --spacing 1e-3 -q -o strip.h5
    for sig in TERM INT; do
      "$bin/rubber-run" --scene "$scenes/stretch.ini" strip.h5 --stop.t_max 1 -q -o out.h5 & pid=$!
      for _ in $(seq 100); do [[ -n $(ls -A | grep '^\.out\.h5\.tmp-' || true) ]] && break; sleep 0.1; done
      kill -$sig $pid; set +e; wait $pid; rc=$?; set -e
      [[ $rc -gt 128 ]] || fail "SIG$sig: exit $rc, expected death by the signal"
      [[ -z $(ls -A | grep -E '^\.out\.h5\.tmp-|^out\.h5$' || true) ]] || fail "SIG$sig: left $(ls -A)"
    done
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case"
