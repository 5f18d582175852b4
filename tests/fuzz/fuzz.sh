#!/usr/bin/env bash
# Fuzzes every reading tool: makes small valid files of every kind (a cell mesh, a node mesh, a DEM run, a
# rubber run, a wave run, a fragments file; a scene of each engine, a column of values), then runs fuzz_readers on MUTANTS mutants of each through
# every tool that reads that kind (and through standard input). Fails on any signal, hang or exit code
# other than 0, 1 and 2; the failing mutants are kept in WORK/failures.
# Usage: fuzz.sh SOURCE_DIR BIN_DIR DRIVER WORK_DIR MUTANTS [SEED [TIMEOUT_S [MEMORY_MB]]]
set -euo pipefail
src=$1 bin=$2 driver=$3 work=$4 mutants=$5 seed=${6:-1} timeout=${7:-20} memory=${8:-4096}
scenes=$src/data/scenes
rm -rf "$work" && mkdir -p "$work" && cd "$work"
work=$(pwd)

"$bin/mesh-gen" voronoi --shape disc --diameter 0.06 --cells 60 --seed 3 -q -o mesh.h5
"$bin/mesh-gen" triangular --nodes 12x6 --spacing 1e-3 -q -o strip.h5
"$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 2e-5 --output.frame_interval 5e-6 -q -o run.h5
"$bin/rubber-run" --scene "$scenes/stretch.ini" strip.h5 --crack.seed_length 0 --stop.t_max 1e-4 --output.frame_interval 3e-5 -q -o rubber.h5
"$bin/mesh-gen" triangular --nodes 100x4 --spacing 1e-3 -q |
  "$bin/rubber-run" --scene "$scenes/wave.ini" - --stop.t_max 5e-4 --output.frame_interval 2e-5 -q -o wave.h5
# Long enough for the disc to break into dozens of fragments (powerlaw-fit needs 10 values or more).
"$bin/dem-run" --scene "$scenes/explosion.ini" mesh.h5 --stop.t_max 1e-4 --output.frame_interval 1e-4 -q -o broken.h5
"$bin/fragment-count" broken.h5 -q -o fragments.h5

# Checkpoints: a run killed after its first checkpoint (every 2 steps) leaves one; the same command line with
# --resume reads it.
make_checkpoint() {
  local out=$1; shift
  "$@" -o "$out" --checkpoint-every 2 -q &
  local pid=$!
  for _ in $(seq 500); do [[ -s $out.ckpt ]] && break; sleep 0.02; done
  kill -KILL "$pid" 2>/dev/null || true
  wait "$pid" 2>/dev/null || true
  [[ -s $out.ckpt ]] || { echo "fuzz.sh: no checkpoint of $*" >&2; exit 1; }
}
dem_checkpointed=("$bin/dem-run" --scene "$scenes/explosion.ini" "$work/mesh.h5" --stop.t_max 2e-3 --output.frame_interval 5e-4)
rubber_checkpointed=("$bin/rubber-run" --scene "$scenes/stretch.ini" "$work/strip.h5" --crack.seed_length 0 --stop.t_max 2e-4
                     --output.frame_interval 3e-5)
make_checkpoint dem.h5 "${dem_checkpointed[@]}"
make_checkpoint rubber-ck.h5 "${rubber_checkpointed[@]}"

cp "$scenes/explosion.ini" explosion.ini
cp "$scenes/stretch.ini" stretch.ini
awk 'BEGIN { print "# fragment masses"; for (k = 1; k <= 200; k++) printf "%.6g\n", (1 - (k - 0.5) / 200) ^ (-1 / 1.5) }' > values.txt

short_dem=(--stop.t_max 2e-6 -q -o out.h5)
{
  echo "$work/mesh.h5 $bin/mesh-gen check {} -q"
  echo "$work/mesh.h5 $bin/mesh-gen check - -q <{}"
  echo "$work/mesh.h5 $bin/dem-run --scene $scenes/explosion.ini {} ${short_dem[*]}"
  echo "$work/mesh.h5 $bin/render {} -q -o out.png"
  echo "$work/mesh.h5 $bin/h5-xdmf {} -q -o out.xmf"
  echo "$work/strip.h5 $bin/mesh-gen check {} -q"
  echo "$work/strip.h5 $bin/rubber-run --scene $scenes/stretch.ini {} --crack.seed_length 0 --stop.t_max 2e-5 -q -o out.h5"
  echo "$work/strip.h5 $bin/render {} -q -o out.svg"
  echo "$work/run.h5 $bin/observables {} -q"
  echo "$work/run.h5 $bin/observables - --compare $work/run.h5 -q <{}"
  echo "$work/run.h5 $bin/fragment-count {} -q -o out.h5"
  echo "$work/run.h5 $bin/render {} -q -o out.png"
  echo "$work/run.h5 $bin/h5-xdmf {} -q -o out.xmf"
  echo "$work/run.h5 $bin/wave-speed {} --format text -q"
  echo "$work/run.h5 $bin/mesh-gen check {} -q"
  echo "$work/rubber.h5 $bin/observables {} -q"
  echo "$work/rubber.h5 $bin/observables {} --crack-shape -q"
  echo "$work/rubber.h5 $bin/render {} -q -o out.png"
  echo "$work/rubber.h5 $bin/h5-xdmf {} -q -o out.xmf"
  echo "$work/wave.h5 $bin/wave-speed {} --format text -q"
  echo "$work/wave.h5 $bin/observables {} -q"
  echo "$work/fragments.h5 $bin/powerlaw-fit {} --bootstrap 0 --gof-samples 0 --format text -q"
  echo "$work/fragments.h5 $bin/powerlaw-fit - --bootstrap 0 --gof-samples 0 -q -o out.h5 <{}"
  echo "$work/fragments.h5 $bin/render $work/broken.h5 --fragments {} -q -o out.png"
  echo "$work/fragments.h5 $bin/h5-xdmf $work/broken.h5 --fragments {} -q -o out.xmf"
  echo "$work/dem.h5.ckpt ${dem_checkpointed[*]} --resume {} -q -o out.h5"
  echo "$work/rubber-ck.h5.ckpt ${rubber_checkpointed[*]} --resume {} -q -o out.h5"
  # Text inputs; a damaged scene may ask for any time step or length of run: the steps are capped.
  echo "$work/explosion.ini $bin/dem-run --scene {} $work/mesh.h5 --stop.t_max 2e-6 --stop.max_steps 40 -q -o out.h5"
  echo "$work/stretch.ini $bin/rubber-run --scene {} $work/strip.h5 --crack.seed_length 0 --stop.t_max 2e-5 --stop.max_steps 200 -q -o out.h5"
  echo "$work/values.txt $bin/powerlaw-fit {} --bootstrap 0 --gof-samples 0 --format text -q"
  echo "$work/values.txt $bin/powerlaw-fit - --bootstrap 0 --gof-samples 0 --format text -q <{}"
} > spec.txt

"$driver" --spec spec.txt --mutants "$mutants" --seed "$seed" --timeout "$timeout" --memory "$memory" \
  --jobs "${FUZZ_JOBS:-2}" --work "$work/runs"
