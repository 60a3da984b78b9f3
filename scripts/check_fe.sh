#!/usr/bin/env bash
# Check a reduced (or analytic) run against the full FE model at the same
# states: scripts/check_fe.sh file.prm [--ranks N] [--mesh reference|quick]
# [--rerun]. Runs the file if its results are not there, then the FE model
# (it says what that will cost once it has meshed), and prints per state the
# distance in K_secant, K_tangent and every pin force next to both models'
# error estimates (scripts/check_fe.py; doc/reduced-model.md).
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
[ $# -ge 1 ] || { echo "usage: scripts/check_fe.sh file.prm [--ranks N] [--mesh reference|quick] [--rerun]" >&2; exit 1; }
if [ "$(id -u)" -eq 0 ]; then
  export OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1
fi
exec /usr/bin/python3 "$CYCLOID_ROOT/scripts/check_fe.py" "$@" --exe "$CYCLOID_BUILD/cycloid-contact"
