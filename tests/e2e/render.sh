#!/usr/bin/env bash
# End-to-end checks of render (pictures) and h5-xdmf (XDMF sidecars) on real runs: a 300-cell disc
# exploded by dem-run for 20 µs (5 frames), a small rubber sheet, a mesh.
# Usage: render.sh BIN_DIR SCENES_DIR WORK_DIR CASE
set -euo pipefail
bin=$1 scenes=$2 work=$3 case=$4
rm -rf "$work" && mkdir -p "$work" && cd "$work"
rd=$bin/render
hx=$bin/h5-xdmf

fail() { echo "FAIL: $*" >&2; exit 1; }

# The 300-cell disc of the dem-run tests and a short explosion of it: frames every 5 µs.
make_run() {
  "$bin/mesh-gen" voronoi --shape disc --diameter 0.209 --cells 300 --seed "${1:-7}" -q -o "${2:-mesh.h5}"
  "$bin/dem-run" --scene "$scenes/explosion.ini" "${2:-mesh.h5}" --stop.t_max 2e-5 --output.frame_interval 5e-6 \
    -q -o "${3:-run.h5}"
}
# Number of rows of a dataset, as h5dump prints its dataspace.
rows() { h5dump -H -d "$2" "$1" | sed -n 's/.*DATASPACE *SIMPLE { ( \([0-9]*\).*/\1/p' | head -1; }
# Bytes of a file as hex, from an offset.
bytes() { od -An -tx1 -j "$2" -N "$3" "$1" | tr -d ' \n'; }
# PNG checks: magic bytes, then the IHDR width and height; prints "WIDTHxHEIGHT".
png_size() {
  [[ $(bytes "$1" 0 8) == 89504e470d0a1a0a ]] || fail "$1: not a PNG file (magic bytes)"
  [[ $(bytes "$1" 12 4) == 49484452 ]] || fail "$1: no IHDR chunk first"
  echo "$((16#$(bytes "$1" 16 4)))x$((16#$(bytes "$1" 20 4)))"
}
# XML well-formedness: xmllint when there is one, else a look at the first and last lines.
xml_ok() {
  if command -v xmllint >/dev/null; then
    xmllint --noout "$1" || fail "$1: not well-formed XML"
  else
    head -1 "$1" | grep -q '^<?xml' || fail "$1: no XML declaration"
  fi
}
no_temporaries() {
  if ls -A . | grep -q '\.tmp-'; then fail "temporary files left behind: $(ls -A | grep '\.tmp-')"; fi
}
# expect_refusal "what the message must name" command...: exit 2, the message names the fault, no
# picture or sidecar left behind.
expect_refusal() {
  local needle=$1; shift
  set +e; "$@" >stdout.txt 2>stderr.txt; local rc=$?; set -e
  cat stderr.txt
  [[ $rc -eq 2 ]] || fail "exit $rc, expected 2: $*"
  grep -qF -- "$needle" stderr.txt || fail "message does not name '$needle': $*"
  [[ ! -e out.png && ! -e out.svg && ! -e out.xmf ]] || fail "output left behind: $*"
  no_temporaries
}

case $case in
  help)
    "$rd" --help | grep -q "Example" || fail "render --help has no example"
    "$rd" --help | grep -q -- "--fragments" || fail "render --help does not document --fragments"
    "$hx" --help | grep -q "Example" || fail "h5-xdmf --help has no example"
    "$rd" --version | grep -qE "^render [0-9]" || fail "render --version"
    "$hx" --version | grep -qE "^h5-xdmf [0-9]" || fail "h5-xdmf --version"
    set +e; "$rd" >/dev/null 2>&1; rc=$?; set -e
    [[ $rc -eq 2 ]] || fail "render without arguments: exit $rc, expected 2"
    ;;
  pictures)
    make_run
    n=$(rows run.h5 /particles/cells/mass)
    [[ $n -gt 250 ]] || fail "unexpected cell count '$n'"
    # PNG: the size it reports is the size it wrote; the width asked for.
    "$rd" run.h5 -o run.png --width 640 2>stderr.txt
    cat stderr.txt
    size=$(png_size run.png)
    [[ ${size%x*} -eq 640 ]] || fail "run.png is $size, asked for width 640"
    grep -q "wrote run.png ($size, frame 4)" stderr.txt || fail "reported size differs from $size, or not the final frame"
    "$rd" run.h5 -o fixed.png --width 500 --height 300 -q
    [[ $(png_size fixed.png) == 500x300 ]] || fail "fixed.png is $(png_size fixed.png), asked for 500x300"
    # SVG: XML, one filled path per cell at least.
    "$rd" run.h5 -o run.svg --axes -q
    xml_ok run.svg
    grep -q '<svg' run.svg || fail "run.svg has no svg element"
    filled=$(grep -c 'fill-rule:nonzero;fill:rgb(' run.svg || true)
    [[ $filled -ge $n ]] || fail "run.svg has $filled filled paths for $n cells"
    # Every colouring, frames by index and by time, a mesh, standard output.
    "$rd" run.h5 --frame 0 --colour strain --beams broken -q -o strain.png
    "$rd" run.h5 --time 1e-5 --colour angle --beams off -q -o angle.png
    "$rd" run.h5 --colour /particles/cells/area --range 0,2e-4 -q -o area.svg
    "$rd" mesh.h5 -q -o mesh.png
    "$rd" - --format svg -q -o - <run.h5 >stdout.svg
    xml_ok stdout.svg
    "$bin/fragment-count" run.h5 -q -o fragments.h5
    "$rd" run.h5 --fragments fragments.h5 -o fragments.png 2>stderr.txt
    cat stderr.txt
    ! grep -q warning stderr.txt || fail "warning for the fragments of this very run"
    for f in strain.png angle.png mesh.png fragments.png; do png_size "$f" >/dev/null; done
    xml_ok area.svg
    no_temporaries
    ;;
  movie)
    make_run
    mkdir frames
    "$rd" run.h5 --all-frames --colour speed --width 320 -o frames/explosion-%04d.png 2>stderr.txt
    cat stderr.txt
    grep -q "wrote 5 pictures" stderr.txt || fail "expected 5 pictures"
    first=$(png_size frames/explosion-0000.png)
    for k in 0 1 2 3 4; do
      f=$(printf 'frames/explosion-%04d.png' "$k")
      [[ $(png_size "$f") == "$first" ]] || fail "$f differs in size from the first frame: one view for the sequence"
    done
    [[ $(ls frames | wc -l) -eq 5 ]] || fail "stray files in frames/: $(ls frames)"
    "$rd" run.h5 --all-frames --every 2 --width 320 -q -o frames/every-%d.svg
    [[ -e frames/every-0.svg && -e frames/every-2.svg && ! -e frames/every-3.svg ]] || fail "--every 2: $(ls frames)"
    ;;
  rubber)
    "$bin/mesh-gen" triangular --nodes 40x16 --spacing 1e-3 --notch 0.01 -q -o sheet.h5
    "$bin/rubber-run" --scene "$scenes/stretch.ini" sheet.h5 --stop.t_max 5e-5 --output.frame_interval 2.5e-5 \
      --crack.seed_length 0.01 -q -o crack.h5
    "$rd" crack.h5 -o crack.png --axes 2>stderr.txt
    cat stderr.txt
    png_size crack.png >/dev/null
    "$rd" crack.h5 -o crack.svg -q
    xml_ok crack.svg
    "$rd" sheet.h5 -o sheet.png -q
    "$hx" crack.h5 -q
    xml_ok crack.xmf
    grep -q 'crack.h5:/particles/nodes/position/value|' crack.xmf || fail "crack.xmf: no node positions"
    grep -q 'crack.h5:/connectivity/bonds/trajectory/strain/value|' crack.xmf || fail "crack.xmf: no bond strains"
    ! grep -q 'TopologyType="Mixed"' crack.xmf || fail "crack.xmf: polygons in a node mesh"
    ;;
  xdmf)
    make_run
    n=$(rows run.h5 /particles/cells/mass)
    b=$(rows run.h5 /connectivity/beams/pairs)
    "$hx" run.h5 2>stderr.txt
    cat stderr.txt
    [[ -e run.xmf ]] || fail "no run.xmf next to run.h5"
    xml_ok run.xmf
    # Every reference names a dataset of run.h5 that exists.
    refs=$(grep -o 'run\.h5:/[^<|]*' run.xmf | sed 's/^run\.h5://' | sort -u)
    [[ -n $refs ]] || fail "run.xmf refers to no dataset"
    for path in $refs; do h5dump -H -d "$path" run.h5 >/dev/null 2>&1 || fail "run.xmf refers to missing $path"; done
    echo "$refs" | grep -qx /particles/cells/position/value || fail "no positions referenced"
    echo "$refs" | grep -qx /connectivity/beams/trajectory/strain/value || fail "no beam strains referenced"
    # Dimensions: 5 frames of N cells and B beams; one grid per frame for cells, beams and polygons.
    grep -q "position/value|4 0 0:1 1 1:1 $n 2:5 $n 2<" run.xmf || fail "no slab of the final frame with [5,$n,2]"
    grep -q "strain/value|4 0:1 1:1 $b:5 $b<" run.xmf || fail "no slab of the final strains with [5,$b]"
    [[ $(grep -c '<Time Value=' run.xmf) -eq 15 ]] || fail "expected 15 timed grids"
    grep -q "<Topology Name=\"reference_polygons\" TopologyType=\"Mixed\" NumberOfElements=\"$n\">" run.xmf \
      || fail "no polygon topology of $n cells"
    # XDMF 2 flavour: HyperSlab DataItems over the whole [T,N,2] dataset.
    "$hx" run.h5 --flavour xdmf2 -q -o run2.xmf
    xml_ok run2.xmf
    grep -q "Dimensions=\"5 $n 2\" NumberType=\"Float\" Precision=\"8\" Format=\"HDF\">run.h5:/particles/cells/position/value<" \
      run2.xmf || fail "run2.xmf: no [5,$n,2] positions"
    grep -q 'ItemType="HyperSlab"' run2.xmf || fail "run2.xmf: no HyperSlab"
    # A mesh, fragments, another folder, standard output.
    "$hx" mesh.h5 -q
    xml_ok mesh.xmf
    grep -q 'mesh.h5:/particles/cells/centroid<' mesh.xmf || fail "mesh.xmf: no centroids"
    "$bin/fragment-count" run.h5 -q -o fragments.h5
    mkdir sub
    "$hx" run.h5 --fragments fragments.h5 -q -o sub/run.xmf
    grep -q '\.\./fragments\.h5:/fragments/cell_fragment<' sub/run.xmf || fail "sub/run.xmf: no fragment labels"
    grep -q '\.\./run\.h5:/particles/cells/mass<' sub/run.xmf || fail "sub/run.xmf: references not relative to it"
    "$hx" run.h5 -q -o - >stdout.xmf
    xml_ok stdout.xmf
    # The same sidecar but for its provenance (another command line, maybe another second).
    cmp -s <(grep -v '<Information Name="provenance"' stdout.xmf) <(grep -v '<Information Name="provenance"' run.xmf) ||
      fail "standard output differs from run.xmf"
    no_temporaries
    ;;
  bad-input)
    make_run
    "$bin/../tests/e2e/make_bad_files" .
    echo "not hdf5" > notes.txt
    expect_refusal "missing.h5: no such file" "$rd" missing.h5 -o out.png
    expect_refusal "notes.txt: not an HDF5 file" "$rd" notes.txt -o out.png
    expect_refusal "nomesh.h5: holds no mesh" "$rd" nomesh.h5 -o out.png
    expect_refusal "format version 2.0 is not supported" "$rd" version2.h5 -o out.png
    expect_refusal "standard input is empty" "$rd" - -o out.png </dev/null
    expect_refusal "'out.jpg': the picture's format comes from its extension" "$rd" run.h5 -o out.jpg
    expect_refusal "--frame 9: run.h5 has frames 0..4" "$rd" run.h5 --frame 9 -o out.png
    expect_refusal "--colour nosuch: run.h5 has no dataset or time series" "$rd" run.h5 --colour nosuch -o out.png
    expect_refusal "--colour vertex_offset" "$rd" run.h5 --colour vertex_offset -o out.png
    expect_refusal "--colour fragment: give the fragments file" "$rd" run.h5 --colour fragment -o out.png
    expect_refusal "--beams: unknown mode 'maybe'" "$rd" run.h5 --beams maybe -o out.png
    expect_refusal "--time: mesh.h5 is a mesh file" "$rd" mesh.h5 --time 1e-5 -o out.png
    expect_refusal "--colour speed: mesh.h5 is a mesh" "$rd" mesh.h5 --colour speed -o out.png
    expect_refusal "frame-number pattern" "$rd" run.h5 --all-frames -o out.png
    expect_refusal "--range: MAX must be above MIN" "$rd" run.h5 --range 2,1 -o out.png
    expect_refusal "--view" "$rd" run.h5 --view 0,0,1 -o out.png
    expect_refusal "give one of them" "$rd" run.h5 --frame 1 --time 1e-5 -o out.png
    expect_refusal "folder 'nowhere' does not exist" "$rd" run.h5 -o nowhere/out.png
    expect_refusal "expected fragments" "$rd" run.h5 --fragments mesh.h5 -o out.png
    # Fragments of another mesh (200 cells): the labels do not fit.
    "$bin/mesh-gen" voronoi --shape disc --diameter 0.17 --cells 200 --seed 7 -q -o other-mesh.h5
    "$bin/dem-run" --scene "$scenes/explosion.ini" other-mesh.h5 --stop.t_max 1e-5 -q -o other.h5
    "$bin/fragment-count" other.h5 -q -o other-fragments.h5
    expect_refusal "/fragments/cell_fragment" "$rd" run.h5 --fragments other-fragments.h5 -o out.png
    expect_refusal "/fragments/cell_fragment" "$hx" run.h5 --fragments other-fragments.h5 -o out.xmf
    expect_refusal "not standard input" "$hx" - -o out.xmf <run.h5
    expect_refusal "missing.h5: no such file" "$hx" missing.h5 -o out.xmf
    expect_refusal "nomesh.h5: holds no mesh" "$hx" nomesh.h5 -o out.xmf
    expect_refusal "--flavour: unknown value" "$hx" run.h5 --flavour vtk -o out.xmf
    expect_refusal "is the input FILE" "$hx" run.h5 -o run.h5
    ;;
  *) fail "unknown case $case" ;;
esac
echo "PASS $case"
