#!/usr/bin/env bash
# Benchmarks of the toolkit's workloads. Usage: bench/run.sh [BIN_DIR]   (REPEATS=5 by default)
# Prints a Markdown table: median, min and max wall time over the repeats, and peak memory (max RSS).
# Not a test: the machine is shared and noisy; quote medians, and compare ratios within one run.
set -euo pipefail
bin=${1:-build/tools}
repeats=${REPEATS:-5}
out=bench/out
mkdir -p "$out"
command -v /usr/bin/time >/dev/null || { echo "bench: needs GNU time: apt-get install -y time" >&2; exit 1; }

# run NAME COMMAND...: times COMMAND `repeats` times and prints one table row.
run() {
  local name=$1; shift
  local times=() mems=()
  for ((r = 0; r < repeats; r++)); do
    /usr/bin/time -f "%e %M" -o "$out/time.txt" "$@" >/dev/null
    read -r t m <"$out/time.txt"
    times+=("$t"); mems+=("$m")
  done
  local sorted=($(printf '%s\n' "${times[@]}" | sort -g))
  local median=${sorted[$((repeats / 2))]}
  local peak=$(printf '%s\n' "${mems[@]}" | sort -g | tail -1)
  local size=$(stat -c %s "$out/mesh.h5")
  awk -v n="$name" -v med="$median" -v lo="${sorted[0]}" -v hi="${sorted[$((repeats - 1))]}" -v p="$peak" -v s="$size" \
    'BEGIN { printf "| %s | %s | %s | %s | %.0f | %.1f |\n", n, med, lo, hi, p / 1024, s / 1048576 }'
}

echo "mesh-gen, $repeats repeats each, $(nproc) cores, $(date -u +%Y-%m-%d)"
echo
echo "| workload | median s | min s | max s | peak MB | file MB |"
echo "|---|---|---|---|---|---|"
for n in 100 316 1000; do
  size=$(awk -v n="$n" 'BEGIN { print n * 0.01 }')
  run "voronoi rect ${n}x${n} ($((n * n)) cells)" \
    "$bin/mesh-gen" voronoi --shape rect --size "${size}x${size}" --cells "${n}x${n}" --seed 1 -q -o "$out/mesh.h5"
done
run "voronoi disc 10^5 cells" "$bin/mesh-gen" voronoi --shape disc --diameter 4 --cells 100000 --seed 1 -q -o "$out/mesh.h5"
run "triangular 1000x1000 nodes" "$bin/mesh-gen" triangular --nodes 1000x1000 --spacing 1e-3 --notch 0.2 -q -o "$out/mesh.h5"
