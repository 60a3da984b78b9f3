#!/usr/bin/env bash
# Quick start: install what is missing, build, and run a parameter file on
# 2 MPI ranks.   Usage: scripts/run.sh [file.prm]   (default prm/seed-case.prm)
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
prm=${1:-$CYCLOID_ROOT/prm/seed-case.prm}
[ -f "$prm" ] || { echo "error: parameter file '$prm' not found" >&2; exit 1; }
cycloid_mpirun 2 "$CYCLOID_BUILD/cycloid-contact" "$prm"
