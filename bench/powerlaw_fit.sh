#!/usr/bin/env bash
# powerlaw-fit benchmarks. Usage: bench/powerlaw_fit.sh [BIN_DIR]   (REPEATS=5)
# Goals (issue 4): the fit with the x_min scan of 10^5 values in under 1 s; 1000 bootstrap resamples of
# 10^4 values in under 10 s. Samples: Pareto, alpha = 2.5, x_min = 1, seeded (awk's srand).
set -euo pipefail
bin=${1:-build/tools}
repeats=${REPEATS:-5}
out=bench/out
mkdir -p "$out"
pareto() { awk -v n="$1" -v s="$2" 'BEGIN { srand(s); for (i = 0; i < n; i++) printf "%.17g\n", (1 - rand()) ^ (-1 / 1.5) }'; }
pareto 100000 1 > "$out/pl-1e5.txt"
pareto 10000 2 > "$out/pl-1e4.txt"
median() {
  local times=()
  for ((r = 0; r < repeats; r++)); do
    /usr/bin/time -f "%e %U" -o "$out/time.txt" "$@" >/dev/null 2>&1
    times+=("$(cat "$out/time.txt")")
  done
  printf '%s\n' "${times[@]}" | sort -g | sed -n "$((repeats / 2 + 1))p"
}
echo "powerlaw-fit, median of $repeats, $(nproc) cores, $(date -u +%Y-%m-%d)"
echo
echo "| workload | wall s | CPU s (user) |"
echo "|---|---|---|"
read -r w u <<< "$(median "$bin/powerlaw-fit" "$out/pl-1e5.txt" --format text --bootstrap 0 --gof-samples 0 --no-compare -q -o -)"
echo "| 10^5 values, x_min scan | $w | $u |"
read -r w u <<< "$(median "$bin/powerlaw-fit" "$out/pl-1e4.txt" --format text --bootstrap 1000 --gof-samples 0 --no-compare -q -o -)"
echo "| 10^4 values, 1000 bootstrap resamples | $w | $u |"
