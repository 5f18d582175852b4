#!/usr/bin/env bash
# End-to-end checks of dem-run through files and pipes. Usage: dem_run.sh BIN_DIR SCENES_DIR WORK_DIR CASE
# Small meshes (a few hundred cells of the paper's size g = 1.07 cm) and short runs.
set -euo pipefail
bin=$1 scenes=$2 work=$3 case=$4
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail, expect_refusal
refusal_outputs=(out.h5)
refusal_inputs=(disc.h5 nodes.h5 nomesh.h5 notes.txt '^bad-')
rm -rf "$work" && mkdir -p "$work" && cd "$work"
dr=$bin/dem-run
mg=$bin/mesh-gen

# A 300-cell disc (diameter 2·sqrt(300/π)·g) and a 24 × 12 block, both with g = 1.07 cm.
disc() { "$mg" voronoi --shape disc --diameter 0.209 --cells 300 --seed "${1:-7}" -q -o "${2:-disc.h5}"; }
block() { "$mg" voronoi --shape rect --size 0.2568x0.1284 --cells 24x12 --seed "${1:-7}" -q -o "${2:-block.h5}"; }

# The summary line "... K of B beams broken ..." of a run's stderr: prints "K B".
broken_counts() { sed -n 's/.* \([0-9][0-9]*\) of \([0-9][0-9]*\) beams broken.*/\1 \2/p' "$1" | tail -1; }

# Number of beam-break events recorded in a run file.
break_events() { h5dump -H -d /observables/beam_breaks/index "$1" | sed -n 's/.*SIMPLE { ( \([0-9]*\) ).*/\1/p'; }

# A root attribute of a run file, as h5dump prints its value.
root_attr() { h5dump -a "/$2" "$1" | sed -n 's/.*(0): *//p' | tr -d '"'; }

case $case in
  help)
    "$dr" --help | grep -q "Example" || fail "--help has no example"
    "$dr" --help | grep -q -- "--scene" || fail "--help does not document --scene"
    "$dr" --version | grep -qE "^dem-run [0-9]" || fail "--version"
    set +e; "$dr" >/dev/null 2>&1; rc=$?; set -e
    [[ $rc -eq 2 ]] || fail "no arguments: exit $rc, expected 2"
    ;;
  bad-input)
    disc
    "$mg" triangular --nodes 20x20 --spacing 1e-3 -q -o nodes.h5
    "$bin/../tests/e2e/make_bad_files" .
    rm -f version2.h5
    echo "not hdf5" > notes.txt
    expect_refusal "missing.ini: cannot read the scene file" "$dr" --scene missing.ini disc.h5 -o out.h5
    expect_refusal "unknown key(s): material.frobnicate" \
      "$dr" --scene "$scenes/explosion.ini" disc.h5 --material.frobnicate 1 -o out.h5
    expect_refusal "material.t_eps = '-0.5': must be positive" \
      "$dr" --scene "$scenes/explosion.ini" disc.h5 --material.t_eps -0.5 -o out.h5
    expect_refusal "physics.friction = 'maybe'" \
      "$dr" --scene "$scenes/explosion.ini" disc.h5 --physics.friction maybe -o out.h5
    expect_refusal "integrator.kind: unknown integrator 'rk4'" \
      "$dr" --scene "$scenes/explosion.ini" disc.h5 --integrator.kind rk4 -o out.h5
    expect_refusal "nodes.h5: holds a node mesh; dem-run needs cells" \
      "$dr" --scene "$scenes/explosion.ini" nodes.h5 -o out.h5
    expect_refusal "missing.h5: no such file" "$dr" --scene "$scenes/explosion.ini" missing.h5 -o out.h5
    expect_refusal "notes.txt: not an HDF5 file" "$dr" --scene "$scenes/explosion.ini" notes.txt -o out.h5
    expect_refusal "standard input is empty" "$dr" --scene "$scenes/explosion.ini" - -o out.h5 </dev/null
    # A time step above the stability bound: refused with the bound in the message. The number printed
    # must be the real bound: 0.99 of it runs, 1.01 of it is refused.
    expect_refusal "is above the stability bound" \
      "$dr" --scene "$scenes/explosion.ini" disc.h5 --integrator.dt 1e-4 -o out.h5
    bound=$(sed -n 's/.*above the stability bound \([0-9.e+-]*\) s.*/\1/p' stderr.txt)
    [[ -n $bound ]] || fail "no bound in the message"
    below=$(awk -v b="$bound" 'BEGIN { printf "%.6g", 0.99 * b }')
    above=$(awk -v b="$bound" 'BEGIN { printf "%.6g", 1.01 * b }')
    echo "bound $bound s: trying $below (must run) and $above (must be refused)"
    expect_refusal "stability bound $bound s" \
      "$dr" --scene "$scenes/explosion.ini" disc.h5 --integrator.dt "$above" -o out.h5
    "$dr" --scene "$scenes/explosion.ini" disc.h5 --integrator.dt "$below" --stop.t_max 2e-5 -q -o below.h5 \
      || fail "dt = 0.99 × bound refused"
    # The override runs it anyway (a few steps only).
    "$dr" --scene "$scenes/explosion.ini" disc.h5 --integrator.dt "$above" --integrator.allow_unstable on \
      --stop.t_max 5e-5 -q -o override.h5 || fail "allow_unstable did not override"
    ;;
  pipe)
    # mesh-gen | dem-run gives the same datasets as the file.
    disc 7 disc.h5
    "$dr" --scene "$scenes/explosion.ini" disc.h5 --stop.t_max 3e-4 -q -o file.h5
    "$mg" voronoi --shape disc --diameter 0.209 --cells 300 --seed 7 -q |
      "$dr" --scene "$scenes/explosion.ini" - --stop.t_max 3e-4 -q -o pipe.h5
    h5diff --exclude-path /provenance file.h5 pipe.h5 || fail "pipe and file differ"
    [[ $(root_attr pipe.h5 kind) == run ]] || fail "not a run file"
    ;;
  reproducible)
    # Same mesh, scene and seed: bit-identical datasets on a second run, and on 1 and 2 threads. The
    # impact scene with damping and friction on exercises every term. The thread comparison needs a
    # sample above the engine's OpenMP thresholds (more than 4096 cells and beams, more than 1024
    # candidate pairs), so it runs a 72 × 60 block (4320 cells, ~12700 beams) for 30 steps.
    block 5 block.h5
    "$mg" voronoi --shape rect --size 0.7704x0.642 --cells 72x60 --seed 5 -q -o big.h5
    dissipative=(--physics.damping on --material.gamma_n 1e4 --physics.friction on --material.friction 0.3
                 --material.gamma_t 1e4 --seed 11 -q)
    "$dr" --threads 1 --scene "$scenes/impact.ini" block.h5 --stop.t_max 5e-4 "${dissipative[@]}" -o a.h5
    "$dr" --threads 1 --scene "$scenes/impact.ini" block.h5 --stop.t_max 5e-4 "${dissipative[@]}" -o b.h5
    h5diff --exclude-path /provenance a.h5 b.h5 || fail "second run differs"
    "$dr" --threads 1 --scene "$scenes/impact.ini" big.h5 --stop.t_max 3e-5 "${dissipative[@]}" -o c1.h5
    "$dr" --threads 2 --scene "$scenes/impact.ini" big.h5 --stop.t_max 3e-5 "${dissipative[@]}" -o c2.h5
    h5diff --exclude-path /provenance c1.h5 c2.h5 || fail "1 and 2 threads differ"
    # The runs did something: beams broke.
    (( $(break_events a.h5) > 0 )) || fail "no beam broke"
    (( $(break_events c1.h5) > 0 )) || fail "no beam broke (big block)"
    # The seed is recorded.
    h5dump -d /provenance/seed a.h5 | grep -q '"11"' || fail "seed not recorded"
    ;;
  explosion|impact)
    # A short paper-like run (small sample, Table 1, t_ε = 3 %, t_Θ = 4°) to its stop rule: many beams
    # broken, the stop rule recorded, the final frame written.
    if [[ $case == explosion ]]; then disc 3 mesh.h5; else block 3 mesh.h5; fi
    "$dr" --scene "$scenes/$case.ini" mesh.h5 -o run.h5 2>log.txt || { cat log.txt; fail "$case run failed"; }
    cat log.txt
    read -r broken beams < <(broken_counts log.txt)
    reason=$(root_attr run.h5 stop_reason)
    echo "$case: $broken of $beams beams broken, stop: $reason"
    [[ $reason == "no beam broke for 300 steps" ]] || fail "$case stopped by '$reason', not by its stop rule"
    # "Many": at least a tenth of the beams (the explosion and the impact deposit ~500 J in a 300-cell
    # sample, 1.5 J per cell, ~1e3 times a beam's breaking energy, so most of the sample is damaged).
    (( broken * 10 >= beams )) || fail "only $broken of $beams beams broken"
    [[ $(break_events run.h5) == "$broken" ]] || fail "break events $(break_events run.h5) != $broken broken beams"
    ;;
  start)
    # integrator.start (issue 7 §1): zero (default) or exact; anything else refused naming the key. The
    # exact start records its force evaluations; the run files record dt to full precision.
    disc
    expect_refusal "integrator.start" \
      "$dr" --scene "$scenes/pulse.ini" disc.h5 --integrator.start taylor -o out.h5
    smooth=(--physics.contacts off --stop.max_steps 20 --stop.t_max 1 -q)
    "$dr" --scene "$scenes/pulse.ini" disc.h5 "${smooth[@]}" -o zero.h5
    "$dr" --scene "$scenes/pulse.ini" disc.h5 "${smooth[@]}" --integrator.start exact -o exact.h5
    "$dr" --scene "$scenes/pulse.ini" disc.h5 "${smooth[@]}" --integrator.start exact --integrator.kind verlet -o verlet.h5
    [[ $(root_attr zero.h5 start_evaluations) == 0 ]] || fail "zero start: $(root_attr zero.h5 start_evaluations) evaluations"
    evals=$(root_attr exact.h5 start_evaluations)
    (( evals > 0 && evals <= 150 )) || fail "exact start: $evals evaluations"
    [[ $(root_attr verlet.h5 start_evaluations) == 0 ]] || fail "verlet spent evaluations on an exact start"
    h5dump -a /parameters/dem-run/integrator.start exact.h5 | grep -q '"exact"' || fail "integrator.start not recorded"
    dt=$(h5dump -a /parameters/dem-run/derived.dt exact.h5 | sed -n 's/.*(0): *"\(.*\)".*/\1/p')
    [[ $(echo "$dt" | tr -cd '0-9' | sed 's/^0*//' | wc -c) -gt 10 ]] || fail "derived.dt = '$dt' is rounded"
    # The two starts give different trajectories (gear5's r3..r5 differ), Verlet ignores the key.
    ! h5diff -q --exclude-path /provenance --exclude-path /parameters zero.h5 exact.h5 >/dev/null || fail "exact start changed nothing"
    ;;
  beams-off)
    # A scene without beams (loose grains) still writes a run file with every mesh beam, all broken.
    disc
    "$dr" --scene "$scenes/explosion.ini" disc.h5 --physics.beams off --physics.breaking off --stop.t_max 2e-4 -q -o loose.h5
    h5dump -y -d /connectivity/beams/trajectory/intact/value loose.h5 | sed -n '/DATA {/,/}/p' | grep -q '[1-9]' &&
      fail "beams off, yet some are intact in the run file"
    [[ $(h5dump -y -d /connectivity/beams/trajectory/intact/value loose.h5 | sed -n '/DATA {/,/}/p' | grep -c '0') -gt 0 ]] ||
      fail "no intact flags in the run file"
    ;;
  *) fail "unknown case $case" ;;
esac
echo "PASS $case"
