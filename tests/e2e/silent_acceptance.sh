#!/usr/bin/env bash
# Input the tools once accepted silently (exit 0, the fault ignored or a value quietly chosen), now refused:
# exit 2, the value, file or option at fault named, no output or temporary left.
# Usage: silent_acceptance.sh SOURCE_DIR BIN_DIR WORK_DIR CASE
#   run-frames       fragment-count: an intact flag of 7, a frame at t = -1 s
#   nan-frame        render: a cell at a NaN position or angle (it was left out of the picture)
#   overlap          a cell stacked on another, through mesh-gen check and the readers of meshes
#   repeated-key     a scene key twice on the command line or in a --config file (the last one won)
#   nested-config    'config = FILE' inside a --config file (ignored)
#   config-file      a directory, a device or a binary file as --config (read as empty)
#   ignored-option   mesh-gen options the chosen shape or disorder ignores
#   scene-values     moduli of 0, a time step that needs more than 1e12 steps
#   same-input       powerlaw-fit given one file twice, or two copies of one
set -euo pipefail
src=$1 bin=$2 work=$3 case=$4
scenes=$src/data/scenes
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail, expect_refusal
rm -rf "$work" && mkdir -p "$work" && cd "$work"
refusal_outputs=(out.h5 out.png out.txt)
refusal_inputs=('^bad-' '^nomesh\.h5$' '^version2\.h5$' '^mesh\.h5$' '^strip\.h5$' '^run\.h5$' '^a\.h5$' '^b\.h5$'
                '^link\.h5$' '\.cfg$' '^folder$')

disc() { "$bin/mesh-gen" voronoi --shape disc --diameter 0.06 --cells 60 --seed 3 -q -o mesh.h5; }
dem=("$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 1e-6 -o out.h5)

case $case in
  run-frames)
    "$bin/../tests/e2e/make_bad_files" .
    expect_refusal "bad-run-intact-7.h5:/connectivity/beams/trajectory/intact/value: frame 2: beam 3: intact flag 7, expected 0 or 1" \
      "$bin/fragment-count" bad-run-intact-7.h5 -o out.h5
    expect_refusal "bad-run-negative-time.h5:/particles/cells/position/time: frame 1: t = -1 s after 0 s" \
      "$bin/fragment-count" bad-run-negative-time.h5 -o out.h5
    expect_refusal "frame times must be finite, >= 0 and non-decreasing" \
      "$bin/fragment-count" bad-run-negative-time.h5 --frame 0 -o out.h5
    ;;
  nan-frame)
    "$bin/../tests/e2e/make_bad_files" .
    expect_refusal "bad-run-nan-position.h5:/particles/cells/position: frame 2 (t = 2e-06 s): cell 4: (nan," \
      "$bin/render" bad-run-nan-position.h5 -o out.png
    expect_refusal "bad-run-nan-angle.h5:/particles/cells/angle: frame 2 (t = 2e-06 s): cell 6: angle nan is not finite" \
      "$bin/render" bad-run-nan-angle.h5 --time 2e-6 -o out.png
    # Each frame drawn is checked: a movie stops at the frame.
    expect_refusal "frame 2 (t = 2e-06 s): cell 4" "$bin/render" bad-run-nan-position.h5 --all-frames -o out-%d.png
    rm -f out-*.png
    ;;
  overlap)
    "$bin/../tests/e2e/make_bad_files" .
    needle="overlap: cells 5 and 32 overlap by"
    expect_refusal "$needle" "$bin/mesh-gen" check bad-stacked-cell.h5
    grep -qF "(100% of the smaller), centroids 0 m apart" stderr.txt || fail "the overlap is not measured"
    expect_refusal "bad-stacked-cell.h5: invalid mesh: $needle" \
      "$bin/dem-run" --scene "$scenes/uniaxial.ini" bad-stacked-cell.h5 --stop.t_max 1e-6 -o out.h5
    expect_refusal "bad-stacked-cell.h5: invalid mesh: $needle" "$bin/render" bad-stacked-cell.h5 -o out.png
    ;;
  repeated-key)
    disc
    expect_refusal "--material.t_eps: given twice on the command line ('0.02', then '0.03')" \
      "${dem[@]}" --material.t_eps 0.02 --material.t_eps 0.03
    expect_refusal "--stop.t_max: given twice on the command line" "${dem[@]}" --stop.t_max=1e-5
    printf '[material]\nt_eps = 0.02\nt_eps = 0.03\n' > twice.cfg
    expect_refusal "--config twice.cfg: key 'material.t_eps' is given twice" "${dem[@]}" --config twice.cfg
    printf 'material.t_eps = 0.02\n[material]\nt_eps = 0.03\n' > spelt-twice.cfg
    expect_refusal "--config spelt-twice.cfg: key 'material.t_eps' is given twice" "${dem[@]}" --config spelt-twice.cfg
    # Once in the file and once on the command line: legal, the command line wins.
    printf '[material]\nt_eps = 0.02\n' > once.cfg
    "${dem[@]}" --config once.cfg --material.t_eps 0.03 -q
    h5dump -a /parameters/dem-run/material.t_eps out.h5 | grep -q '"0.0299999' || fail "the command line does not win"
    rm -f out.h5
    ;;
  nested-config)
    disc
    printf 'config = other.cfg\n' > nested.cfg
    message="--config nested.cfg: 'config' cannot be set inside a config file"
    expect_refusal "$message" "${dem[@]}" --config nested.cfg
    expect_refusal "$message" "$bin/mesh-gen" voronoi --cells 8x4 --config nested.cfg -o out.h5
    ;;
  config-file)
    mkdir folder
    expect_refusal "--config folder: is a directory, not a file of 'key = value' lines" \
      "$bin/mesh-gen" voronoi --cells 8x4 --config folder -o out.h5
    expect_refusal "--config /dev/null: not a regular file" "$bin/mesh-gen" voronoi --cells 8x4 --config /dev/null -o out.h5
    printf 'seed = 3\n\0\001\002' > binary.cfg
    expect_refusal "binary.cfg: the --config file holds a NUL byte: not a text file" \
      "$bin/mesh-gen" voronoi --cells 8x4 --config binary.cfg -o out.h5
    # A pipe (the shell's <(...)) is read.
    "$bin/mesh-gen" voronoi --cells 8x4 --config <(printf 'seed = 4\n') -q -o out.h5 || fail "--config from a pipe"
    rm -f out.h5
    ;;
  ignored-option)
    mg=("$bin/mesh-gen" voronoi -o out.h5)
    expect_refusal "--size: applies to --shape rect; a disc takes --diameter" \
      "${mg[@]}" --shape disc --size 0.4x0.2 --cells 60
    expect_refusal "--diameter: applies to --shape disc; a rectangle takes --size" \
      "${mg[@]}" --shape rect --diameter 0.4 --cells 8x4
    printf 'shape = disc\nsize = 0.4x0.2\n' > disc.cfg
    expect_refusal "--size: applies to --shape rect" "${mg[@]}" --cells 60 --config disc.cfg
    ;;
  scene-values)
    disc
    "$bin/mesh-gen" triangular --nodes 60x20 --spacing 1e-3 -q -o strip.h5
    expect_refusal "--material.beam_modulus = '0': must be positive" "${dem[@]}" --material.beam_modulus 0
    expect_refusal "--material.grain_modulus = '0': must be positive" "${dem[@]}" --material.grain_modulus 0
    expect_refusal "--integrator.dt = '1e-300': 1e+294 steps to reach stop.t_max = 1e-06 s, more than 1e+12" \
      "${dem[@]}" --integrator.dt 1e-300
    expect_refusal "--integrator.dt = '1e-300':" \
      "$bin/rubber-run" --scene "$scenes/stretch.ini" strip.h5 --integrator.dt 1e-300 -o out.h5
    grep -qF "steps to reach stop.t_max" stderr.txt || fail "rubber-run: the step count is not named"
    ;;
  same-input)
    disc
    "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 2e-6 -q -o run.h5
    "$bin/fragment-count" run.h5 -q -o a.h5
    cp a.h5 b.h5
    ln -s a.h5 link.h5
    fit=("$bin/powerlaw-fit" --format text -o out.txt)
    expect_refusal "inputs 'a.h5' and './a.h5' are one file" "${fit[@]}" a.h5 ./a.h5
    expect_refusal "inputs 'a.h5' and 'link.h5' are one file" "${fit[@]}" a.h5 link.h5
    expect_refusal "inputs 'a.h5' and '-' are one file" "${fit[@]}" a.h5 - < a.h5
    expect_refusal "inputs 'a.h5' and 'b.h5' are copies of one file (the same /provenance file_uuid" \
      "${fit[@]}" a.h5 b.h5
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case"
