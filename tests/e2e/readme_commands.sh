#!/usr/bin/env bash
# Keeps the manual true: runs every command of the README's code blocks, in order, in one scratch folder
# (later commands use the files earlier ones wrote), with the tools of this build on the PATH, and fails
# on the first command that exits non-zero. Make targets run as their miniature (MINI=1) with the built
# tools; the test suite and the benchmarks are not run from here (the suite is what runs this; timings
# are not tests), nor SLURM commands (sbatch, srun, salloc …: no cluster here): for those only the target
# or script is checked to exist.
# Usage: readme_commands.sh SOURCE_DIR BUILD_DIR WORK_DIR
set -euo pipefail
src=$1 build=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work"
fail() { echo "FAIL: $*" >&2; exit 1; }
for entry in data pipelines scripts bench Makefile.analysis; do ln -s "$src/$entry" .; done
export PATH=$build/tools:$PATH

# The lines inside ``` fences (plain, sh or bash), in order.
mapfile -t commands < <(awk '/^```/ { inside = !inside; next } inside && NF' "$src/README.md")
[[ ${#commands[@]} -ge 20 ]] || fail "only ${#commands[@]} commands found in README.md"

make_targets=$({ make -f Makefile.analysis -pRrq : 2>/dev/null || true; } | awk -F: '/^[a-z][a-z-]*:/ { print $1 }' | sort -u)
ran=0 checked=0
for command in "${commands[@]}"; do
  if [[ $command =~ ^make\ -f\ Makefile\.analysis\ ([a-z-]+) ]]; then
    target=${BASH_REMATCH[1]}
    grep -qx -- "$target" <<<"$make_targets" || fail "README names a make target that does not exist: $target"
    case $target in
      test|sanitize-test|bench) checked=$((checked + 1)); echo "checked (not run here): $command"; continue ;;
    esac
    command="make -f Makefile.analysis $target MINI=1 NO_BUILD=1 BUILD=$build RESULTS=$work/results JOBS=2"
  elif [[ $command =~ ^([A-Za-z_]+=\$\()?(sbatch|srun|salloc|squeue|scontrol|scancel|sinfo)\  ]]; then
    # SLURM commands need a cluster: not run here; the scripts and make targets they name must exist.
    read -ra words <<<"$command"
    for word in "${words[@]}"; do
      word=${word%)}
      [[ $word == scripts/* ]] || continue
      [[ -f $word ]] && bash -n "$word" || fail "README names a script that does not exist or parse: $word"
    done
    if [[ $command =~ make\ -f\ Makefile\.analysis\ ([a-z-]+) ]]; then
      grep -qx -- "${BASH_REMATCH[1]}" <<<"$make_targets" || fail "README names a make target that does not exist: ${BASH_REMATCH[1]}"
    fi
    checked=$((checked + 1)); echo "checked (needs SLURM, not run here): $command"; continue
  elif [[ $command =~ ^([A-Z0-9_]+=[^\ ]+\ )*bash\ (bench/[a-z_/-]+\.sh) ]]; then
    script=${BASH_REMATCH[2]}
    bash -n "$script" || fail "README names a benchmark script that does not parse: $script"
    checked=$((checked + 1)); echo "checked (not run here): $command"; continue
  fi
  echo "\$ $command"
  set +e; bash -o pipefail -c "$command" >"$work/last.out" 2>"$work/last.err"; rc=$?; set -e
  if [[ $rc -ne 0 ]]; then
    tail -n 20 "$work/last.err" >&2
    fail "exit $rc: $command"
  fi
  ran=$((ran + 1))
done
echo "README: $ran commands ran, $checked checked"
