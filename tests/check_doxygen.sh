#!/usr/bin/env bash
# Run Doxygen on the library headers (doc/Doxyfile) and fail on any warning.
# Usage: check_doxygen.sh SOURCE_DIR WORK_DIR
set -euo pipefail
src=$1 work=$2
rm -rf "$work" && mkdir -p "$work"
cd "$src/doc"
CYCLOID_DOXYGEN_OUTPUT="$work" doxygen Doxyfile >"$work/stdout.txt" 2>&1
if [ -s "$work/warnings.txt" ]; then
  echo "FAIL: $(wc -l <"$work/warnings.txt") Doxygen warnings:"
  head -50 "$work/warnings.txt"
  exit 1
fi
echo "ok: Doxygen ran without warnings"
