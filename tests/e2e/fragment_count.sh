#!/usr/bin/env bash
# End-to-end checks of fragment-count through files and pipes.
# Usage: fragment_count.sh BIN_DIR MAKE_RUN WORK_DIR CASE
#   MAKE_RUN is tests/e2e/fragment_count_make_run (a mesh -> run file with beams broken by rule).
set -euo pipefail
bin=$1 make_run=$2 work=$3 case=$4
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail, expect_refusal
refusal_outputs=(out.h5)
refusal_inputs=('^in' notes.txt)
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fc=$bin/fragment-count
mg=$bin/mesh-gen

# values FILE OBJECT: the values of a dataset or (with -a) an attribute, one a line.
values() {
  local flag=-d
  if [[ $1 == -a ]]; then flag=-a; shift; fi
  h5dump -y -w 0 -m %.17g $flag "$2" "$1" |
    awk '/^ *DATA \{/ {on = 1; next} on && /^ *\}/ {exit} on {gsub(/,/, " "); print}' | tr -s ' ' '\n' | grep -v '^$'
}
value() { values "$@" | head -1; }
sum() { awk '{ s += $1 } END { printf "%.17g\n", s }'; }
# close A B [REL]: |A - B| <= REL * max(|A|, |B|)
close() { awk -v a="$1" -v b="$2" -v r="${3:-1e-12}" 'BEGIN { d = a - b; if (d < 0) d = -d; m = (a < 0 ? -a : a);
  if ((b < 0 ? -b : b) > m) m = (b < 0 ? -b : b); exit !(d <= r * m) }'; }

case $case in
  help)
    "$fc" --help | grep -q "Example" || fail "--help has no example"
    "$fc" --help | grep -q -- "--min-cells" || fail "--help does not list --min-cells"
    "$fc" --version | grep -qE "^fragment-count [0-9]" || fail "--version"
    set +e; "$fc" >/dev/null 2>&1; rc=$?; set -e
    [[ $rc -eq 2 ]] || fail "no input: exit $rc, expected 2"
    ;;
  pipe)
    # Through a file and through a pipe: the same fragments (the input's name differs in /parameters).
    "$mg" voronoi --shape rect --size 0.40x0.20 --cells 40x20 --seed 7 -q -o mesh.h5
    "$make_run" mesh.h5 run.h5 --frames 3 --break-fraction 0.6 --seed 3
    "$fc" run.h5 -o file.h5 2>summary.txt
    cat summary.txt
    grep -qE "^fragment-count: frame 2 .*: [0-9]+ fragments, largest .*% of the mass, [0-9]+ single cells$" summary.txt \
      || fail "no one-line summary"
    [[ $(wc -l <summary.txt) -eq 1 ]] || fail "summary is not one line"
    "$mg" voronoi --shape rect --size 0.40x0.20 --cells 40x20 --seed 7 -q | "$make_run" - run-pipe.h5 \
      --frames 3 --break-fraction 0.6 --seed 3
    cat run-pipe.h5 | "$fc" - -q | cat >pipe.h5
    [[ -s pipe.h5 ]] || fail "nothing on standard output"
    h5diff --exclude-path /provenance --exclude-path /parameters file.h5 pipe.h5 || fail "pipe and file differ"
    [[ $(value -a file.h5 /kind) == '"fragments"' ]] || fail "root kind is not fragments"
    # Lineage: this tool, then the run maker, then mesh-gen.
    h5dump -d /provenance/tool file.h5 | grep -q '"fragment-count", "fragment_count_make_run", "mesh-gen"' \
      || fail "provenance lineage not copied"
    # Sizes and conservation.
    f=$(value -a file.h5 /fragments/fragments)
    [[ $(values file.h5 /fragments/mass | wc -l) -eq $f ]] || fail "mass has not $f rows"
    [[ $(values file.h5 /fragments/cell_fragment | wc -l) -eq 800 ]] || fail "cell_fragment has not 800 rows"
    [[ $(values file.h5 /fragments/cell_count | sum) == 800 ]] || fail "cell counts do not add up to 800"
    close "$(values file.h5 /fragments/mass | sum)" "$(value -a file.h5 /fragments/total_mass)" 1e-12 \
      || fail "fragment masses do not add up to the total mass"
    # Histogram: counts add up to the fragments of >= min_cells cells (all of them by default).
    [[ $(values file.h5 /fragments/histogram/count | sum) -eq $f ]] || fail "histogram counts"
    ;;
  known-clusters)
    # A square grid cut in two halves along x = 0.2 from frame 1 on: two fragments of 400 cells (of
    # equal mass but for the rounding of the cell areas, which decides their order).
    "$mg" voronoi --shape rect --size 0.40x0.20 --cells 40x20 --disorder 0 -q -o mesh.h5
    "$make_run" mesh.h5 run.h5 --frames 3 --cut-x 0.2
    "$fc" run.h5 -q -o out-final.h5
    [[ $(value -a out-final.h5 /fragments/fragments) -eq 2 ]] || fail "the cut grid is not in two fragments"
    [[ $(values out-final.h5 /fragments/cell_count | tr '\n' ' ') == "400 400 " ]] || fail "halves are not 400 cells"
    [[ $(value -a out-final.h5 /fragments/frame) -eq 2 ]] || fail "default is not the final frame"
    mapfile -t label < <(values out-final.h5 /fragments/cell_fragment)
    left=${label[0]}
    for j in $(seq 0 19); do for i in $(seq 0 39); do
      want=$(( i < 20 ? left : 1 - left ))
      [[ ${label[$((j * 40 + i))]} -eq $want ]] || fail "cell ($i, $j) is not in the fragment of its half"
    done; done
    # Frame 0 (intact) is one fragment; --time picks the nearest frame; --frame=-3 is frame 0.
    "$fc" run.h5 -q --frame 0 -o out-0.h5
    [[ $(value -a out-0.h5 /fragments/fragments) -eq 1 ]] || fail "intact grid is not one fragment"
    "$fc" run.h5 -q --frame=-3 -o out-m3.h5
    h5diff --exclude-path /provenance --exclude-path /parameters out-0.h5 out-m3.h5 || fail "--frame=-3 is not frame 0"
    "$fc" run.h5 -q --time 0.0012 -o out-t.h5
    [[ $(value -a out-t.h5 /fragments/frame) -eq 1 && $(value -a out-t.h5 /fragments/step) -eq 100 ]] \
      || fail "--time 0.0012 did not pick frame 1"
    # Every beam broken: every cell a fragment; --min-cells 2 empties the histogram but lists them all.
    "$make_run" mesh.h5 dust.h5 --frames 2 --break-fraction 1.01
    "$fc" dust.h5 --min-cells 2 -o out-dust.h5 2>summary.txt
    cat summary.txt
    grep -q "800 fragments (0 of >= 2 cells), largest 0.125% of the mass, 800 single cells" summary.txt \
      || fail "summary of the dust"
    [[ $(value -a out-dust.h5 /fragments/fragments) -eq 800 ]] || fail "dust is not 800 fragments"
    [[ $(value -a out-dust.h5 /fragments/min_cells) -eq 2 ]] || fail "min_cells not recorded"
    [[ $(values out-dust.h5 /fragments/histogram/count | sum) -eq 0 ]] || fail "histogram of >= 2 cells not empty"
    "$fc" dust.h5 -q -o out-dust1.h5
    [[ $(values out-dust1.h5 /fragments/histogram/count | sum) -eq 800 ]] || fail "histogram of all cells"
    ;;
  frames)
    # Time series: one fragment at first, more as beams break, the last entry is the counted frame.
    "$mg" voronoi --shape disc --diameter 0.4 --cells 500 --seed 2 -q -o mesh.h5
    "$make_run" mesh.h5 run.h5 --frames 6 --break-fraction 0.6 --seed 5
    "$fc" run.h5 -q --time-series -o out.h5
    mapfile -t count < <(values out.h5 /fragments/time_series/count)
    mapfile -t step < <(values out.h5 /fragments/time_series/step)
    mapfile -t largest < <(values out.h5 /fragments/time_series/largest_mass)
    [[ ${#count[@]} -eq 6 && ${step[*]} == "0 100 200 300 400 500" ]] || fail "time series has not the 6 frames"
    [[ ${count[0]} -eq 1 ]] || fail "intact disc is not one fragment"
    for k in 1 2 3 4 5; do
      (( count[k] >= count[k - 1] )) || fail "fragment count decreases as beams break"
    done
    [[ ${count[5]} -eq $(value -a out.h5 /fragments/fragments) ]] || fail "last entry is not the final frame"
    close "${largest[0]}" "$(value -a out.h5 /fragments/total_mass)" 1e-12 || fail "intact disc is not all the mass"
    close "${largest[5]}" "$(value out.h5 /fragments/mass)" 1e-12 || fail "largest mass of the final frame"
    # --min-cells counts only fragments of that size in the time series.
    "$fc" run.h5 -q --time-series --min-cells 2 -o out2.h5
    last2=$(values out2.h5 /fragments/time_series/count | tail -1)
    singles=$(values out.h5 /fragments/cell_count | grep -cx 1 || true)
    [[ $last2 -eq $((count[5] - singles)) ]] || fail "--min-cells 2 time series does not leave single cells out"
    ;;
  dem-run)
    # The real chain: mesh-gen | dem-run (explosion, a short run) | fragment-count, through a pipe and
    # through files: the same fragments; every cell counted once, the masses add up.
    scenes=$(dirname "$0")/../../data/scenes
    "$mg" voronoi --shape disc --diameter 0.209 --cells 300 --seed 7 -q -o mesh.h5
    "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 5e-4 -q -o run.h5
    "$fc" run.h5 --time-series -o file.h5 2>summary.txt
    cat summary.txt
    "$mg" voronoi --shape disc --diameter 0.209 --cells 300 --seed 7 -q |
      "$bin/dem-run" --scene "$scenes/explosion.ini" - --stop.t_max 5e-4 -q | "$fc" - --time-series -q >pipe.h5
    h5diff --exclude-path /provenance --exclude-path /parameters file.h5 pipe.h5 || fail "pipe and file differ"
    n=$(values file.h5 /fragments/cell_fragment | wc -l)
    [[ $(values file.h5 /fragments/cell_count | sum) -eq $n ]] || fail "cell counts do not add up to $n"
    close "$(values file.h5 /fragments/mass | sum)" "$(value -a file.h5 /fragments/total_mass)" 1e-12 \
      || fail "fragment masses do not add up to the total mass"
    close "$(values run.h5 /particles/cells/mass | sum)" "$(value -a file.h5 /fragments/total_mass)" 1e-12 \
      || fail "total mass is not the run's"
    h5dump -d /provenance/tool file.h5 | grep -q '"fragment-count", "dem-run", "mesh-gen"' || fail "lineage"
    ;;
  bad-input)
    "$mg" voronoi --shape rect --size 0.40x0.20 --cells 10x5 -q -o in-mesh.h5
    "$make_run" in-mesh.h5 in-run.h5 --frames 3 --break-fraction 0.5
    "$make_run" in-mesh.h5 in-inertia.h5 --corrupt inertia
    "$make_run" in-mesh.h5 in-pairs.h5 --corrupt pairs
    "$make_run" in-mesh.h5 in-intact.h5 --corrupt intact
    echo "not hdf5" > notes.txt
    expect_refusal "missing.h5: no such file" "$fc" missing.h5 -o out.h5
    expect_refusal "notes.txt: not an HDF5 file" "$fc" notes.txt -o out.h5
    expect_refusal "in-mesh.h5: holds a file of kind 'mesh', expected run" "$fc" in-mesh.h5 -o out.h5
    expect_refusal "--frame 3: out of range, in-run.h5 holds 3 frames" "$fc" in-run.h5 --frame 3 -o out.h5
    expect_refusal "--frame -4: out of range" "$fc" in-run.h5 --frame=-4 -o out.h5
    expect_refusal "--frame and --time" "$fc" in-run.h5 --frame 1 --time 0 -o out.h5
    expect_refusal "--min-cells" "$fc" in-run.h5 --min-cells 0 -o out.h5
    expect_refusal "--bins-per-decade" "$fc" in-run.h5 --bins-per-decade 0 -o out.h5
    expect_refusal "in-inertia.h5:/particles/cells/inertia: has 49 values, expected 50" "$fc" in-inertia.h5 -o out.h5
    expect_refusal "in-pairs.h5:/connectivity/beams/pairs: row" "$fc" in-pairs.h5 -o out.h5
    expect_refusal "in-intact.h5:/connectivity/beams/trajectory/intact/value" "$fc" in-intact.h5 -o out.h5
    expect_refusal "in-intact.h5:/connectivity/beams/trajectory/intact/value" "$fc" in-intact.h5 --frame 0 --time-series -o out.h5
    expect_refusal "standard input is empty" "$fc" - -o out.h5 </dev/null
    expect_refusal "unrecognised option '--frobnicate'" "$fc" in-run.h5 --frobnicate -o out.h5
    ;;
  *) fail "unknown case $case" ;;
esac
echo "PASS $case"
