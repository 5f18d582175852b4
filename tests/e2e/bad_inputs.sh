#!/usr/bin/env bash
# Bad input every tool must refuse (exit 2, the culprit named, no output or temporary left) and runaway
# states a run must stop (exit 1, the step and the body named).
# Usage: bad_inputs.sh SOURCE_DIR BIN_DIR WORK_DIR CASE
#   meshes   each mesh of make_bad_files breaking one invariant, through every tool that reads it
#   options  numeric options and scene values out of range, misplaced arguments and missing values, an empty
#            scene or one without loading.kind, an XDMF-unsafe name
#   runaway  cells and nodes flying off: exit 1 naming the step and the body; a frame interval of 1e-300 s
#            that must not hang
set -euo pipefail
src=$1 bin=$2 work=$3 case=$4
scenes=$src/data/scenes
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail, expect_refusal
rm -rf "$work" && mkdir -p "$work" && cd "$work"
refusal_outputs=(out.h5 out.png out.xmf)
refusal_inputs=('^bad-' '^nomesh' '^version2' '^mesh\.h5$' '^run\.h5$' '^strip\.h5$' '^values\.txt$' '^empty\.ini$' '^kindless\.ini$' '^a:b\.h5$')

case $case in
  meshes)
    "$bin/../tests/e2e/make_bad_files" .
    dem=("$bin/dem-run" --scene "$scenes/uniaxial.ini" --stop.t_max 1e-6 -q -o out.h5)
    rubber=("$bin/rubber-run" --scene "$scenes/stretch.ini" --stop.t_max 1e-6 -q -o out.h5)
    # file : what the message must name. The faults users met, through every tool that reads a mesh file:
    while IFS=: read -r file needle; do
      expect_refusal "$needle" "${dem[@]}" "$file"
      expect_refusal "$needle" "$bin/render" "$file" -q -o out.png
      expect_refusal "$needle" "$bin/h5-xdmf" "$file" -q -o out.xmf
      rm -f "${file%.h5}.xmf"
    done <<'CASES'
bad-nan-vertex.h5:invalid mesh: finite: cell 1: vertex 1 is not finite
bad-nan-centroid.h5:invalid mesh: finite: cell 3: centroid is not finite
bad-clockwise.h5:convex: cell 2 is not convex and counter-clockwise
bad-non-convex.h5:convex: cell 2 is not convex and counter-clockwise
bad-zero-beam.h5:beam length: beam 4 (1, 9): 0 m is not positive
bad-nan-beam.h5:invalid mesh: finite: beam 4: length is not finite
bad-self-beam.h5:beam order: beam 4 (1, 1) joins a cell to itself
bad-negative-area.h5:area: cell 6: area -
bad-short-centroid.h5:/particles/cells/centroid: gives 31 cells, but area, second_moment, vertex_offset give 32
bad-float-offsets.h5:/particles/cells/vertex_offset: holds floating-point values
CASES
    # ... and further ones, through dem-run (every reader shares the validation above).
    while IFS=: read -r file needle; do
      expect_refusal "$needle" "${dem[@]}" "$file"
    done <<'CASES'
bad-nan-area.h5:invalid mesh: finite: cell 5: area is not finite
bad-inf-spacing.h5:invalid mesh: finite: attribute spacing is not finite
bad-huge-spacing.h5:invalid mesh: spacing: 1000000 m, far from the cells' mean size
bad-outside-box.h5:invalid mesh: bounds: cell 4: centroid
bad-offset-overflow.h5:/particles/cells/vertex_offset: decreases at cell 3
CASES
    while IFS=: read -r file needle; do
      expect_refusal "$needle" "${rubber[@]}" "$file"
      expect_refusal "$needle" "$bin/render" "$file" -q -o out.png
    done <<'CASES'
bad-node-nan.h5:invalid mesh: finite: node 7: position is not finite
bad-node-nan-spacing.h5:invalid mesh: finite: attribute spacing is not finite
bad-node-bond-length.h5:bond length: bond 3 (1, 10): 0.002 m
bad-node-duplicate-bond.h5:bond duplicate: bond 4 (1, 10)
bad-node-overflow.h5:reference_position: has 60 rows, but the attributes say nx = 4611686018427387904, ny = 4
CASES
    # Run files carry their mesh: every tool that reads runs refuses one that breaks an invariant.
    area="bad-run-nan-area.h5: invalid mesh: finite: cell 5: area is not finite"
    expect_refusal "$area" "$bin/fragment-count" bad-run-nan-area.h5 -q -o out.h5
    expect_refusal "$area" "$bin/wave-speed" bad-run-nan-area.h5 --format text -q
    expect_refusal "$area" "$bin/render" bad-run-nan-area.h5 -q -o out.png
    expect_refusal "$area" "$bin/h5-xdmf" bad-run-nan-area.h5 --polygons off -q -o out.xmf
    node="bad-run-node-nan.h5: invalid mesh: finite: node 7: position is not finite"
    expect_refusal "$node" "$bin/observables" bad-run-node-nan.h5 --crack-shape -q
    expect_refusal "$node" "$bin/wave-speed" bad-run-node-nan.h5 --format text -q
    expect_refusal "$node" "$bin/h5-xdmf" bad-run-node-nan.h5 -q -o out.xmf
    # mesh-gen check reports the same faults, all of them.
    set +e; "$bin/mesh-gen" check bad-clockwise.h5 > report.txt 2>&1; rc=$?; set -e
    [[ $rc -ne 0 ]] && grep -q "cell 2 is not convex" report.txt || fail "mesh-gen check passes a clockwise cell"
    rm -f report.txt
    ;;
  options)
    "$bin/mesh-gen" voronoi --shape disc --diameter 0.06 --cells 60 --seed 3 -q -o mesh.h5
    "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 2e-6 -q -o run.h5
    "$bin/mesh-gen" triangular --nodes 60x20 --spacing 1e-3 -q -o strip.h5
    awk 'BEGIN { for (k = 1; k <= 200; k++) printf "%.6g\n", (1 - (k - 0.5) / 200) ^ (-1 / 1.5) }' > values.txt
    : > empty.ini
    expect_refusal "--seed: must be a whole number" "$bin/mesh-gen" voronoi --cells 8x4 --seed -1 -o out.h5
    expect_refusal "--seed: must be a whole number" "$bin/mesh-gen" voronoi --cells 8x4 --seed 99999999999999999999 -o out.h5
    expect_refusal "--threads: must lie in [0," "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --threads 100000 -o out.h5
    expect_refusal "--threads: must not be negative, got '-1'" "$bin/powerlaw-fit" values.txt --threads -1 --format text
    expect_refusal "--significance: must lie in (0, 1), got 2" "$bin/powerlaw-fit" values.txt --significance 2
    expect_refusal "--bootstrap: must lie in [0, 1000000]" "$bin/powerlaw-fit" values.txt --bootstrap 2000000000
    expect_refusal "--polygon-limit: must not be negative" "$bin/h5-xdmf" run.h5 --polygon-limit -5 -o out.xmf
    expect_refusal "--threshold: must be a finite number, got 'nan'" "$bin/wave-speed" run.h5 --threshold nan
    expect_refusal "--min-section: must be a finite number, got 'inf'" "$bin/mesh-gen" voronoi --cells 8x4 --min-section inf -o out.h5
    expect_refusal "empty.ini: the scene file sets no keys" "$bin/dem-run" --scene empty.ini mesh.h5 -o out.h5
    printf '[material]\ndensity = 5000\n' > kindless.ini
    expect_refusal "kindless.ini: loading.kind is required" "$bin/dem-run" --scene kindless.ini mesh.h5 -o out.h5
    expect_refusal "kindless.ini: loading.kind is required" "$bin/rubber-run" --scene kindless.ini strip.h5 -o out.h5
    expect_refusal "loading.energy = 1e+300 J: kicks cell" \
      "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --loading.energy 1e300 -o out.h5
    expect_refusal "--loading.impact_speed = '1e6': must lie in (0, 100000]" \
      "$bin/dem-run" --scene "$scenes/impact.ini" mesh.h5 --loading.impact_speed 1e6 -o out.h5
    expect_refusal "--material.density = '1e9': must lie in (0, 100000]" \
      "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --material.density 1e9 -o out.h5
    expect_refusal "--loading.stretch_y = '1e6': must lie in (0, 100]" \
      "$bin/rubber-run" --scene "$scenes/stretch.ini" strip.h5 --loading.stretch_y 1e6 -o out.h5
    expect_refusal "crack.seed_length = 10 m: not shorter than the crack line" \
      "$bin/rubber-run" --scene "$scenes/stretch.ini" strip.h5 --crack.seed_length 10 -o out.h5
    cp run.h5 a:b.h5
    expect_refusal "XDMF cannot refer to a file whose path contains ':'" "$bin/h5-xdmf" a:b.h5 -o out.xmf
    expect_refusal "more arguments than inputs: 'mesh.h5', 'run.h5'" "$bin/mesh-gen" check mesh.h5 run.h5
    expect_refusal "--scene: missing value" "$bin/dem-run" mesh.h5 --scene
    expect_refusal "--seed: missing value" "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 -o out.h5 --seed
    expect_refusal "no input given" "$bin/dem-run" --scene "$scenes/explosion.ini" -o out.h5
    ;;
  runaway)
    # Valid scenes whose bodies fly off: cells kicked to 37 km/s with nothing to hold them, a rubber sheet
    # shaken at 90 km/s. Exit 1 naming the step and the body, no output left.
    "$bin/mesh-gen" voronoi --shape disc --diameter 0.06 --cells 60 --seed 3 -q -o mesh.h5
    "$bin/mesh-gen" triangular --nodes 60x20 --spacing 1e-3 -q -o strip.h5
    runaway() {
      local pattern=$1; shift
      set +e; "$@" -q -o out.h5 2>stderr.txt; local rc=$?; set -e
      cat stderr.txt
      [[ $rc -eq 1 ]] || fail "exit $rc, expected 1: $*"
      grep -qE "$pattern" stderr.txt || fail "the runaway message names no step and body: $*"
      [[ -z $(ls -A | grep -v -e mesh.h5 -e strip.h5 -e stderr.txt || true) ]] || fail "left behind: $(ls -A)"
    }
    runaway "runaway at step [0-9]+ .*: cell [0-9]+ is at" "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 \
      --physics.beams off --physics.breaking off --physics.contacts off --loading.energy 1e7 --integrator.dt 1e-6 \
      --stop.t_max 1e-2
    runaway "runaway at step [0-9]+ .*: node [0-9]+ is at" "$bin/rubber-run" --scene "$scenes/stretch.ini" strip.h5 \
      --crack.seed_length 0 --stop.tip_margin 0 --initial.noise 9e4 --stop.t_max 1e-2
    # Not a hang: frames asked for every 1e-300 s are taken once a step.
    timeout 20 "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --output.frame_interval 1e-300 \
      --stop.max_steps 30 -q -o frames.h5 || fail "a frame interval of 1e-300 s: exit $?"
    [[ $(h5dump -H -d /particles/cells/position/value frames.h5 | sed -n 's/.*SIMPLE { ( \([0-9]*\),.*/\1/p') == 31 ]] \
      || fail "a frame interval of 1e-300 s: not one frame a step"
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case"
