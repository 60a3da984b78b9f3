#!/usr/bin/env bash
# Install what is missing, build, and run the test suite (ctest). Exits
# non-zero on any failure. .ci/run calls exactly this.
set -euo pipefail
source "$(dirname "${BASH_SOURCE[0]}")/setup.sh"
cd "$CYCLOID_BUILD"
ctest --output-on-failure -j "$(nproc)" "$@"
