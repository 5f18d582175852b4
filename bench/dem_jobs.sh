#!/usr/bin/env bash
# The users' DEM jobs at scale, measured as they run: the explosion of a disc and the impact on a block with the
# paper's cell size (Kun et al. 1999) at 10^4, 10^5 and 10^6 cells, dt = 1e-7 s, run to T_MAX (the paper's
# stop rule, 300 steps without a break, off: at 10^5 cells it ends the explosion near 1.1 ms), the scene's output.
# Usage: bench/dem_jobs.sh [BIN_DIR]
#   SIZES="10000 100000"  SCENES="explosion impact"  THREADS="1 2"  REPEATS=1 (more: a table of the medians too)
#   T_MAX=5e-3 (s; the 10^6-cell runs: T_MAX_LARGE=5e-4, through the break-up around the charge or projectile)
#   REPORT_ONLY=1: the tables again from the runs kept in bench/out/jobs (no run)
# The disc's diameter and the block's sides grow with the square root of the cells (1100 cells in 0.40 m, 800 in
# 0.40 × 0.20 m); the charge (500 J into the central cell's neighbours) and the projectile (457 J in one cell)
# are the paper's. Per run: wall and CPU ns per cell-step over the whole run, and per phase (before break-up:
# until 10 % of the beams that break have broken; during: to 90 %; after), from dem-run's progress lines
# (step and steps per second every 5 s); peak memory (max RSS; MB = 10^6 bytes) and per cell; then contacts and
# broken beams per cell over time, from the run's observables; the share of the step's time of each phase of the
# step (dem-run --profile). Configurations run interleaved, repeat by repeat.
set -euo pipefail
bin=${1:-build/tools}
sizes=${SIZES:-"10000 100000"}
scenes=${SCENES:-"explosion impact"}
threads=${THREADS:-"1 2"}
repeats=${REPEATS:-1}
dt=1e-7
out=bench/out/jobs
mkdir -p "$out"
command -v /usr/bin/time >/dev/null || { echo "bench: needs GNU time: apt-get install -y time" >&2; exit 1; }

# mesh SCENE CELLS: the mesh file of a job (made once).
mesh() {
  local f="$out/$1-$2.h5"
  if [[ ! -f $f ]]; then
    if [[ $1 == explosion ]]; then
      "$bin/mesh-gen" voronoi --shape disc --diameter "$(awk -v c="$2" 'BEGIN { printf "%.4f", 0.4 * sqrt(c / 1100) }')" \
        --cells "$2" --seed 1 -q -o "$f"
    else
      local nx ny
      read -r nx ny <<<"$(awk -v c="$2" 'BEGIN { y = int(sqrt(c / 2) + 0.5); printf "%d %d", 2 * y, y }')"
      "$bin/mesh-gen" voronoi --shape rect --size "$(awk -v x="$nx" -v y="$ny" 'BEGIN { printf "%.2fx%.2f", x / 100, y / 100 }')" \
        --cells "${nx}x${ny}" --seed 1 -q -o "$f"
    fi
  fi
  echo "$f"
}

# run_job SCENE CELLS THREADS: runs the job once (its run file, progress log and times kept), then report_job.
run_job() {
  local scene=$1 cells=$2 t=$3 m t_max
  m=$(mesh "$scene" "$cells")
  t_max=${T_MAX:-5e-3}
  ((cells >= 1000000)) && t_max=${T_MAX_LARGE:-5e-4}
  /usr/bin/time -f "%e %U %S %M" -o "$out/$scene-$cells-t$t.time" "$bin/dem-run" --threads "$t" \
    --scene "data/scenes/$scene.ini" "$m" --integrator.dt "$dt" --stop.t_max "$t_max" \
    --stop.steps_without_breaking 0 --checkpoint-every 0 --profile -o "$out/$scene-$cells-t$t.h5" 2>"$out/$scene-$cells-t$t.log"
  report_job "$scene" "$cells" "$t"
}

# report_job SCENE CELLS THREADS: the Markdown row of a job's last run (REPORT_ONLY=1: rows of the runs kept).
report_job() {
  local scene=$1 cells=$2 t=$3 base wall user sys rss steps phases
  base="$out/$scene-$cells-t$t"
  read -r wall user sys rss <"$base.time"
  steps=$(h5dump -a /steps "$base.h5" | awk '/\(0\)/ { print $2 }')
  # Broken beams over time (the observables), and the steps at which 10 % and 90 % of the final count broke.
  "$bin/observables" "$base.h5" --columns intact_beams,contacts -q | grep -v '^#' | tail -n +2 >"$out/obs.csv"
  phases=$(awk -F, -v dt="$dt" '
    NR == 1 { first = $2 } { s[NR] = $1 / dt; b[NR] = first - $2; n = NR }
    END { total = b[n]; a = 0; c = 0
          for (k = 1; k <= n; ++k) { if (!a && b[k] >= 0.1 * total) a = s[k]; if (!c && b[k] >= 0.9 * total) c = s[k] }
          printf "%.0f %.0f", a, c }' "$out/obs.csv")
  # Elapsed time at each progress line (steps / rate), then the time at the phase boundaries by interpolation.
  grep -o 'step [0-9]*, [0-9.e+]* steps/s' "$base.log" | awk '{ printf "%d %.6f\n", $2, $2 / $3 }' >"$out/elapsed.txt" || true
  awk -v cells="$cells" -v steps="$steps" -v wall="$wall" -v cpu="$(awk -v u="$user" -v s="$sys" 'BEGIN { print u + s }')" \
    -v rss="$rss" -v ph="$phases" -v name="$scene" -v t="$t" '
    BEGIN { split(ph, p, " "); n = 1; st[1] = 0; el[1] = 0 }
    { ++n; st[n] = $1; el[n] = $2 }
    function at(x,   k) {  # elapsed s at step x (linear between progress lines; the rate of the last one past them)
      for (k = 2; k <= n; ++k) if (st[k] >= x) return el[k - 1] + (x - st[k - 1]) * (el[k] - el[k - 1]) / (st[k] - st[k - 1])
      return n > 2 ? el[n] + (x - st[n]) * (el[n] - el[n - 1]) / (st[n] - st[n - 1]) : x * wall / steps }
    function ns(a, b) { return b > a ? (at(b) - at(a)) * 1e9 / (cells * (b - a)) : 0 }
    END {
      loop = n > 1 ? at(steps) : wall
      printf "| %s | %d | %s | %d | %.0f | %.0f | %.0f | %.0f | %.0f | %.1f | %.0f | %.2f |\n", name, cells, t, steps,
        loop * 1e9 / (cells * steps), cpu * 1e9 / (cells * steps), ns(0, p[1]), ns(p[1], p[2]), ns(p[2], steps),
        wall, rss * 1024 / 1e6, rss * 1024 / cells / 1000 }' "$out/elapsed.txt"
}

echo "dem-run jobs, dt $dt s, $(nproc) cores, $(date -u +%Y-%m-%d)"
echo
echo "| job | cells | threads | steps | ns per cell-step, whole run | CPU | before break-up | during | after | wall s | peak MB | KB per cell |"
echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
rows=$(mktemp)
trap 'rm -f "$rows"' EXIT
for ((r = 0; r < repeats; r++)); do
  for cells in $sizes; do
    for scene in $scenes; do
      for t in $threads; do
        if [[ ${REPORT_ONLY:-0} == 1 ]]; then report_job "$scene" "$cells" "$t"; else run_job "$scene" "$cells" "$t"; fi
      done
    done
  done | tee -a "$rows"
  [[ ${REPORT_ONLY:-0} == 1 ]] && break
done

# The median of each column over the repeats of a job (the middle run; the mean of the middle two for an even count).
if ((repeats > 1)) && [[ ${REPORT_ONLY:-0} != 1 ]]; then
  echo
  echo "Medians over $repeats interleaved repeats:"
  echo
  echo "| job | cells | threads | steps | ns per cell-step, whole run | CPU | before break-up | during | after | wall s | peak MB | KB per cell |"
  echo "|---|---|---|---|---|---|---|---|---|---|---|---|"
  awk -F'|' '
    { key = $2 "|" $3 "|" $4; if (!(key in seen)) { seen[key] = 1; order[++jobs] = key }
      runs[key]++; for (c = 5; c <= 13; ++c) v[key, c, runs[key]] = $c }
    function median(key, c,   n, i, j, t, a) {
      n = runs[key]; for (i = 1; i <= n; ++i) a[i] = v[key, c, i] + 0
      for (i = 2; i <= n; ++i) for (j = i; j > 1 && a[j - 1] > a[j]; --j) { t = a[j]; a[j] = a[j - 1]; a[j - 1] = t }
      return n % 2 ? a[(n + 1) / 2] : 0.5 * (a[n / 2] + a[n / 2 + 1]) }
    END { for (k = 1; k <= jobs; ++k) { key = order[k]; printf "|%s|", key
            for (c = 5; c <= 13; ++c) printf " %s |", c == 12 ? sprintf("%.0f", median(key, c)) : c == 13 ? sprintf("%.2f", median(key, c)) : c == 11 ? sprintf("%.1f", median(key, c)) : sprintf("%.0f", median(key, c))
            printf "\n" } }' "$rows"
fi

echo
echo "Contacts and broken beams per cell over time (the last run of each job):"
echo
echo "| job | cells | t = 10 % of the run | 20 % | 40 % | 60 % | 80 % | 100 % |"
echo "|---|---|---|---|---|---|---|---|"
for cells in $sizes; do
  for scene in $scenes; do
    run=$(ls -t "$out/$scene-$cells"-t*.h5 2>/dev/null | head -1)
    [[ -n $run ]] || continue
    "$bin/observables" "$run" --columns intact_beams,contacts -q | grep -v '^#' | tail -n +2 |
      awk -F, -v name="$scene" -v cells="$cells" '
        NR == 1 { first = $2 } { tm[NR] = $1; b[NR] = first - $2; c[NR] = $3; n = NR }
        END { printf "| %s | %d |", name, cells
              split("0.1 0.2 0.4 0.6 0.8 1", f, " ")
              for (k = 1; k <= 6; ++k) { i = int(f[k] * (n - 1)) + 1
                printf " %.2g ms: %.3f contacts, %.4f broken |", tm[i] * 1e3, c[i] / cells, b[i] / cells }
              printf "\n" }'
  done
done

echo
echo "Share of the step's time by phase (dem-run --profile, the last run of each job; serial: one thread):"
echo
logs=()
for cells in $sizes; do for scene in $scenes; do for t in $threads; do
  [[ -f "$out/$scene-$cells-t$t.log" ]] && logs+=("$out/$scene-$cells-t$t.log")
done; done; done
((${#logs[@]} > 0)) && awk '
  FNR == 1 { job = FILENAME; sub(/.*\//, "", job); sub(/\.log$/, "", job); jobs[++nj] = job; on = 0 }
  /phases of [0-9]+ steps/ { on = 1; next }
  on && /^  total / { serial[job] = $NF; on = 0; next }
  on && / (parallel|serial) / { name = $0; sub(/^  /, "", name); sub(/ +(parallel|serial) .*/, "", name)
    kind = $0; sub(/.* (parallel|serial) .*/, "", kind); k = ($0 ~ / serial /) ? " (serial)" : ""
    if (!((name k) in seen)) { seen[name k] = 1; order[++np] = name k }
    share[job, name k] = $(NF - 1) }
  END { printf "| phase |"; for (j = 1; j <= nj; ++j) printf " %s |", jobs[j]; printf "\n|---|"
        for (j = 1; j <= nj; ++j) printf "---|"; printf "\n"
        for (p = 1; p <= np; ++p) { printf "| %s |", order[p]
          for (j = 1; j <= nj; ++j) printf " %s |", ((jobs[j], order[p]) in share) ? share[jobs[j], order[p]] : "-"
          printf "\n" }
        printf "| outside parallel loops |"; for (j = 1; j <= nj; ++j) printf " %s |", serial[jobs[j]]; printf "\n" }' "${logs[@]}"
