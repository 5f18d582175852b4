#!/usr/bin/env bash
# dem-run benchmarks. Usage: bench/dem_run.sh [BIN_DIR]   (REPEATS=5, THREADS="1 2")
# 1. Nanoseconds per cell-step at 10^4 and 10^5 cells, on 1 and 2 threads, for beams only and for the
#    full model (beams, contacts, damping, friction, breaking): the wall (and CPU) time of S and 2S steps,
#    differenced, so set-up (reading, the stability bound) does not count; the configurations run
#    interleaved, repeat by repeat; the median of the repeats, and the fastest (the fastest 2S-step run
#    minus the fastest S-step run). The 10^5-cell runs measure steps
#    40-80 (the 10^4-cell ones 400-800): the pulse has disturbed fewer pairs by then, so fewer overlap.
#    (A 10^4-cell row at steps 40-80 differences runs ~0.1 s apart: start-up jitter swamps it.)
# 2. Wall time and steps of the paper-scale explosion (1100 cells) and impact (800 cells).
set -euo pipefail
bin=${1:-build/tools}
repeats=${REPEATS:-5}
threads=${THREADS:-"1 2"}
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # measure_configs, time_once, median_of
require_gnu_time
scenes=data/scenes

beams_only=(--physics.contacts off --physics.breaking off --physics.friction off --physics.damping off)
full_model=(--physics.contacts on --physics.breaking on --physics.friction on --physics.damping on
            --material.friction 0.3 --material.gamma_n 1000 --material.gamma_t 1000)
quiet_output=(--output.frame_interval 1 --output.observe_every 1000000 --stop.t_max 1 --stop.steps_without_breaking 0)

echo "dem-run, median of $repeats, $(nproc) cores, $(date -u +%Y-%m-%d)"
echo
echo "| cells | model | threads | steps | ns per cell-step, wall: median | fastest | CPU median |"
echo "|---|---|---|---|---|---|---|"
# command_for MODEL:THREADS: the dem-run command of one configuration (measure_configs runs them interleaved,
# repeat by repeat, so that a change of load hits every configuration alike).
command_for() {
  local model=${1%%:*} t=${1##*:} extra
  if [[ $model == beams ]]; then extra="${beams_only[*]}"; else extra="${full_model[*]}"; fi
  echo "$bin/dem-run --threads $t --scene $scenes/pulse.ini $out/dem-mesh.h5 -q -o $out/dem-run.h5 ${quiet_output[*]} $extra --loading.energy 1"
}
for run in "100 400" "316 40"; do
  read -r side steps <<<"$run"
  cells=$((side * side))
  size=$(awk -v n="$side" 'BEGIN { print n * 0.01 }')
  "$bin/mesh-gen" voronoi --shape rect --size "${size}x${size}" --cells "${side}x${side}" --seed 1 -q -o "$out/dem-mesh.h5"
  configs=()
  for model in beams full; do
    for t in $threads; do configs+=("$model:$t"); done
  done
  measure_configs "$cells" "$steps" "${configs[@]}"
  for c in "${configs[@]}"; do
    # shellcheck disable=SC2086
    printf '| %d | %s | %s | %d | %s | %s | %s |\n' "$cells" "${c%%:*}" "${c##*:}" "$steps" \
      "$(median_of ${wall[$c]})" "$(fastest_ns "$cells" "$steps" "$c")" "$(median_of ${cpu[$c]})"
  done
done

echo
echo "| paper-scale run | threads | steps | median wall s | 1-thread time over this |"
echo "|---|---|---|---|---|"
"$bin/mesh-gen" voronoi --shape disc --diameter 0.4 --cells 1100 --seed 7 -q -o "$out/disc.h5"
"$bin/mesh-gen" voronoi --shape rect --size 0.40x0.20 --cells 40x20 --seed 7 -q -o "$out/block.h5"
# The thread counts interleaved, repeat by repeat, so that a change of load hits them alike; the speed-up
# is the ratio of medians measured in this one run.
for run in "explosion disc" "impact block"; do
  # shellcheck disable=SC2086  # two words: the scene and its mesh
  set -- $run
  declare -A walls=()
  for ((r = 0; r < repeats; r++)); do
    for t in $threads; do
      read -r w _ <<<"$(time_once "$bin/dem-run" --threads "$t" --scene "$scenes/$1.ini" "$out/$2.h5" -q -o "$out/$1.h5")"
      walls[$t]+=" $w"
    done
  done
  steps=$(h5dump -a /steps "$out/$1.h5" | awk '/\(0\)/ { print $2 }')
  first=""
  for t in $threads; do
    # shellcheck disable=SC2086
    m=$(median_of ${walls[$t]})
    [[ -z $first ]] && first=$m
    awk -v n="$1" -v t="$t" -v s="$steps" -v m="$m" -v f="$first" \
      'BEGIN { printf "| %s | %s | %s | %s | %.2f |\n", n, t, s, m, f / m }'
  done
  unset walls
done
