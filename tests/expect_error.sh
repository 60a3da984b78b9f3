#!/usr/bin/env bash
# Run the executable on a bad parameter file and check that it (1) exits
# non-zero, (2) prints an error matching the file's "# expect: REGEX" line
# and (3) writes no result file (or, with a "# allow: partial results" line,
# only valid CSV files: a solver failure after the run started).
# Usage: expect_error.sh EXECUTABLE PRM WORKDIR
set -u
exe=$1 prm=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
if [ -f "$prm" ]; then
  expect=$(sed -n 's/^# expect: //p' "$prm")
else
  expect="cannot open the parameter file"
fi
"$exe" "$prm" >stdout.txt 2>stderr.txt
status=$?
if [ "$status" -eq 0 ]; then
  echo "FAIL: exit status 0 for $prm"; cat stdout.txt stderr.txt; exit 1
fi
if ! grep -Eq "$expect" stderr.txt; then
  echo "FAIL: stderr does not match '$expect':"; cat stderr.txt; exit 1
fi
if grep -q "An error occurred in line" stderr.txt; then
  echo "FAIL: the user sees a deal.II stack banner instead of a message:"; cat stderr.txt; exit 1
fi
if [ -f "$prm" ] && grep -q '^# allow: partial results' "$prm"; then
  # A solver failure after the run started: what was written must be valid
  # CSV (a header line, then complete rows of as many fields).
  for f in $(find . -name '*.csv'); do
    awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad || NR < 1 }' "$f" \
      || { echo "FAIL: $f is not a valid CSV after the error"; cat "$f"; exit 1; }
  done
elif find . -name '*.csv' | grep -q .; then
  echo "FAIL: results were written for a bad input:"; find . -name '*.csv'; exit 1
fi
echo "ok: exit $status, message: $(head -c 300 stderr.txt)"
