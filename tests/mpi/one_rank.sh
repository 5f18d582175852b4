#!/usr/bin/env bash
# dem-run started as two ranks (it runs one process per run): exit 2 from the job, one message, no output; and
# started on its own, it runs as always. Usage: one_rank.sh TOOLS_DIR SCENES_DIR
set -euo pipefail
tools=$1 scenes=$2
here=$(cd "$(dirname "$0")" && pwd)
work=$(mktemp -d)
trap 'rm -rf "$work"' EXIT
"$tools/mesh-gen" voronoi --shape disc --diameter 0.2 --cells 200 --seed 3 -q -o "$work/disc.h5"
set +e
bash "$here/mpirun.sh" 2 "$tools/dem-run" --scene "$scenes/explosion.ini" "$work/disc.h5" --stop.t_max 1e-5 -q \
  -o "$work/run.h5" 2> "$work/err"
code=$?
set -e
messages=$(grep -c "^dem-run: error: started as 2 ranks" "$work/err" || true)
[[ $code -eq 2 ]] || { echo "exit $code, expected 2"; cat "$work/err"; exit 1; }
[[ $messages -eq 1 ]] || { echo "$messages messages, expected 1"; cat "$work/err"; exit 1; }
[[ ! -e $work/run.h5 ]] || { echo "an output was written"; exit 1; }
"$tools/dem-run" --scene "$scenes/explosion.ini" "$work/disc.h5" --stop.t_max 1e-5 -q -o "$work/run.h5"
echo "two ranks refused with one message (exit 2); one process ran"
