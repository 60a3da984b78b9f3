#!/usr/bin/env bash
# Run the executable on NP MPI ranks in WORKDIR, then a checker script on
# the output directory that the prm names.
# Usage: run_and_check.sh NP EXECUTABLE PRM WORKDIR CHECKER [ARGS...]
set -euo pipefail
np=$1 exe=$2 prm=$3 work=$4 checker=$5
shift 5
rm -rf "$work" && mkdir -p "$work" && cd "$work"
flags=()
[ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)
[ "$(nproc)" -lt "$np" ] && flags+=(--oversubscribe)
mpirun "${flags[@]}" -np "$np" "$exe" "$prm"
# The output directory as deal.II reads the prm (not a second parser).
outdir=$("$exe" --print-parameters=json "$prm" | /usr/bin/python3 -c \
  'import json, sys; print(json.load(sys.stdin)["Output directory"]["value"])')
/usr/bin/python3 "$checker" "$prm" "$work/$outdir" "$@"
