#!/usr/bin/env bash
# The overlap of polygon pairs, the contact law's geometry, on its own: the neighbour pairs of the
# paper-scale explosion at 0.5, 1 and 4 ms, each overlap computed by clipping and from the lines the pair
# kept from the evaluation before (what dem-run does for most of them), ns per pair (median of 5 rounds).
# Usage: bench/overlap_pairs.sh [BIN_DIR]   (BIN_DIR: the tools, default build/tools; the benchmark
# program is built beside them, in ../bench)
set -euo pipefail
bin=${1:-build/tools}
out=bench/out
mkdir -p "$out"
prog=$bin/../bench/overlap-pairs
[[ -x $prog ]] || { echo "bench: no $prog (build the project first)" >&2; exit 1; }
"$bin/mesh-gen" voronoi --shape disc --diameter 0.4 --cells 1100 --seed 7 -q -o "$out/ov-disc.h5"
"$bin/dem-run" --scene data/scenes/explosion.ini "$out/ov-disc.h5" --stop.t_max 4e-3 --output.frame_interval 5e-4 \
  -q -o "$out/ov-run.h5"
echo "overlap of neighbour pairs, explosion frames, $(date -u +%Y-%m-%d)"
for frame in 1 2 8; do
  echo
  echo "t = $(awk -v f="$frame" 'BEGIN { print f * 0.5 }') ms:"
  "$prog" "$out/ov-run.h5" "$frame" "${PASSES:-1000}"
done
