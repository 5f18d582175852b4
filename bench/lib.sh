# shellcheck shell=bash disable=SC2154
# Helpers shared by the bench scripts: source it after setting `out` (a directory for scratch files)
# and `repeats` (SC2154: both are the caller's). Not a test: the machine is shared and noisy; quote medians, and compare ratios measured
# within one run of a script.

# Stops unless GNU time is installed (every helper reads its times from it).
require_gnu_time() {
  command -v /usr/bin/time >/dev/null || { echo "bench: needs GNU time: apt-get install -y time" >&2; exit 1; }
}

# time_once COMMAND...: runs COMMAND once (its output discarded) and prints "WALL CPU" in seconds, CPU =
# user + system (GNU time: 10 ms resolution), WALL from the shell's clock (microseconds: short runs are
# differenced). On failure prints the command's standard error and stops the script. Scratch files are
# per process, so two benchmarks may share $out.
time_once() {
  local tf="$out/time.$$.txt" ef="$out/stderr.$$.txt" t0 t1
  t0=$EPOCHREALTIME
  /usr/bin/time -f "%U %S" -o "$tf" "$@" >/dev/null 2>"$ef" ||
    { echo "bench: failed: $*" >&2; cat "$ef" >&2; rm -f "$tf" "$ef"; exit 1; }
  t1=$EPOCHREALTIME
  awk -v t0="$t0" -v t1="$t1" '{ printf "%.4f %.2f\n", t1 - t0, $1 + $2 }' "$tf"
  rm -f "$tf" "$ef"
}

# median_of VALUE...: the median (the middle value; the upper middle for an even count).
median_of() {
  printf '%s\n' "$@" | sort -g | sed -n "$(($# / 2 + 1))p"
}

# median_wall COMMAND...: median wall seconds of COMMAND over $repeats runs.
median_wall() {
  local times=() wall cpu r
  for ((r = 0; r < repeats; r++)); do
    read -r wall cpu <<<"$(time_once "$@")"
    times+=("$wall")
  done
  median_of "${times[@]}"
}

# step_ns UNITS STEPS COMMAND...: one measurement of the cost of a step, set-up and output excluded: runs
# COMMAND --stop.max_steps STEPS and then 2×STEPS, back to back, and prints "CPU WALL SHORT LONG": the
# differences of their CPU and wall times in nanoseconds per unit (cell, node) per step, and the two wall
# times in seconds.
step_ns() {
  local units=$1 steps=$2 w1 c1 w2 c2
  shift 2
  read -r w1 c1 <<<"$(time_once "$@" --stop.max_steps "$steps")"
  read -r w2 c2 <<<"$(time_once "$@" --stop.max_steps "$((2 * steps))")"
  awk -v u="$units" -v s="$steps" -v w1="$w1" -v c1="$c1" -v w2="$w2" -v c2="$c2" \
    'BEGIN { printf "%.0f %.0f %s %s\n", (c2 - c1) / (u * s) * 1e9, (w2 - w1) / (u * s) * 1e9, w1, w2 }'
}

# fastest_ns UNITS STEPS NAME: the wall ns per unit per step of the least disturbed runs of a configuration
# measured by measure_configs: its fastest 2×STEPS run minus its fastest STEPS run. (The smallest of the
# per-repeat differences would not do: a repeat whose short run was slowed gives a difference near zero.)
fastest_ns() {
  # shellcheck disable=SC2086
  awk -v u="$1" -v s="$2" -v a="$(printf '%s\n' ${short_wall[$3]} | sort -g | head -1)" \
    -v b="$(printf '%s\n' ${long_wall[$3]} | sort -g | head -1)" 'BEGIN { printf "%.0f", (b - a) / (u * s) * 1e9 }'
}

# measure_configs UNITS STEPS NAME...: the cost of a step of each configuration NAME, whose command line
# (without --stop.max_steps) the caller's function `command_for NAME` prints. A configuration that fails
# on a 1-step probe is not measured: its first error line goes to failed[NAME]. The others are measured
# by step_ns, $repeats times, all configurations once per repeat (interleaved, so that a change of load
# hits them all alike); cpu[NAME] and wall[NAME] get the per-repeat values, space-separated, and
# short_wall[NAME] and long_wall[NAME] the wall times of the runs (for fastest_ns).
declare -gA failed=() cpu=() wall=() short_wall=() long_wall=()
measure_configs() {
  local units=$1 steps=$2 name m c w w1 w2 r
  shift 2
  for name in "$@"; do
    cpu[$name]="" wall[$name]="" short_wall[$name]="" long_wall[$name]=""
    # shellcheck disable=SC2046
    if ! $(command_for "$name") --stop.max_steps 1 >/dev/null 2>"$out/probe.$$.txt"; then
      failed[$name]=$(grep -m1 . "$out/probe.$$.txt" | sed 's/|/\\|/g')
    fi
  done
  rm -f "$out/probe.$$.txt"
  for ((r = 0; r < repeats; r++)); do
    for name in "$@"; do
      [[ -n ${failed[$name]:-} ]] && continue
      # shellcheck disable=SC2046
      m=$(step_ns "$units" "$steps" $(command_for "$name"))
      read -r c w w1 w2 <<<"$m"
      cpu[$name]+=" $c" wall[$name]+=" $w" short_wall[$name]+=" $w1" long_wall[$name]+=" $w2"
    done
  done
}

# cost_row TERM WITH WITHOUT [REFERENCE]: a Markdown row: the median CPU ns of configuration WITH minus
# that of WITHOUT, and its share of REFERENCE's (default WITH).
cost_row() {
  local ref=${4:-$2}
  if [[ -n ${failed[$2]:-} || -n ${failed[$3]:-} ]]; then
    echo "| $1 | n/a | | $2 − $3 (a configuration failed) |"
    return
  fi
  # shellcheck disable=SC2086
  awk -v t="$1" -v a="$(median_of ${cpu[$2]})" -v b="$(median_of ${cpu[$3]})" -v all="$(median_of ${cpu[$ref]})" \
    -v w="$2" -v wo="$3" 'BEGIN { printf "| %s | %.0f | %.0f | %s − %s |\n", t, a - b, 100 * (a - b) / all, w, wo }'
}

# config_cells NAME: "median | min | max | wall median" of a measured configuration, or "fails: ... | | |".
config_cells() {
  if [[ -n ${failed[$1]:-} ]]; then
    echo "fails: ${failed[$1]} | | |"
    return
  fi
  local sorted
  # shellcheck disable=SC2086
  read -ra sorted <<<"$(printf '%s\n' ${cpu[$1]} | sort -g | tr '\n' ' ')"
  # shellcheck disable=SC2086
  echo "$(median_of ${cpu[$1]}) | ${sorted[0]} | ${sorted[-1]} | $(median_of ${wall[$1]})"
}

# same_bits A.h5 B.h5: "yes" when the two files hold the same data bit for bit, provenance and the creator's
# name and version aside, else "no" (a dataset or attribute that differs shows as "N differences found";
# empty datasets, which h5diff cannot compare, count as the same). The output is captured before it is
# searched, with `|| true`: h5diff exits 1 when it finds differences, which under pipefail, or with grep -q
# breaking its pipe, would read as "no difference".
same_bits() {
  local report
  report=$(h5diff -r --exclude-path /provenance --exclude-attribute /h5md/creator "$1" "$2" 2>&1 || true)
  if grep -q '^[1-9][0-9]* differences\? found' <<<"$report"; then echo no; else echo yes; fi
}
