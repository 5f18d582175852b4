#!/usr/bin/env bash
# What each physics term of dem-run costs. Usage: bench/dem_terms.sh [BIN_DIR]
# (REPEATS=3, CELLS_SIDE=100, STEPS=200)
# The same scene, the explosion (data/scenes/explosion.ini: the paper's kick of 500 J, dt = 1e-6 s) on a
# CELLS_SIDE² Voronoi rectangle (10^4 cells of the paper's size), with each term on and off: contacts
# (overlap repulsion and the contact search), beams, breaking (the pass after every step), friction and
# damping (γ_N = γ_T = 1000 s^-1, μ = 0.3 when on), and the two "on with a zero coefficient" cases.
# One thread (OMP_NUM_THREADS=1). Nanoseconds per cell-step from the CPU time (user + system) of STEPS
# and 2×STEPS steps run back to back, differenced so that set-up and output do not count; the median
# over the repeats, the configurations interleaved in every repeat so that a change of load hits them
# all. Wall-clock figures beside them for reference (the machine is shared: they carry the load).
# A term's cost is the difference between two configurations that differ in that term alone (a term
# that needs another is measured with the other on: friction and damping act on contacts, breaking on
# beams). Prints Markdown tables.
set -euo pipefail
bin=${1:-build/tools}
repeats=${REPEATS:-3}
side=${CELLS_SIDE:-100}
steps=${STEPS:-200}
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # measure_configs, config_cells, cost_row
require_gnu_time

cells=$((side * side))
size=$(awk -v n="$side" 'BEGIN { print n * 0.01 }')
mesh="$out/terms-mesh.h5"
"$bin/mesh-gen" voronoi --shape rect --size "${size}x${size}" --cells "${side}x${side}" --seed 1 -q -o "$mesh"

# Configurations: name, then the switches (contacts beams breaking friction damping) and extra keys.
names=(all-on friction-off damping-off friction-damping-off breaking-off contacts-off beams-off all-off
       friction-zero damping-zero)
declare -A switches=(
  [all-on]="on on on on on"
  [friction-off]="on on on off on"
  [damping-off]="on on on on off"
  [friction-damping-off]="on on on off off"
  [breaking-off]="on on off on on"
  [contacts-off]="off on on off off"
  [beams-off]="on off off on on"
  [all-off]="off off off off off"
  [friction-zero]="on on on on on"
  [damping-zero]="on on on on on"
)
declare -A extra=(
  [friction-zero]="--material.friction 0 --material.gamma_t 0"
  [damping-zero]="--material.gamma_n 0"
)
command_for() {  # the dem-run command line of configuration $1
  local c b k f d
  read -r c b k f d <<<"${switches[$1]}"
  echo "env OMP_NUM_THREADS=1 $bin/dem-run --scene data/scenes/explosion.ini $mesh -q -o $out/terms-run.h5" \
    "--output.frame_interval 1 --output.observe_every 1000000 --stop.t_max 1 --stop.steps_without_breaking 0" \
    "--physics.contacts $c --physics.beams $b --physics.breaking $k --physics.friction $f --physics.damping $d" \
    "--material.friction 0.3 --material.gamma_n 1000 --material.gamma_t 1000 ${extra[$1]:-}"
}

measure_configs "$cells" "$steps" "${names[@]}"

echo "dem-run, cost of each physics term: explosion scene, $cells cells, steps $steps..$((2 * steps)), 1 thread,"
echo "median of $repeats (configurations interleaved), $(nproc) cores shared with other jobs (load $(cut -d' ' -f1-3 /proc/loadavg)), $(date -u +%Y-%m-%d)"
echo
echo "| configuration | contacts | beams | breaking | friction | damping | ns per cell-step (CPU) | min | max | wall ns (median) |"
echo "|---|---|---|---|---|---|---|---|---|---|"
for name in "${names[@]}"; do
  read -r c b k f d <<<"${switches[$name]}"
  label=$name
  [[ -n ${extra[$name]:-} ]] && label="$name (${extra[$name]//--material./})"
  echo "| $label | $c | $b | $k | $f | $d | $(config_cells "$name") |"
done

echo
echo "| term | cost, ns per cell-step (CPU) | % of all-on | measured as |"
echo "|---|---|---|---|"
cost_row friction all-on friction-off all-on
cost_row damping all-on damping-off all-on
cost_row breaking all-on breaking-off all-on
cost_row "contacts (search + repulsion)" friction-damping-off contacts-off all-on
cost_row "beams (forces)" breaking-off beams-off all-on
cost_row "friction on, μ = γ_T = 0" friction-zero friction-off all-on
cost_row "damping on, γ_N = 0" damping-zero damping-off all-on
# Additivity: the floor (every term off: the integrator alone) plus the five costs against all-on.
if [[ -z ${failed[all-off]:-} && -z ${failed[beams-off]:-} ]]; then
  # shellcheck disable=SC2086
  awk -v on="$(median_of ${cpu[all-on]})" -v off="$(median_of ${cpu[all-off]})" -v f="$(median_of ${cpu[friction-off]})" \
    -v d="$(median_of ${cpu[damping-off]})" -v k="$(median_of ${cpu[breaking-off]})" \
    -v fd="$(median_of ${cpu[friction-damping-off]})" -v c="$(median_of ${cpu[contacts-off]})" \
    -v bo="$(median_of ${cpu[beams-off]})" \
    'BEGIN { s = off + (on - f) + (on - d) + (on - k) + (fd - c) + (k - bo);
             printf "\nall-off (%.0f) + the five term costs = %.0f ns per cell-step, against all-on %.0f\n", off, s, on }'
fi
