#!/usr/bin/env bash
# Two builds of dem-run compared on the full model at 10^4 cells (the contact-bound row of bench/dem_run.sh),
# not part of `make bench`: it needs two binaries. Usage:
#   bench/compare-full-model.sh OLD_DEM_RUN NEW_DEM_RUN   (REPEATS=9, THREADS=1)
# The cost of a step is the CPU time of 800 steps minus that of 400 (set-up and output do not count), in ns
# per cell-step. The machine is shared and its pace changes from minute to minute, so the two binaries run
# alternately, round by round (the order swapped every round); quote the median of the per-round ratios
# new/old. Also says whether the two runs' outputs after 800 steps are the same bit for bit (h5diff,
# provenance and version aside).
set -euo pipefail
old=${1:?usage: bench/compare-full-model.sh OLD_DEM_RUN NEW_DEM_RUN}
new=${2:?usage: bench/compare-full-model.sh OLD_DEM_RUN NEW_DEM_RUN}
repeats=${REPEATS:-9}
threads=${THREADS:-1}
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # time_once, median_of, same_bits
require_gnu_time
mesh_gen=$(dirname "$new")/mesh-gen
[[ -x $mesh_gen ]] || mesh_gen=build/tools/mesh-gen
"$mesh_gen" voronoi --shape rect --size 1x1 --cells 100x100 --seed 1 -q -o "$out/fm-mesh.h5"
# The full model of bench/dem_run.sh.
model=(--physics.contacts on --physics.breaking on --physics.friction on --physics.damping on
       --material.friction 0.3 --material.gamma_n 1000 --material.gamma_t 1000
       --output.frame_interval 1 --output.observe_every 1000000 --stop.t_max 1 --stop.steps_without_breaking 0
       --loading.energy 1)
# cpu_of BIN NAME: "CPU400 CPU800", the CPU seconds of 400 and of 800 steps; the 800-step output goes to
# $out/fm-NAME.h5.
cpu_of() {
  local cpu400 cpu800
  read -r _ cpu400 <<<"$(time_once "$1" --threads "$threads" --scene data/scenes/pulse.ini "$out/fm-mesh.h5" -q \
    -o "$out/fm-$2-400.h5" "${model[@]}" --stop.max_steps 400)"
  read -r _ cpu800 <<<"$(time_once "$1" --threads "$threads" --scene data/scenes/pulse.ini "$out/fm-mesh.h5" -q \
    -o "$out/fm-$2.h5" "${model[@]}" --stop.max_steps 800)"
  echo "$cpu400 $cpu800"
}
# ns_between CPU400 CPU800: ns per cell-step of steps 400-800.
ns_between() { awk -v a="$1" -v b="$2" 'BEGIN { printf "%.0f", (b - a) / (1e4 * 400) * 1e9 }'; }
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
echo "dem-run full model, 10^4 cells, $threads thread(s), steps 400-800, CPU ns per cell-step, $repeats rounds, $(date -u +%Y-%m-%d)"
echo
echo "| old: median, fastest | new: median, fastest | new/old, median of rounds | same bits |"
echo "|---|---|---|---|"
echo "| $(median_of "${ns_old[@]}"), $fastest_old | $(median_of "${ns_new[@]}"), $fastest_new |" \
  "$(median_of "${ratios[@]}") | $same |"
echo
echo "(rounds: old ${ns_old[*]}; new ${ns_new[*]})"
