#!/usr/bin/env bash
# The paper-scale explosion on two threads (goal: under 1 s) measured again and again over an hour: this VM's
# pace changes from one quarter hour to the next (the same build 0.70-1.13 s within an hour), so one median
# says little about how often the goal holds. Every EVERY seconds (default 240), REPEATS runs (default 5);
# prints the time of day and the median of each round, then how many rounds had a median under the goal.
# ONE_THREAD=N adds N runs on one thread to each round and their median: whether a slow round is the
# machine (both slower) or the threads. Not part of `make bench` (it takes an hour).
# Usage: bench/explosion-over-time.sh [BIN_DIR]   (ROUNDS=15, EVERY=240, REPEATS=5, THREADS=2, GOAL=1.0,
#        ONE_THREAD=0)
set -euo pipefail
bin=${1:-build/tools}
rounds=${ROUNDS:-15}
every=${EVERY:-240}
repeats=${REPEATS:-5}
threads=${THREADS:-2}
goal=${GOAL:-1.0}
one_thread=${ONE_THREAD:-0}
out=bench/out
mkdir -p "$out"
# shellcheck source=bench/lib.sh
source "$(dirname "$0")/lib.sh"  # median_wall
require_gnu_time
"$bin/mesh-gen" voronoi --shape disc --diameter 0.4 --cells 1100 --seed 7 -q -o "$out/over-time-disc.h5"

echo "explosion, $threads threads, $repeats runs every $every s, $(date -u +%Y-%m-%d)"
echo
if ((one_thread > 0)); then
  echo "| UTC | median wall s | one thread, median wall s |"
  echo "|---|---|---|"
else
  echo "| UTC | median wall s |"
  echo "|---|---|"
fi
under=0
for ((k = 0; k < rounds; k++)); do
  m=$(median_wall "$bin/dem-run" --threads "$threads" --scene data/scenes/explosion.ini "$out/over-time-disc.h5" -q \
    -o "$out/over-time-explosion.h5")
  if ((one_thread > 0)); then
    m1=$(repeats=$one_thread median_wall "$bin/dem-run" --threads 1 --scene data/scenes/explosion.ini \
      "$out/over-time-disc.h5" -q -o "$out/over-time-explosion.h5")
    echo "| $(date -u +%H:%M) | $m | $m1 |"
  else
    echo "| $(date -u +%H:%M) | $m |"
  fi
  if awk -v m="$m" -v g="$goal" 'BEGIN { exit !(m < g) }'; then under=$((under + 1)); fi
  if ((k + 1 < rounds)); then sleep "$every"; fi
done
echo
echo "rounds with a median under $goal s: $under of $rounds"
