#!/usr/bin/env bash
# A LAUNCH prefix for the cluster test, after `srun -n1 -c1`: appends "JOB STEP TOOL OUTPUT" to $STEP_LOG
# (the job and step srun gave it, the tool and its -o file), then becomes the command.
set -euo pipefail
out= prev=
for arg in "$@"; do
  [[ $prev == -o ]] && out=$arg
  prev=$arg
done
echo "${SLURM_JOB_ID:-none} ${SLURM_STEP_ID:-none} $(basename "$1") $out" >> "$STEP_LOG"
exec "$@"
