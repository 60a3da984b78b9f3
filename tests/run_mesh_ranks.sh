#!/usr/bin/env bash
# Run `Run = mesh` on 1 and on 2 MPI ranks and compare both outputs with
# an independent VTK reader.   Usage: run_mesh_ranks.sh EXECUTABLE PRM WORKDIR
set -euo pipefail
exe=$1 prm=$2 work=$3
here=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
flags=()
[ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)
[ "$(nproc)" -lt 2 ] && flags+=(--oversubscribe)
rm -rf "$work" && mkdir -p "$work" && cd "$work"
outdir=$(sed -n 's/^ *set Output directory *= *//p' "$prm")
mpirun "${flags[@]}" -np 1 "$exe" "$prm"
mv "$outdir" np1
mpirun "${flags[@]}" -np 2 "$exe" "$prm"
mv "$outdir" np2
cmp np1/mesh.csv np2/mesh.csv
/usr/bin/python3 "$here/check_mesh_output.py" "$prm" np1 np2
