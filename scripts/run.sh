#!/usr/bin/env bash
# Quick start: install what is missing, build, and run a parameter file on
# 2 MPI ranks.   Usage: scripts/run.sh [file.prm]   (default prm/seed-case.prm:
# the seed case with the reduced 3D model, about a minute; it then prints how
# far the run is from the full 3D FE model's reference of the same states)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
prm=${1:-$CYCLOID_ROOT/prm/seed-case.prm}
[ -f "$prm" ] || { echo "error: parameter file '$prm' not found" >&2; exit 1; }
cycloid_mpirun 2 "$CYCLOID_BUILD/cycloid-contact" "$prm"
if [ $# -eq 0 ]; then
  /usr/bin/python3 "$CYCLOID_ROOT/scripts/compare_reference.py" output/seed-case \
    "$CYCLOID_ROOT/doc/reduced/seed-reference.csv"
fi
