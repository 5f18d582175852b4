#!/usr/bin/env bash
# End-to-end checks of mesh-gen through files and pipes. Usage: mesh_gen.sh BIN_DIR WORK_DIR CASE
set -euo pipefail
bin=$1 work=$2 case=$3
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail, expect_refusal
refusal_outputs=(out.h5)
refusal_inputs=('^in' nomesh.h5 version2.h5 notes.txt '^bad-')
rm -rf "$work" && mkdir -p "$work" && cd "$work"
mg=$bin/mesh-gen

case $case in
  help)
    for sub in voronoi triangular check; do
      "$mg" $sub --help | grep -q "Example" || fail "$sub --help has no example"
    done
    "$mg" --help | grep -q voronoi || fail "mesh-gen --help does not list commands"
    "$mg" --version | grep -qE "^mesh-gen [0-9]" || fail "--version"
    set +e; "$mg" >/dev/null 2>&1; rc=$?; set -e
    [[ $rc -eq 2 ]] || fail "no command: exit $rc, expected 2"
    ;;
  pipe)
    # The pipe and the file give the same datasets; the check reads standard input.
    "$mg" voronoi --shape rect --size 0.40x0.20 --cells 40x20 --seed 7 -q -o file.h5
    "$mg" voronoi --shape rect --size 0.40x0.20 --cells 40x20 --seed 7 -q | tee pipe.h5 | "$mg" check - | tee summary.txt
    grep -q "^ok" summary.txt || fail "check through the pipe"
    h5diff --exclude-path /provenance file.h5 pipe.h5 || fail "pipe and file differ"
    "$mg" triangular --nodes 30x20 --spacing 1e-3 --notch 0.01 -q | "$mg" check - | grep -q "^ok" || fail "triangular pipe"
    "$mg" voronoi --shape disc --cells 300 -q | "$mg" check - | grep -q "^ok" || fail "disc pipe"
    ;;
  reproducible)
    # Same options and seed: identical datasets; another seed: different ones.
    "$mg" voronoi --shape disc --diameter 0.4 --cells 1100 --seed 3 -q -o a.h5
    "$mg" voronoi --shape disc --diameter 0.4 --cells 1100 --seed 3 -q -o b.h5
    "$mg" voronoi --shape disc --diameter 0.4 --cells 1100 --seed 4 -q -o c.h5
    h5diff --exclude-path /provenance a.h5 b.h5 || fail "same seed, different data"
    if h5diff -q --exclude-path /provenance --exclude-path /parameters a.h5 c.h5; then fail "different seeds, same data"; fi
    # Provenance: tool, command line and seed recorded.
    h5dump -d /provenance/command_line a.h5 | grep -q -- "--seed 3" || fail "command line not recorded"
    h5dump -d /provenance/seed a.h5 | grep -q '"3"' || fail "seed not recorded"
    h5dump -a /parameters/mesh-gen/cells a.h5 | grep -q '"1100"' || fail "options not recorded"
    ;;
  bad-input)
    "$bin/../tests/e2e/make_bad_files" .
    echo "not hdf5" > notes.txt
    expect_refusal "missing.h5: no such file" "$mg" check missing.h5
    expect_refusal "notes.txt: not an HDF5 file" "$mg" check notes.txt
    expect_refusal "nomesh.h5: holds no mesh" "$mg" check nomesh.h5
    expect_refusal "format version 2.0 is not supported" "$mg" check version2.h5
    expect_refusal "standard input is empty" "$mg" check - </dev/null
    expect_refusal "standard input is not an HDF5 file" "$mg" check - <notes.txt
    expect_refusal "--size" "$mg" voronoi --size -0.4x0.2 --cells 40x20 -o out.h5
    expect_refusal "--size" "$mg" voronoi --size 0x0.2 --cells 40x20 -o out.h5
    expect_refusal "--cells" "$mg" voronoi --cells 0x20 -o out.h5
    expect_refusal "--diameter" "$mg" voronoi --shape disc --diameter -1 --cells 100 -o out.h5
    expect_refusal "--disorder" "$mg" voronoi --cells 40x20 --disorder 1.5 -o out.h5
    expect_refusal "--disorder" "$mg" voronoi --cells 40x20 --disorder -0.1 -o out.h5
    expect_refusal "--shape" "$mg" voronoi --shape hexagon --cells 40x20 -o out.h5
    expect_refusal "--spacing" "$mg" triangular --nodes 10x10 --spacing 0 -o out.h5
    expect_refusal "--nodes" "$mg" triangular --nodes 10 --spacing 1e-3 -o out.h5
    expect_refusal "unknown command 'hexagon'" "$mg" hexagon
    expect_refusal "unrecognised option '--frobnicate'" "$mg" voronoi --cells 4x4 --frobnicate -o out.h5
    ;;
  *) fail "unknown case $case" ;;
esac
echo "PASS $case"
