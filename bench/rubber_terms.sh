#!/usr/bin/env bash
# What each optional physics term of rubber-run costs. Usage: bench/rubber_terms.sh [BIN_DIR]
# (REPEATS=3, NODES=400x80, STEPS=400)
# The same scene, data/scenes/stretch.ini (λ = (1.2, 3), seed crack, clamps) on a NODES lattice, with each
# switch of its [physics] on and off: damping (Kelvin, uniform and near_failure at the scene's β),
# irreversible breaking, toughening (every 10 steps), all three at once, damping on with β = 0, energy-neutral
# failure (law.failure = freeze) and a crack path (crack.path_cutoff_ratio).
# One thread. Nanoseconds per node-step from the CPU time (user + system) of STEPS and 2×STEPS steps run
# back to back, differenced so that set-up and output do not count (observations off); the median over
# the repeats, the configurations interleaved in every repeat. Wall-clock figures beside them for
# reference (the machine is shared). A term's cost is its configuration minus all-off. Prints Markdown.
set -euo pipefail
bin=${1:-build/tools}
repeats=${REPEATS:-3}
nodes_xy=${NODES:-400x80}
steps=${STEPS:-400}
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # measure_configs, config_cells, cost_row
require_gnu_time

mesh="$out/terms-rubber-mesh.h5"
"$bin/mesh-gen" triangular --nodes "$nodes_xy" --spacing 1e-3 -q -o "$mesh"
nodes=$(awk -v s="$nodes_xy" 'BEGIN { split(s, a, "x"); print a[1] * a[2] }')

names=(all-off damping-uniform damping-near-failure damping-zero irreversible toughening all-on freeze crack-path)
declare -A keys=(
  [all-off]=""
  [damping-uniform]="--physics.damping on --damping.kind uniform"
  [damping-near-failure]="--physics.damping on --damping.kind near_failure"
  [damping-zero]="--physics.damping on --damping.kind uniform --damping.beta 0"
  [irreversible]="--physics.irreversible on"
  [toughening]="--physics.toughening on"
  [all-on]="--physics.damping on --physics.irreversible on --physics.toughening on"
  [freeze]="--law.failure freeze"
  [crack-path]="--crack.path_cutoff_ratio 1.2"
)
command_for() {  # the rubber-run command line of configuration $1
  echo "$bin/rubber-run --scene data/scenes/stretch.ini $mesh --threads 1 -q -o $out/terms-rubber-run.h5" \
    "--output.frame_interval 0 --output.observe_every 100000000 --stop.tip_margin 0 ${keys[$1]}"
}

measure_configs "$nodes" "$steps" "${names[@]}"

echo "rubber-run, cost of each optional term: stretch scene, $nodes nodes, steps $steps..$((2 * steps)), 1 thread,"
echo "median of $repeats (configurations interleaved), $(nproc) cores shared with other jobs (load $(cut -d' ' -f1-3 /proc/loadavg)), $(date -u +%Y-%m-%d)"
echo
echo "| configuration | scene keys | ns per node-step (CPU) | min | max | wall ns (median) |"
echo "|---|---|---|---|---|---|"
for name in "${names[@]}"; do
  echo "| $name | ${keys[$name]:-none (all off, as in the scene)} | $(config_cells "$name") |"
done
echo
echo "| term | cost, ns per node-step (CPU) | % of all-off | measured as |"
echo "|---|---|---|---|"
cost_row "damping (uniform)" damping-uniform all-off all-off
cost_row "damping (near_failure)" damping-near-failure all-off all-off
cost_row "damping on, β = 0" damping-zero all-off all-off
cost_row "irreversible breaking" irreversible all-off all-off
cost_row "toughening" toughening all-off all-off
cost_row "all three" all-on all-off all-off
cost_row "energy-neutral failure" freeze all-off all-off
cost_row "crack path" crack-path all-off all-off
