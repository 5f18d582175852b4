#!/usr/bin/env bash
# Benchmark of fragment-count on a 10^6-cell run (goal: under 2 s, read + union-find + write).
# Usage: bench/fragment_count.sh [BUILD_DIR]   (REPEATS=5 by default; BUILD_DIR defaults to build)
# The input: mesh-gen voronoi 1000x1000 (10^6 cells, about 3 10^6 beams), turned into a run of 3 frames
# by the test helper tests/e2e/fragment_count_make_run (built with the tests), with beams broken at
# random: 60% in the final frame (one large fragment and ~6.6 10^4 small ones), and all of them
# (10^6 single cells: the worst case for sorting and writing). Inputs are kept in bench/out and
# reused while the binaries are older than them. Prints a Markdown table: median, min and max wall
# time over the repeats, median CPU time, peak memory (max RSS), output size.
set -euo pipefail
build=${1:-build}
repeats=${REPEATS:-5}
out=bench/out
mkdir -p "$out"
command -v /usr/bin/time >/dev/null || { echo "bench: needs GNU time: apt-get install -y time" >&2; exit 1; }
fc=$build/tools/fragment-count
mg=$build/tools/mesh-gen
make_run=$build/tests/e2e/fragment_count_make_run
for b in "$fc" "$mg" "$make_run"; do
  [[ -x $b ]] || { echo "bench: $b missing: cmake --build $build (with FRACTURE_TESTS=ON)" >&2; exit 1; }
done

# Inputs (made once).
if [[ ! -s $out/fc-mesh.h5 || $mg -nt $out/fc-mesh.h5 ]]; then
  echo "making the 10^6-cell mesh ..." >&2
  "$mg" voronoi --shape rect --size 10x10 --cells 1000x1000 --seed 1 -q -o "$out/fc-mesh.h5"
fi
for p in 0.6 1.01; do
  if [[ ! -s $out/fc-run-$p.h5 || $make_run -nt $out/fc-run-$p.h5 || $out/fc-mesh.h5 -nt $out/fc-run-$p.h5 ]]; then
    echo "making the run with break fraction $p ..." >&2
    "$make_run" "$out/fc-mesh.h5" "$out/fc-run-$p.h5" --frames 3 --break-fraction "$p" --seed 1
  fi
done

# run NAME OUTPUT COMMAND...: times COMMAND `repeats` times and prints one table row: wall time
# (median, min, max) and the median CPU time (user + system; less disturbed by a busy machine).
run() {
  local name=$1 output=$2; shift 2
  local times=() cpus=() mems=()
  for ((r = 0; r < repeats; r++)); do
    /usr/bin/time -f "%e %U %S %M" -o "$out/time.txt" "$@" >/dev/null
    read -r t u s m <"$out/time.txt"
    times+=("$t"); cpus+=("$(awk -v u="$u" -v s="$s" 'BEGIN { print u + s }')"); mems+=("$m")
  done
  local sorted=($(printf '%s\n' "${times[@]}" | sort -g))
  local cpu_sorted=($(printf '%s\n' "${cpus[@]}" | sort -g))
  local median=${sorted[$((repeats / 2))]}
  local peak=$(printf '%s\n' "${mems[@]}" | sort -g | tail -1)
  local size=$(stat -c %s "$output")
  awk -v n="$name" -v med="$median" -v lo="${sorted[0]}" -v hi="${sorted[$((repeats - 1))]}" \
    -v cpu="${cpu_sorted[$((repeats / 2))]}" -v p="$peak" -v s="$size" \
    'BEGIN { printf "| %s | %s | %s | %s | %.2f | %.0f | %.1f |\n", n, med, lo, hi, cpu, p / 1024, s / 1048576 }'
}

cells=$(h5ls -S "$out/fc-mesh.h5/particles/cells/area" | awk '{gsub(/[{}\/]/, " "); print $3}')
beams=$(h5ls -S "$out/fc-mesh.h5/connectivity/beams/length" | awk '{gsub(/[{}\/]/, " "); print $3}')
echo "fragment-count, $cells cells, $beams beams, $repeats repeats each, $(nproc) cores, $(date -u +%Y-%m-%d)," \
  "load average $(cut -d' ' -f1 /proc/loadavg)"
echo "run files: $(stat -c %s "$out/fc-run-0.6.h5" | awk '{printf "%.0f MB", $1 / 1048576}') each"
echo
echo "| workload | median s | min s | max s | median CPU s | peak MB | output MB |"
echo "|---|---|---|---|---|---|---|"
run "60% of beams broken, file to file" "$out/fc-frag.h5" "$fc" "$out/fc-run-0.6.h5" -q -o "$out/fc-frag.h5"
run "60% broken, stdin to stdout" "$out/fc-frag-pipe.h5" \
  bash -c "cat '$out/fc-run-0.6.h5' | '$fc' - -q > '$out/fc-frag-pipe.h5'"
run "60% broken, --time-series (3 frames)" "$out/fc-frag-ts.h5" \
  "$fc" "$out/fc-run-0.6.h5" -q --time-series -o "$out/fc-frag-ts.h5"
run "all beams broken (10^6 fragments)" "$out/fc-frag-dust.h5" "$fc" "$out/fc-run-1.01.h5" -q -o "$out/fc-frag-dust.h5"
echo
"$fc" "$out/fc-run-0.6.h5" -o "$out/fc-frag.h5" 2>&1 | sed "s/^/    /"
