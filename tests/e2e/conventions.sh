#!/usr/bin/env bash
# The conventions every tool promises (README, "Conventions of every tool"), checked tool by tool:
# --help with an example, --version, a bad option refused with exit 2, -q silences standard error,
# --config FILE takes effect (the command line winning over it); and the provenance of the outputs
# without a /provenance group (PNG text chunk, SVG <metadata>, CSV and `key value` first line, XDMF Information).
# Usage: conventions.sh SOURCE_DIR BIN_DIR WORK_DIR CASE [COMMAND ...]
#   CASE is a tool ("dem-run", "mesh-gen.voronoi"), "provenance", or "every-tool" followed by the
#   commands the other cases cover (they must be every tool of tools/ and every mesh-gen subcommand).
set -euo pipefail
src=$1 bin=$2 work=$3 case=$4
shift 4
scenes=$src/data/scenes
source "$(cd "$(dirname "$0")" && pwd)/lib.sh"  # fail
rm -rf "$work" && mkdir -p "$work" && cd "$work"

# Inputs, small and short: a 300-cell disc exploded for 20 µs (5 frames), its fragments, a rubber strip
# stretched for 0.1 ms.
mesh() { "$bin/mesh-gen" voronoi --shape disc --diameter 0.209 --cells 300 --seed 7 -q -o mesh.h5; }
dem_run() {
  mesh
  "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 2e-5 --output.frame_interval 5e-6 -q -o run.h5
}
strip() { "$bin/mesh-gen" triangular --nodes 60x20 --spacing 1e-3 -q -o strip.h5; }
rubber_short=(--stop.t_max 1e-4 --output.frame_interval 5e-5)

# An attribute of a file, as h5dump prints its value.
attr() { h5dump -a "$2" "$1" | sed -n 's/.*(0): *//p' | tr -d '"'; }
# Rows of a dataset.
rows() { h5dump -H -d "$2" "$1" | sed -n 's/.*DATASPACE *SIMPLE { ( \([0-9]*\).*/\1/p' | head -1; }
# A resolved parameter of a run.
param() { "$bin/observables" "$1" --parameter "$2"; }
# same A B: the two numbers are equal (1e-5 and 1.0000000000000001e-05 are).
same() { awk -v a="$1" -v b="$2" 'BEGIN { exit !(a + 0 == b + 0 && a != "") }'; }

# quiet CMD...: without -q the command says something on standard error, with -q nothing (it succeeds).
quiet() {
  "$@" >/dev/null 2>loud.txt || fail "$*: exit $?"
  [[ -s loud.txt ]] || fail "$*: says nothing without -q (cannot check that -q silences it)"
  "$@" -q >/dev/null 2>quiet.txt || fail "$* -q: exit $?"
  [[ ! -s quiet.txt ]] || fail "$* -q: standard error not empty: $(cat quiet.txt)"
}
# refused NEEDLE CMD...: exit 2, the message names NEEDLE.
refused() {
  local needle=$1; shift
  set +e; "$@" >stdout.txt 2>stderr.txt; local rc=$?; set -e
  [[ $rc -eq 2 ]] || fail "exit $rc, expected 2: $*"
  grep -qF -- "$needle" stderr.txt || fail "message does not name '$needle': $* ($(cat stderr.txt))"
}

# The checks every command shares: help with an example naming the tool, version, -q and --config in
# the help, bad options and unreadable or wrong config files refused with exit 2.
common() {
  local tool=$1
  local cmd=("$bin/$tool" "${@:2}") name="$tool${2:+ $2}"
  "${cmd[@]}" --help > help.txt || fail "$name --help: exit $?"
  awk -v ex="  $name " 'seen && index($0, ex) == 1 { found = 1 } /^Example/ { seen = 1 } END { exit !found }' help.txt ||
    fail "$name --help: no example of '$name'"
  for opt in --config --quiet -q --version; do
    grep -qF -- "$opt" help.txt || fail "$name --help does not document $opt"
  done
  # Only the tools whose output is an HDF5 file alone may say that '-' writes the HDF5 file.
  case $name in
    "mesh-gen voronoi" | "mesh-gen triangular" | dem-run | rubber-run | fragment-count) ;;
    *) ! grep -q 'writes the HDF5 file' help.txt || fail "$name --help: -o says it writes the HDF5 file" ;;
  esac
  "${cmd[@]}" --version | grep -qE "^$name [0-9]" || fail "$name --version"
  refused "--no-such-option" "${cmd[@]}" --no-such-option
  refused "missing.cfg" "${cmd[@]}" --config missing.cfg
  echo "no_such_key = 1" > unknown.cfg
  refused "no_such_key" "${cmd[@]}" --config unknown.cfg
}

[[ $case == every-tool || $case == provenance ]] || common ${case/./ }

case $case in
  every-tool)
    # The cases cover every tool and every mesh-gen subcommand: a new one must join them.
    expected=$(for f in "$src"/tools/*.cpp; do basename "$f" .cpp; done | grep -vx mesh-gen
               "$bin/mesh-gen" --help | sed -n 's/^  \([a-z-]*\) .*/mesh-gen.\1/p')
    [[ $(sort <<< "$expected") == $(printf '%s\n' "$@" | sort) ]] ||
      fail "the tools and subcommands ($(echo $expected)) differ from the tested ones ($*)"
    ;;
  mesh-gen.voronoi)
    quiet "$bin/mesh-gen" voronoi --cells 8x4 -o q.h5
    printf 'shape = rect\ncells = 8x4\nseed = 3\nquiet = true\n' > mesh.cfg
    "$bin/mesh-gen" voronoi --config mesh.cfg -o a.h5 2>stderr.txt
    [[ ! -s stderr.txt ]] || fail "quiet = true in the config file: standard error not empty"
    cells=$(rows a.h5 /particles/cells/area)
    [[ $cells == 32 ]] || fail "cells = 8x4 in the config file: $cells cells"
    [[ $(attr a.h5 /parameters/mesh-gen/seed) == 3 ]] || fail "seed = 3 in the config file not recorded"
    "$bin/mesh-gen" voronoi --config mesh.cfg --seed 5 -o b.h5
    [[ $(attr b.h5 /parameters/mesh-gen/seed) == 5 ]] || fail "--seed 5 does not win over the config file"
    ;;
  mesh-gen.triangular)
    quiet "$bin/mesh-gen" triangular --nodes 5x4 --spacing 1e-3 -o q.h5
    printf 'nodes = 5x4\nspacing = 2e-3\n' > mesh.cfg
    "$bin/mesh-gen" triangular --config mesh.cfg -q -o a.h5
    nodes=$(rows a.h5 /particles/nodes/reference_position)
    [[ $nodes == 20 ]] || fail "nodes = 5x4 in the config file: $nodes nodes"
    [[ $(attr a.h5 /parameters/mesh-gen/spacing) == 0.002 ]] || fail "spacing = 2e-3 in the config file not recorded"
    ;;
  mesh-gen.check)
    mesh
    "$bin/mesh-gen" check mesh.h5 | grep -q '^ok' || fail "check without -q prints no summary"
    "$bin/mesh-gen" check mesh.h5 -q > out.txt 2>&1 || fail "check -q: exit $?"
    [[ ! -s out.txt ]] || fail "check -q prints: $(cat out.txt)"
    printf 'input = mesh.h5\nquiet = true\n' > check.cfg
    "$bin/mesh-gen" check --config check.cfg > out.txt 2>&1 || fail "check --config: exit $?"
    [[ ! -s out.txt ]] || fail "quiet = true in the config file: check prints $(cat out.txt)"
    # -q keeps the exit code and the error messages.
    "$bin/../tests/e2e/make_bad_files" .
    refused "nomesh.h5" "$bin/mesh-gen" check nomesh.h5 -q
    ;;
  dem-run)
    mesh
    quiet "$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 5e-6 -o q.h5
    # Tool options and scene keys (dotted, or under a [section]) in the file; the command line wins.
    printf 'scene = %s\nseed = 5\nstop.t_max = 1e-5\n[material]\nt_eps = 0.02\n' "$scenes/explosion.ini" > run.cfg
    "$bin/dem-run" --config run.cfg mesh.h5 --material.t_eps 0.025 -q -o a.h5
    [[ $(param a.h5 seed) == 5 ]] || fail "seed = 5 in the config file: $(param a.h5 seed)"
    same "$(param a.h5 stop.t_max)" 1e-5 || fail "stop.t_max = 1e-5 in the config file: $(param a.h5 stop.t_max)"
    same "$(param a.h5 material.t_eps)" 0.025 || fail "--material.t_eps does not win over the config file"
    awk -v t="$(attr a.h5 /end_time)" 'BEGIN { exit !(t > 0.9e-5 && t < 1.1e-5) }' || fail "the run did not stop at 1e-5 s"
    printf 'scene = %s\nmaterial.no_such_key = 1\n' "$scenes/explosion.ini" > typo.cfg
    refused "material.no_such_key" "$bin/dem-run" --config typo.cfg mesh.h5 -o out.h5
    ;;
  rubber-run)
    strip
    quiet "$bin/rubber-run" --scene "$scenes/stretch.ini" strip.h5 "${rubber_short[@]}" -o q.h5
    printf 'scene = %s\nseed = 4\n[stop]\nt_max = 1e-4\n[output]\nframe_interval = 5e-5\n[loading]\nstretch_y = 3\n' \
      "$scenes/stretch.ini" > run.cfg
    "$bin/rubber-run" --config run.cfg strip.h5 --loading.stretch_y 2.5 -q -o a.h5
    [[ $(param a.h5 seed) == 4 ]] || fail "seed = 4 in the config file: $(param a.h5 seed)"
    same "$(param a.h5 stop.t_max)" 1e-4 || fail "[stop] t_max = 1e-4 in the config file: $(param a.h5 stop.t_max)"
    same "$(param a.h5 loading.stretch_y)" 2.5 || fail "--loading.stretch_y does not win over the config file"
    ;;
  observables)
    dem_run
    "$bin/observables" run.h5 -q > all.csv 2>stderr.txt
    [[ ! -s stderr.txt ]] || fail "observables -q: standard error not empty"
    printf 'columns = kinetic_energy_translational\n' > obs.cfg
    "$bin/observables" run.h5 --config obs.cfg > one.csv
    header=$(awk '!/^#/ { print; exit }' one.csv)
    [[ $header == time_s,kinetic_energy_translational* && $header != *,*,* ]] ||
      fail "columns = kinetic_energy_translational in the config file: '$header'"
    [[ $(awk '!/^#/ { print; exit }' all.csv) == *,*,* ]] || fail "observables without --columns: one column only"
    ;;
  fragment-count)
    dem_run
    quiet "$bin/fragment-count" run.h5 -o q.h5
    printf 'min-cells = 2\nbins-per-decade = 4\n' > frag.cfg
    "$bin/fragment-count" run.h5 --config frag.cfg --bins-per-decade 3 -q -o a.h5
    [[ $(attr a.h5 /parameters/fragment-count/min-cells) == 2 ]] || fail "min-cells = 2 in the config file not recorded"
    [[ $(attr a.h5 /parameters/fragment-count/bins-per-decade) == 3 ]] || fail "--bins-per-decade does not win over the config file"
    ;;
  powerlaw-fit)
    awk 'BEGIN { for (k = 1; k <= 200; k++) printf "%.6g\n", (1 - (k - 0.5) / 200) ^ (-1 / 1.5) }' > values.txt
    quiet "$bin/powerlaw-fit" values.txt --format text --bootstrap 0 --gof-samples 0 -o q.txt
    printf 'format = text\nbootstrap = 0\ngof-samples = 0\n' > fit.cfg
    "$bin/powerlaw-fit" values.txt --config fit.cfg -q > fit.txt
    grep -q '^alpha ' fit.txt || fail "format = text in the config file: no 'alpha' line"
    ;;
  wave-speed)
    quiet "$bin/wave-speed" --theory dem --young 4.1e8 --poisson 0.2 --density 5000 -o q.h5
    printf 'theory = dem\nyoung = 4.1e8\npoisson = 0.2\ndensity = 5000\nformat = text\n' > theory.cfg
    "$bin/wave-speed" --config theory.cfg -q > a.txt
    "$bin/wave-speed" --config theory.cfg --young 1.64e9 -q > b.txt
    [[ -s a.txt ]] && ! cmp -s a.txt b.txt || fail "--config: no text prediction, or --young does not win over it"
    ;;
  render)
    dem_run
    quiet "$bin/render" run.h5 -o q.png
    printf 'width = 640\nformat = png\n' > render.cfg
    "$bin/render" run.h5 --config render.cfg -q -o a.png
    [[ $(od -An -tu1 -j 16 -N 4 a.png | awk '{ print $1 * 16777216 + $2 * 65536 + $3 * 256 + $4 }') == 640 ]] ||
      fail "width = 640 in the config file: not a PNG 640 pixels wide"
    ;;
  h5-xdmf)
    dem_run
    quiet "$bin/h5-xdmf" run.h5 -o q.xmf
    printf 'flavour = xdmf2\n' > xdmf.cfg
    "$bin/h5-xdmf" run.h5 --config xdmf.cfg -q -o a.xmf
    grep -q 'HyperSlab' a.xmf || fail "flavour = xdmf2 in the config file: no HyperSlab"
    ;;
  provenance)
    dem_run
    uuid=$(attr run.h5 /provenance/file_uuid)
    # provenance_line FILE TOOL: the line names the tool, the version, the input run and its command line.
    check_line() {
      grep -qE "tool=$2 version=[0-9][^ ]* time=[0-9TZ:-]+ .*inputs=$uuid.* command=[^ ]*$2 run.h5" <<< "$1" ||
        fail "$2: provenance line '$1'"
    }
    # PNG: a valid text chunk (length, CRC) with keyword "provenance", right after IHDR; also on standard output
    # and in every picture of a movie.
    "$bin/render" run.h5 -q -o a.png
    "$bin/render" run.h5 -q -o - > b.png
    "$bin/render" run.h5 --all-frames --every 2 -q -o movie-%d.png
    for png in a.png b.png movie-0.png movie-2.png; do
      [[ $(od -An -c -j 37 -N 4 "$png" | tr -d ' ') == tEXt ]] || fail "$png: no tEXt chunk after IHDR"
      text=$(od -An -c -j 41 -N 11 "$png" | tr -d ' ')
      [[ $text == 'provenance\0' ]] || fail "$png: text chunk keyword '$text'"
      check_line "$(tr -d '\000' < "$png" | grep -aom1 'tool=render[ -~]*')" render
    done
    if python3 -c 'import zlib' 2>/dev/null; then
      python3 - a.png <<'EOF' || fail "a.png: a chunk's CRC or length is wrong"
import struct, sys, zlib
data = open(sys.argv[1], "rb").read()
at, types = 8, []
while at < len(data):
    n, t = struct.unpack(">I4s", data[at:at + 8])
    assert zlib.crc32(data[at + 4:at + 8 + n]) == struct.unpack(">I", data[at + 8 + n:at + 12 + n])[0], t
    types.append(t)
    at += 12 + n
assert at == len(data) and types[0] == b"IHDR" and types[1] == b"tEXt" and types[-1] == b"IEND", types
EOF
    fi
    # SVG: <metadata id="provenance"> in the <svg> element, well-formed.
    "$bin/render" run.h5 -q -o a.svg
    xmllint --noout a.svg 2>/dev/null || ! command -v xmllint >/dev/null || fail "a.svg: not well-formed XML"
    check_line "$(sed -n 's/.*<metadata id="provenance">\(.*\)<\/metadata>.*/\1/p' a.svg)" render
    # CSV: the provenance as a '#' first line, the header second.
    "$bin/observables" run.h5 --columns kinetic_energy_translational > a.csv
    check_line "$(head -1 a.csv | sed -n 's/^# //p')" observables
    sed -n 2p a.csv | grep -q '^time_s,kinetic_energy_translational' || fail "a.csv: the header is not the second line"
    # Fragments enough for a fit: a run with beams broken by rule (tests/e2e/fragment_count_make_run).
    "$bin/../tests/e2e/fragment_count_make_run" mesh.h5 broken.h5 --frames 2 --break-fraction 0.6 --seed 3
    "$bin/fragment-count" broken.h5 -q -o fragments.h5
    "$bin/powerlaw-fit" fragments.h5 --format text --bootstrap 0 --gof-samples 0 --histogram-csv hist.csv -q > fit.txt
    head -1 hist.csv | grep -qE "^# tool=powerlaw-fit .*inputs=$(attr fragments.h5 /provenance/file_uuid) command=" ||
      fail "hist.csv: first line '$(head -1 hist.csv)'"
    [[ $(sed -n 2p hist.csv) == center,density,count,lower,upper ]] || fail "hist.csv: the header is not the second line"
    # `key value` text: the provenance as a '#' first line, the keys after it.
    head -1 fit.txt | grep -qE "^# tool=powerlaw-fit .*inputs=$(attr fragments.h5 /provenance/file_uuid) command=" ||
      fail "fit.txt: first line '$(head -1 fit.txt)'"
    "$bin/observables" run.h5 --compare run.h5 > compare.txt
    check_line "$(head -1 compare.txt | sed -n 's/^# //p')" observables
    [[ $(awk '$1 == "rms_position_difference" { print $2 }' compare.txt) == 0 ]] || fail "compare.txt: '$(cat compare.txt)'"
    "$bin/wave-speed" --theory dem --young 4e8 --poisson 0.2 --density 5000 --format text -q > speeds.txt
    head -1 speeds.txt | grep -qE '^# tool=wave-speed version=[0-9][^ ]* time=[0-9TZ:-]+ command=[^ ]*wave-speed --theory' ||
      fail "speeds.txt: first line '$(head -1 speeds.txt)'"
    # XDMF: an Information element named provenance.
    "$bin/h5-xdmf" run.h5 -q -o a.xmf
    xmllint --noout a.xmf 2>/dev/null || ! command -v xmllint >/dev/null || fail "a.xmf: not well-formed XML"
    check_line "$(sed -n 's/.*<Information Name="provenance" Value="\(.*\)"\/>.*/\1/p' a.xmf)" h5-xdmf
    ;;
  *) fail "unknown case $case" ;;
esac
echo "ok: $case"
