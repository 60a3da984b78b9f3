#!/usr/bin/env bash
# Run a prm on 1 and on 2 MPI ranks, then a checker on both outputs.
# Usage: run_ranks.sh EXECUTABLE PRM WORKDIR CHECKER [EXTRA CHECKER ARGS]
# With CYCLOID_RANKS=2 the run is made on 2 ranks only and the checker gets
# that output twice (for scenes too costly to run twice in ctest; the 1-vs-2
# rank comparison is then left to the cheaper runs of the same code).
set -euo pipefail
exe=$1 prm=$2 work=$3 checker=$4
shift 4
flags=()
[ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)
[ "$(nproc)" -lt 2 ] && flags+=(--oversubscribe)
rm -rf "$work" && mkdir -p "$work" && cd "$work"
# The output directory as deal.II reads the prm (not a second parser).
outdir=$("$exe" --print-parameters=json "$prm" | /usr/bin/python3 -c \
  'import json, sys; print(json.load(sys.stdin)["Output directory"]["value"])')
if [ "${CYCLOID_RANKS:-1,2}" = "2" ]; then
  mpirun "${flags[@]}" -np 2 "$exe" "$prm"
  mv "$outdir" np2
  ln -s np2 np1
else
  mpirun "${flags[@]}" -np 1 "$exe" "$prm"
  mv "$outdir" np1
  mpirun "${flags[@]}" -np 2 "$exe" "$prm"
  mv "$outdir" np2
fi
/usr/bin/python3 "$checker" "$prm" np1 np2 "$exe" "$@"
