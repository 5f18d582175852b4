#!/usr/bin/env bash
# mpirun as the MPI tests need it on any machine, two cores included: more ranks than cores (--oversubscribe),
# no binding (a bound rank silently runs one OpenMP thread), as root when the tests run as root, a time limit so
# that a hang fails (exit 110). Usage: mpirun.sh RANKS COMMAND [ARGS...]
set -euo pipefail
ranks=$1
shift
flags=(--oversubscribe --bind-to none --timeout "${MPI_TEST_TIMEOUT:-120}")
[[ $(id -u) -ne 0 ]] || flags+=(--allow-run-as-root)
exec mpirun "${flags[@]}" -n "$ranks" "$@"
