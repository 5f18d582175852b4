#!/usr/bin/env bash
# Two builds of dem-run compared on the rows of bench/dem_run.sh: the full model (contacts, damping, friction,
# breaking) or the beams alone, at 10^4 or 10^5 cells, on one thread or more. Not part of `make bench`: it needs
# two binaries. Usage:
#   bench/compare-dem-model.sh OLD_DEM_RUN NEW_DEM_RUN   (MODEL=full|beams, SIDE=100|316 cells a side (1 cm
#                                                          each), STEPS=400, THREADS=1, REPEATS=9)
# The cost of a step is the time of 2·STEPS steps minus that of STEPS (set-up and output do not count), in ns
# per cell-step: CPU time on one thread, wall time on more. The machine is shared and its pace changes from minute to minute, so the two binaries run
# alternately, round by round (the order swapped every round); quote the median of the per-round ratios
# new/old. Also says whether the two runs' outputs after 2·STEPS steps are the same bit for bit (h5diff,
# provenance and version aside).
set -euo pipefail
old=${1:?usage: bench/compare-dem-model.sh OLD_DEM_RUN NEW_DEM_RUN}
new=${2:?usage: bench/compare-dem-model.sh OLD_DEM_RUN NEW_DEM_RUN}
repeats=${REPEATS:-9}
threads=${THREADS:-1}
model_name=${MODEL:-full}
side=${SIDE:-100}
steps=${STEPS:-400}
cells=$((side * side))
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # time_once, median_of, same_bits
require_gnu_time
mesh_gen=$(dirname "$new")/mesh-gen
[[ -x $mesh_gen ]] || mesh_gen=build/tools/mesh-gen
size=$(awk -v n="$side" 'BEGIN { print n * 0.01 }')
"$mesh_gen" voronoi --shape rect --size "${size}x${size}" --cells "${side}x${side}" --seed 1 -q -o "$out/fm-mesh.h5"
# The models of bench/dem_run.sh.
case $model_name in
  full) model=(--physics.contacts on --physics.breaking on --physics.friction on --physics.damping on
               --material.friction 0.3 --material.gamma_n 1000 --material.gamma_t 1000) ;;
  beams) model=(--physics.contacts off --physics.breaking off --physics.friction off --physics.damping off) ;;
  *) echo "MODEL: full or beams, got '$model_name'" >&2; exit 2 ;;
esac
model+=(--output.frame_interval 1 --output.observe_every 1000000 --stop.t_max 1 --stop.steps_without_breaking 0
        --loading.energy 1)
# The time a run measures: CPU on one thread, wall on more.
field=2
((threads > 1)) && field=1
# cpu_of BIN NAME: "T1 T2", the seconds (CPU or wall) of STEPS and of 2·STEPS steps; the longer run's output goes
# to $out/fm-NAME.h5.
cpu_of() {
  local t400 t800
  t400=$(time_once "$1" --threads "$threads" --scene data/scenes/pulse.ini "$out/fm-mesh.h5" -q \
    -o "$out/fm-$2-short.h5" "${model[@]}" --stop.max_steps "$steps" | cut -d' ' -f"$field")
  t800=$(time_once "$1" --threads "$threads" --scene data/scenes/pulse.ini "$out/fm-mesh.h5" -q \
    -o "$out/fm-$2.h5" "${model[@]}" --stop.max_steps $((2 * steps)) | cut -d' ' -f"$field")
  echo "$t400 $t800"
}
# ns_between T1 T2: ns per cell-step of steps STEPS to 2·STEPS.
ns_between() { awk -v a="$1" -v b="$2" -v n="$cells" -v s="$steps" 'BEGIN { printf "%.1f", (b - a) / (n * s) * 1e9 }'; }
ns_old=() ns_new=() ratios=() short_old=() long_old=() short_new=() long_new=()
for ((r = 0; r < repeats; r++)); do
  if ((r % 2)); then
    read -r nb4 nb8 <<<"$(cpu_of "$new" new)"
    read -r na4 na8 <<<"$(cpu_of "$old" old)"
  else
    read -r na4 na8 <<<"$(cpu_of "$old" old)"
    read -r nb4 nb8 <<<"$(cpu_of "$new" new)"
  fi
  a=$(ns_between "$na4" "$na8")
  b=$(ns_between "$nb4" "$nb8")
  ns_old+=("$a")
  ns_new+=("$b")
  short_old+=("$na4") long_old+=("$na8") short_new+=("$nb4") long_new+=("$nb8")
  ratios+=("$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')")
done
same=$(same_bits "$out/fm-old.h5" "$out/fm-new.h5")
# The least disturbed runs: the fastest 800-step run minus the fastest 400-step run (the smallest of the rounds'
# differences would not do: a round whose short run was slowed gives a difference near zero).
least() { printf '%s\n' "$@" | sort -g | head -1; }
fastest_old=$(ns_between "$(least "${short_old[@]}")" "$(least "${long_old[@]}")")
fastest_new=$(ns_between "$(least "${short_new[@]}")" "$(least "${long_new[@]}")")
echo "dem-run $model_name model, $cells cells, $threads thread(s), steps $steps-$((2 * steps)), ns per cell-step," \
  "$repeats rounds, $(date -u +%Y-%m-%d)"
echo
echo "| old: median, fastest | new: median, fastest | new/old, median of rounds | same bits |"
echo "|---|---|---|---|"
echo "| $(median_of "${ns_old[@]}"), $fastest_old | $(median_of "${ns_new[@]}"), $fastest_new |" \
  "$(median_of "${ratios[@]}") | $same |"
echo
echo "(rounds: old ${ns_old[*]}; new ${ns_new[*]})"
