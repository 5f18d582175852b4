#!/usr/bin/env bash
# Checkpoints of dem-run at 10^5 and 10^6 cells (the full model on a square of 1 cm cells, a frame every 10
# steps): the size of a checkpoint, the wall time of writing one (dem-run's summary line: checkpoints and the
# time they took), its share of the default interval (15 min), and the run's wall time with and without
# checkpoints every 20 steps (interleaved, median of REPEATS).
# Usage: bench/checkpoint.sh [BIN_DIR]   (REPEATS=3, SIDES="316 1000", STEPS=60)
set -euo pipefail
bin=${1:-build/tools}
repeats=${REPEATS:-3}
sides=${SIDES:-"316 1000"}
steps=${STEPS:-60}
out=bench/out
mkdir -p "$out"
scenes=data/scenes
full_model=(--physics.contacts on --physics.breaking on --physics.friction on --physics.damping on
            --material.friction 0.3 --material.gamma_n 1000 --material.gamma_t 1000 --integrator.dt auto)

median() { sort -g | awk '{ v[NR] = $1 } END { print (NR % 2) ? v[(NR + 1) / 2] : (v[NR / 2] + v[NR / 2 + 1]) / 2 }'; }

echo "dem-run checkpoints, median of $repeats, $(nproc) cores, $(date -u +%Y-%m-%d)"
echo
echo "| cells | frames in it | checkpoint size | write time | share of 15 min | run of $steps steps: none | every 20 steps |"
echo "|---|---|---|---|---|---|---|"
for side in $sides; do
  cells=$((side * side))
  size=$(awk -v n="$side" 'BEGIN { print n * 0.01 }')
  mesh=$out/checkpoint-mesh-$side.h5
  [[ -s $mesh ]] || "$bin/mesh-gen" voronoi --shape rect --size "${size}x${size}" --cells "${side}x${side}" --seed 1 -q -o "$mesh"
  dt=$("$bin/dem-run" --scene "$scenes/pulse.ini" "$mesh" "${full_model[@]}" --loading.energy 1 --stop.max_steps 1 \
         -o "$out/checkpoint-probe.h5" 2>&1 | awk '{ for (k = 1; k < NF; k++) if ($k == "of") { print $(k + 1); exit } }')
  run=("$bin/dem-run" --scene "$scenes/pulse.ini" "$mesh" "${full_model[@]}" --loading.energy 1
       --stop.max_steps "$steps" --stop.t_max 1 --stop.steps_without_breaking 0 --output.observe_every 10
       --output.frame_interval "$(awk -v dt="$dt" 'BEGIN { print 10 * dt }')" -o "$out/checkpoint-run.h5")
  plain=() with=() per=()
  for _ in $(seq "$repeats"); do
    t0=$(date +%s.%N)
    "${run[@]}" --checkpoint-every 0 -q
    t1=$(date +%s.%N)
    line=$("${run[@]}" --checkpoint-every 20 2>&1 | tail -1)
    t2=$(date +%s.%N)
    plain+=("$(awk -v a="$t0" -v b="$t1" 'BEGIN { print b - a }')")
    with+=("$(awk -v a="$t1" -v b="$t2" 'BEGIN { print b - a }')")
    # "(N checkpoints, T s)": the mean time of one
    per+=("$(sed -n 's/.*(\([0-9]*\) checkpoints, \([0-9.e+-]*\) s).*/\2 \1/p' <<<"$line" | awk '{ print $1 / $2 }')")
  done
  # A checkpoint kept: the run killed once its checkpoint half way exists.
  rm -f "$out/checkpoint-run.h5.ckpt"
  "${run[@]}" --checkpoint-every $((steps / 2)) -q &
  pid=$!
  for _ in $(seq 3000); do [[ -s $out/checkpoint-run.h5.ckpt ]] && break; sleep 0.1; done
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  bytes=$(stat -c %s "$out/checkpoint-run.h5.ckpt")
  frames=$(h5dump -H -d /run/particles/cells/position/step "$out/checkpoint-run.h5.ckpt" | awk -F'[(/]' '/DATASPACE/ { print $2 + 0; exit }')
  rm -f "$out/checkpoint-run.h5.ckpt" "$out"/.checkpoint-run.h5*.tmp-*
  write=$(printf '%s\n' "${per[@]}" | median)
  printf '| %d | %s | %.0f MB | %.2f s | %.3f %% | %.1f s | %.1f s |\n' "$cells" "$frames" "$(awk -v b="$bytes" 'BEGIN { print b / 1e6 }')" \
    "$write" "$(awk -v w="$write" 'BEGIN { print 100 * w / 900 }')" "$(printf '%s\n' "${plain[@]}" | median)" \
    "$(printf '%s\n' "${with[@]}" | median)"
done
