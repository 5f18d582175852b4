#!/usr/bin/env bash
# Two builds of rubber-run compared on the 10^6-node stretch scene of bench/rubber_run.sh (not part of `make bench`:
# it needs two binaries). Usage: bench/compare-rubber-run.sh OLD_RUBBER_RUN NEW_RUBBER_RUN
#   (THREADS="1 2", STEPS=100, REPEATS=9, SCENE=data/scenes/stretch.ini: one both builds know)
# The cost is what rubber-run reports, ns per node-step of its time loop (wall; set-up and output aside). The two
# binaries run alternately, round by round (the order swapped every round); quote the median of the per-round
# ratios new/old. Also says whether the outputs are the same bit for bit (h5diff, provenance and version aside).
set -euo pipefail
old=${1:?usage: bench/compare-rubber-run.sh OLD_RUBBER_RUN NEW_RUBBER_RUN}
new=${2:?usage: bench/compare-rubber-run.sh OLD_RUBBER_RUN NEW_RUBBER_RUN}
repeats=${REPEATS:-9}
threads=${THREADS:-"1 2"}
steps=${STEPS:-100}
scene=${SCENE:-data/scenes/stretch.ini}
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # median_of, same_bits
mesh_gen=$(dirname "$new")/mesh-gen
[[ -x $mesh_gen ]] || mesh_gen=build/tools/mesh-gen
"$mesh_gen" triangular --nodes 1000x1000 --spacing 1e-3 -q -o "$out/rr-mesh.h5"
# ns_of BIN NAME T: the loop's ns per node-step of one run on T threads; its output goes to $out/rr-NAME.h5.
ns_of() {
  "$1" --scene "$scene" "$out/rr-mesh.h5" --stop.max_steps "$steps" --output.frame_interval 0 \
    --output.observe_every 100000000 --threads "$3" -o "$out/rr-$2.h5" 2>"$out/rr-$2.log" ||
    { cat "$out/rr-$2.log" >&2; exit 1; }
  sed -n 's/.*(\([0-9.e+-]*\) ns per node-step.*/\1/p' "$out/rr-$2.log" | tail -1
}
echo "rubber-run, 10^6 nodes, $steps steps, $old against $new, $repeats rounds, $(date -u +%Y-%m-%d)"
echo
echo "| threads | old: median ns/node-step | new: median | new/old, median of rounds | same bits |"
echo "|---|---|---|---|---|"
for t in $threads; do
  a_all=() b_all=() ratios=()
  for ((r = 0; r < repeats; r++)); do
    if ((r % 2)); then
      b=$(ns_of "$new" new "$t")
      a=$(ns_of "$old" old "$t")
    else
      a=$(ns_of "$old" old "$t")
      b=$(ns_of "$new" new "$t")
    fi
    a_all+=("$a") b_all+=("$b")
    ratios+=("$(awk -v a="$a" -v b="$b" 'BEGIN { printf "%.3f", b / a }')")
  done
  echo "| $t | $(median_of "${a_all[@]}") | $(median_of "${b_all[@]}") | $(median_of "${ratios[@]}") |" \
    "$(same_bits "$out/rr-old.h5" "$out/rr-new.h5") |"
done
