#!/usr/bin/env bash
# rubber-run on a 10^6-node lattice (1000 x 1000, the stretch scene): nanoseconds per node-step of the time
# loop on 1 and 2 threads. Usage: bench/rubber_run.sh [BIN_DIR]   (STEPS=200 and REPEATS=3 by default)
# The loop time is what rubber-run reports ("ns per node-step": wall time of the steps, observations off);
# setup and the two frames written are not in it. Prints a Markdown table: median, min and max over the
# repeats, and the CPU time of the whole process per node-step (setup included) for comparison.
# Not a test: the machine is shared and noisy; quote medians.
set -euo pipefail
bin=${1:-build/tools}
steps=${STEPS:-200}
repeats=${REPEATS:-3}
scene=${SCENE:-data/scenes/stretch.ini}
out=bench/out
mkdir -p "$out"
command -v /usr/bin/time >/dev/null || { echo "bench: needs GNU time: apt-get install -y time" >&2; exit 1; }

"$bin/mesh-gen" triangular --nodes 1000x1000 --spacing 1e-3 -q -o "$out/rubber-mesh.h5"
nodes=1000000

echo "rubber-run, 10^6 nodes, $steps steps, $repeats repeats, $(nproc) cores, $(date -u +%Y-%m-%d)"
echo
echo "| threads | median ns/node-step | min | max | CPU ns/node-step (whole process) |"
echo "|---|---|---|---|---|"
for threads in 1 2; do
  ns=() cpu=()
  for ((r = 0; r < repeats; r++)); do
    /usr/bin/time -f "%U %S" -o "$out/time.txt" \
      "$bin/rubber-run" --scene "$scene" "$out/rubber-mesh.h5" --stop.max_steps "$steps" \
        --output.frame_interval 0 --output.observe_every 100000000 --threads "$threads" \
        -o "$out/rubber-run.h5" 2>"$out/rubber-run.log"
    ns+=("$(sed -n 's/.*(\([0-9.e+-]*\) ns per node-step.*/\1/p' "$out/rubber-run.log" | tail -1)")
    read -r u s <"$out/time.txt"
    cpu+=("$(awk -v u="$u" -v s="$s" -v n="$nodes" -v k="$steps" 'BEGIN { printf "%.0f", (u + s) * 1e9 / (n * k) }')")
  done
  sorted=($(printf '%s\n' "${ns[@]}" | sort -g))
  csorted=($(printf '%s\n' "${cpu[@]}" | sort -g))
  printf "| %s | %.0f | %.0f | %.0f | %s |\n" "$threads" "${sorted[$((repeats / 2))]}" "${sorted[0]}" \
    "${sorted[$((repeats - 1))]}" "${csorted[$((repeats / 2))]}"
done
