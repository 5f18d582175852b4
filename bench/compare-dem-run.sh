#!/usr/bin/env bash
# Two builds of dem-run compared on the paper-scale explosion and impact (not part of `make bench`: it
# needs two binaries). Usage: bench/compare-dem-run.sh OLD_DEM_RUN NEW_DEM_RUN   (REPEATS=9, THREADS="1 2",
# SCENES=data/scenes; CELLS="10000 100000": the explosion of a disc of that many cells instead (the paper's cell
# size, dt = 1e-7 s, to T_MAX=5e-4 s), with contacts and with beams only (physics.contacts off))
# On a shared machine the load changes from minute to minute, so the two binaries run alternately, round
# by round (the order swapped every round), and the figure to quote is the median of the per-round
# ratios new/old, with the fastest run of each (the least disturbed). Also says whether the outputs are the
# same bit for bit (h5diff, provenance and version aside).
set -euo pipefail
old=${1:?usage: bench/compare-dem-run.sh OLD_DEM_RUN NEW_DEM_RUN}
new=${2:?usage: bench/compare-dem-run.sh OLD_DEM_RUN NEW_DEM_RUN}
repeats=${REPEATS:-9}
threads=${THREADS:-"1 2"}
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # time_once, median_of, same_bits
require_gnu_time
scenes=${SCENES:-data/scenes}  # (SCENES: another folder of scenes, e.g. one an older build knows)
mesh_gen=$(dirname "$new")/mesh-gen
[[ -x $mesh_gen ]] || mesh_gen=build/tools/mesh-gen
# The runs: "LABEL SCENE MESH [OPTIONS...]".
runs=()
if [[ -n ${CELLS:-} ]]; then
  for cells in $CELLS; do
    "$mesh_gen" voronoi --shape disc --diameter "$(awk -v c="$cells" 'BEGIN { printf "%.4f", 0.4 * sqrt(c / 1100) }')" \
      --cells "$cells" --seed 1 -q -o "$out/ab-disc-$cells.h5"
    common="--integrator.dt 1e-7 --stop.t_max ${T_MAX:-5e-4} --stop.steps_without_breaking 0"
    runs+=("explosion-$cells explosion ab-disc-$cells $common" "beams-only-$cells explosion ab-disc-$cells $common --physics.contacts off")
  done
else
  "$mesh_gen" voronoi --shape disc --diameter 0.4 --cells 1100 --seed 7 -q -o "$out/ab-disc.h5"
  "$mesh_gen" voronoi --shape rect --size 0.40x0.20 --cells 40x20 --seed 7 -q -o "$out/ab-block.h5"
  runs=("explosion explosion ab-disc" "impact impact ab-block")
fi

for run in "${runs[@]}"; do
  read -r label scene mesh options <<<"$run"
  for t in $threads; do
    walls_old=() walls_new=() ratios=()
    for ((r = 0; r < repeats; r++)); do
      order=(old new)
      ((r % 2)) && order=(new old)
      declare -A w=()
      for which in "${order[@]}"; do
        bin=$old
        [[ $which == new ]] && bin=$new
        # shellcheck disable=SC2086 # (the options split into words)
        read -r "w[$which]" _ <<<"$(time_once "$bin" --threads "$t" --scene "$scenes/$scene.ini" "$out/$mesh.h5" $options \
          -q -o "$out/ab-$which.h5")"
      done
      walls_old+=("${w[old]}")
      walls_new+=("${w[new]}")
      ratios+=("$(awk -v a="${w[new]}" -v b="${w[old]}" 'BEGIN { printf "%.3f", a / b }')")
      unset w
    done
    same=$(same_bits "$out/ab-old.h5" "$out/ab-new.h5")
    fastest_old=$(printf '%s\n' "${walls_old[@]}" | sort -g | head -1)
    fastest_new=$(printf '%s\n' "${walls_new[@]}" | sort -g | head -1)
    echo "| $label | $t | $(median_of "${walls_old[@]}"), $fastest_old | $(median_of "${walls_new[@]}"), $fastest_new |" \
      "$(median_of "${ratios[@]}") | $same |"
  done
done
