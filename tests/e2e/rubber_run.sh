#!/usr/bin/env bash
# End-to-end checks of rubber-run through files and pipes. Usage: rubber_run.sh BIN_DIR SCENES_DIR WORK_DIR CASE
# Small strips (60 x 20 nodes, Δ = 1 mm) and short runs (a few time units Δ/√a = 25 µs).
set -euo pipefail
bin=$1 scenes=$2 work=$3 case=$4
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail, expect_refusal
refusal_outputs=(out.h5)
refusal_inputs=(strip.h5 cells.h5 nomesh.h5 notes.txt '^bad-')
rm -rf "$work" && mkdir -p "$work" && cd "$work"
rr=$bin/rubber-run
mg=$bin/mesh-gen
stretch=$scenes/stretch.ini
wave=$scenes/wave.ini
short=(--stop.t_max 1e-4 --output.frame_interval 5e-5)

strip() { "$mg" triangular --nodes 60x20 --spacing 1e-3 -q -o "${1:-strip.h5}"; }

# A root attribute of a file, as h5dump prints its value.
root_attr() { h5dump -a "/$2" "$1" | sed -n 's/.*(0): *//p' | tr -d '"'; }

# The values of a numeric dataset, one a line.
values() {
  h5dump -m '%.17g' -y -w 0 -d "$2" "$1" | awk '!done && /DATA \{/ { on = 1; next } on && /\}/ { on = 0; done = 1 } on' |
    tr ',' '\n' | sed '/^ *$/d;s/ //g'
}

# has FILE PATTERN h5dump-options...: the dump contains PATTERN (grep reads it all: no SIGPIPE under pipefail).
has() { local f=$1 p=$2; shift 2; h5dump "$@" "$f" 2>&1 | grep -c -- "$p" >/dev/null; }

case $case in
  help)
    "$rr" --help | grep -q "Example" || fail "--help has no example"
    "$rr" --help | grep -q -- "--scene" || fail "--help does not document --scene"
    "$rr" --help | grep -q -- "--threads" || fail "--help does not document --threads"
    "$rr" --version | grep -qE "^rubber-run [0-9]" || fail "--version"
    set +e; "$rr" >/dev/null 2>&1; rc=$?; set -e
    [[ $rc -eq 2 ]] || fail "no arguments: exit $rc, expected 2"
    ;;
  pipe)
    # mesh-gen | rubber-run, to a file and to standard output: the same data.
    "$mg" triangular --nodes 60x20 --spacing 1e-3 -q | "$rr" --scene "$stretch" - "${short[@]}" -q -o file.h5
    "$mg" triangular --nodes 60x20 --spacing 1e-3 -q | "$rr" --scene "$stretch" - "${short[@]}" -q -o - > pipe.h5
    h5diff --exclude-path /provenance file.h5 pipe.h5 || fail "file and pipe outputs differ"
    [[ $(root_attr file.h5 kind) == run ]] || fail "kind is not run"
    [[ $(root_attr file.h5 model) == rubber ]] || fail "model is not rubber"
    for obs in kinetic_energy potential_energy total_energy crack_tip_x crack_tip_reference_x crack_tip_speed \
               bonds_past_cutoff bond_breaks; do
      h5ls "file.h5/observables/$obs" >/dev/null 2>&1 || fail "observable $obs missing"
    done
    h5ls file.h5/particles/nodes/mass >/dev/null || fail "node masses missing"
    h5dump -a /parameters/rubber-run/derived.dt file.h5 >/dev/null || fail "derived.dt not recorded"
    has file.h5 "stretch_y" -d /parameters/rubber-run/scene_text || fail "scene text not recorded"
    # The lineage: the mesh-gen step is in the provenance.
    has file.h5 mesh-gen -d /provenance/tool || fail "mesh-gen missing from the provenance"
    # The seed crack (25Δ) is there: crack tip at the start about 25 mm from the left edge.
    tip0=$(values file.h5 /observables/crack_tip_reference_x/value | head -1)
    awk -v t="$tip0" 'BEGIN { exit !(t > 0.023 && t < 0.026) }' || fail "initial crack tip at $tip0 m, expected ~0.025"
    ;;
  reproducible)
    # Same input, same bits: twice, and with 1 and 2 threads; noise with another seed differs.
    strip
    "$rr" --scene "$stretch" strip.h5 "${short[@]}" --initial.noise 0.5 --seed 3 -q -o a.h5
    "$rr" --scene "$stretch" strip.h5 "${short[@]}" --initial.noise 0.5 --seed 3 -q -o b.h5
    "$rr" --scene "$stretch" strip.h5 "${short[@]}" --initial.noise 0.5 --seed 3 --threads 2 -q -o c.h5
    "$rr" --scene "$stretch" strip.h5 "${short[@]}" --initial.noise 0.5 --seed 4 -q -o d.h5
    h5diff --exclude-path /provenance a.h5 b.h5 || fail "a second run differs"
    h5diff --exclude-path /provenance a.h5 c.h5 || fail "2 threads differ from 1"
    if h5diff -q --exclude-path /provenance a.h5 d.h5; then fail "another seed gave the same run"; fi
    has a.h5 '"3"' -d /provenance/seed || fail "seed not recorded"
    has a.h5 '"0.5"' -a /parameters/rubber-run/initial.noise || fail "override not recorded"
    ;;
  bad-input)
    strip
    "$mg" voronoi --cells 8x4 -q -o cells.h5
    "$bin/../tests/e2e/make_bad_files" .
    rm -f version2.h5
    echo "not hdf5" > notes.txt
    expect_refusal "missing.ini: cannot read the scene file" "$rr" --scene missing.ini strip.h5 -o out.h5
    expect_refusal "unknown key(s): law.frobnicate" "$rr" --scene "$stretch" strip.h5 --law.frobnicate 1 -o out.h5
    expect_refusal "material.a = '-1': must be positive" "$rr" --scene "$stretch" strip.h5 --material.a -1 -o out.h5
    expect_refusal "law.pair = 'hooke': expected one of marder, marder-c1" "$rr" --scene "$stretch" strip.h5 --law.pair hooke -o out.h5
    expect_refusal "physics.damping = 'maybe'" "$rr" --scene "$stretch" strip.h5 --physics.damping maybe -o out.h5
    expect_refusal "integrator.kind: unknown integrator 'rk4'" \
      "$rr" --scene "$stretch" strip.h5 --integrator.kind rk4 -o out.h5
    expect_refusal "law.cutoff_length" "$rr" --scene "$stretch" strip.h5 --law.cutoff_length 1e-3 -o out.h5
    expect_refusal "boundary.clamp_rows = 10 clamps the whole mesh" \
      "$rr" --scene "$stretch" strip.h5 --boundary.clamp_rows 10 -o out.h5
    expect_refusal "cells.h5: holds polygon cells; rubber-run needs a node mesh" "$rr" --scene "$stretch" cells.h5 -o out.h5
    expect_refusal "nomesh.h5" "$rr" --scene "$stretch" nomesh.h5 -o out.h5
    expect_refusal "missing.h5" "$rr" --scene "$stretch" missing.h5 -o out.h5
    expect_refusal "notes.txt: not an HDF5 file" "$rr" --scene "$stretch" notes.txt -o out.h5
    expect_refusal "standard input is empty" "$rr" --scene "$stretch" - -o out.h5 </dev/null
    expect_refusal "--threads" "$rr" --scene "$stretch" strip.h5 --threads -1 -o out.h5
    # A time step above the stability bound is refused with the bound; 0.99 of it runs.
    expect_refusal "is above the stability bound" "$rr" --scene "$stretch" strip.h5 --integrator.dt 1e-5 -o out.h5
    bound=$(sed -n 's/.*above the stability bound \([0-9.e+-]*\) s.*/\1/p' stderr.txt)
    [[ -n $bound ]] || fail "no bound in the message"
    below=$(awk -v b="$bound" 'BEGIN { printf "%.6g", 0.99 * b }')
    above=$(awk -v b="$bound" 'BEGIN { printf "%.6g", 1.01 * b }')
    expect_refusal "stability bound $bound s" "$rr" --scene "$stretch" strip.h5 --integrator.dt "$above" -o out.h5
    "$rr" --scene "$stretch" strip.h5 --integrator.dt "$below" --stop.t_max 2e-6 -q -o below.h5 \
      || fail "dt = 0.99 × bound refused"
    ;;
  far-field)
    # The default scene is quiet; a cut-off within 15 widths of the far-field bonds is named with its
    # numbers; a bond family shorter than Δ + u_s is named too.
    strip
    "$rr" --scene "$stretch" strip.h5 --stop.t_max 2e-6 -o ok.h5 2>stderr.txt
    if grep -q "warning" stderr.txt; then cat stderr.txt; fail "the default stretch scene warns"; fi
    "$rr" --scene "$stretch" strip.h5 --law.cutoff_length 3.0e-3 --stop.t_max 2e-6 -o near.h5 2>stderr.txt
    cat stderr.txt
    grep -q "warning: law.cutoff_length u_c = 0.003 m (3Δ) is 6.67 cut-off widths" stderr.txt \
      || fail "no far-field warning naming u_c and the widths"
    grep -q "u_0 = 0.0026665 m" stderr.txt || fail "the warning does not name u_0"
    grep -q "stiffens the far field" stderr.txt || fail "the warning does not say what goes wrong"
    grep -q "c_T = " stderr.txt || fail "the warning does not give the lattice's speeds"
    has near.h5 "stiffens" -a /parameters/rubber-run/derived.warnings || fail "warning not recorded"
    "$rr" --scene "$stretch" strip.h5 --loading.stretch_x 1.0 --stop.t_max 2e-6 -o short.h5 2>stderr.txt
    cat stderr.txt
    grep -q "not Mooney-Rivlin" stderr.txt || fail "no warning for a bond family in the short-bond branch"
    grep -q "rows-along y" stderr.txt || fail "the warning does not say how to avoid it"
    "$rr" --scene "$stretch" strip.h5 --law.cutoff_length 3.0e-3 --stop.t_max 2e-6 -q -o quiet.h5 2>stderr.txt
    [[ ! -s stderr.txt ]] || fail "--quiet printed: $(cat stderr.txt)"
    ;;
  wave)
    # A longitudinal pulse in a sheet periodic in y: nothing breaks, energy is conserved, the fronts move.
    "$mg" triangular --nodes 200x4 --spacing 1e-3 -q -o sheet.h5
    "$rr" --scene "$wave" sheet.h5 --stop.t_max 5e-4 --output.frame_interval 1e-4 -o wave.h5 2>stderr.txt
    cat stderr.txt
    grep -q " 0 bonds past u_c" stderr.txt || fail "bonds broke in a wave run"
    # Total energy constant within 1e-3 of the pulse's energy (the largest kinetic energy).
    paste <(values wave.h5 /observables/total_energy/value) <(values wave.h5 /observables/kinetic_energy/value) |
      awk 'NR == 1 { e0 = $1 } { d = $1 - e0; if (d < 0) d = -d; if (d > dmax) dmax = d; if ($2 > kmax) kmax = $2 }
           END { printf "energy change %g J, pulse energy %g J\n", dmax, kmax; exit !(kmax > 0 && dmax < 1e-3 * kmax) }' \
      || fail "energy not conserved"
    # Frames every 1e-4 s: the initial state, 5 frames, and the final one at t_max.
    [[ $(values wave.h5 /particles/nodes/position/step | wc -l) -eq 6 ]] || fail "expected 6 frames"
    "$rr" --scene "$wave" sheet.h5 --pulse.kind shear --stop.t_max 1e-4 -q -o shear.h5 || fail "shear pulse"
    ;;
  freeze)
    # Energy-neutral failure with a crack path: the frozen energy is an observable and part of the
    # potential energy (the total is conserved through failures); 1 and 2 threads give the same file with
    # toughening and near-failure damping on; bad values are refused naming the key.
    strip
    expect_refusal "crack.path_cutoff_ratio = 0.9 must be at least 1" "$rr" --scene "$stretch" strip.h5 \
      --crack.path_cutoff_ratio 0.9 -o out.h5
    expect_refusal "law.failure" "$rr" --scene "$stretch" strip.h5 --law.failure melt -o out.h5
    crack=(--law.failure freeze --law.cutoff none --law.cutoff_length 2.8e-3 --crack.path_cutoff_ratio 1.3
           --integrator.dt 2.5e-7 --stop.t_max 1e-4 --output.frame_interval 5e-5)
    "$rr" --scene "$stretch" strip.h5 "${crack[@]}" -o f.h5 2>stderr.txt
    cat stderr.txt
    h5ls f.h5/observables/frozen_energy >/dev/null 2>&1 || fail "observable frozen_energy missing"
    frozen=$(values f.h5 /observables/frozen_energy/value | tail -1)
    awk -v f="$frozen" 'BEGIN { exit !(f < 0) }' || fail "no three-body energy frozen ($frozen J)"
    # Total energy within 5e-3 of the frozen energy's size (measured 0.020 J against 25.5 J: 8e-4; the paper's
    # law broken at u_c books all of it as a change).
    paste <(values f.h5 /observables/total_energy/value) <(values f.h5 /observables/frozen_energy/value) |
      awk 'NR == 1 { e0 = $1 } { d = $1 - e0; if (d < 0) d = -d; if (d > dmax) dmax = d; f = $2 < 0 ? -$2 : $2 }
           END { printf "energy change %g J, frozen %g J\n", dmax, f; exit !(f > 0 && dmax < 5e-3 * f) }' \
      || fail "energy not conserved through failures"
    more=(--physics.toughening on --toughening.cutoff 5e-3 --physics.damping on --damping.kind near_failure
          --damping.onset 2.7e-3 --initial.noise 0.5 --seed 3)
    "$rr" --scene "$stretch" strip.h5 "${crack[@]}" "${more[@]}" -q -o t1.h5
    "$rr" --scene "$stretch" strip.h5 "${crack[@]}" "${more[@]}" --threads 2 -q -o t2.h5
    h5diff --exclude-path /provenance t1.h5 t2.h5 || fail "2 threads differ from 1"
    ;;
  *) fail "unknown case $case" ;;
esac
echo "PASS $case"
