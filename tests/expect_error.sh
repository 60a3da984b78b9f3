#!/usr/bin/env bash
# Run the executable on a bad parameter file and check that it (1) exits
# non-zero, (2) prints an error matching the file's "# expect: REGEX" line
# and (3) writes no result file (or, with a "# allow: partial results" line,
# only valid CSV files: a solver failure after the run started).
# On NP > 1 ranks also that the error is printed once: one "Error:" line,
# one line matching REGEX, so no copy of another rank, glued or not.
# On any number of ranks: no deal.II stack banner, no "TimerOutput ...
# uncaught exception" notice and no timer table.
# A "# expect on NP ranks: REGEX" line replaces REGEX for a run on NP ranks.
# A "# env: NAME=VALUE" line sets that environment variable for the run
# (e.g. CYCLOID_AVAILABLE_MEMORY_MB, the memory the cost check sees).
# A "# block: PATH" line makes PATH (relative to WORKDIR) a directory before
# the run, so that a file the run writes there cannot be opened (on rank 0
# only: an error on one rank).
# Usage: expect_error.sh EXECUTABLE PRM WORKDIR [NP]
set -u
exe=$1 prm=$2 work=$3 np=${4:-1}
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
if [ -f "$prm" ]; then
  expect=$(sed -n 's/^# expect: //p' "$prm")
  expect_np=$(sed -n "s/^# expect on $np ranks: //p" "$prm")
  [ -n "$expect_np" ] && expect=$expect_np
  for path in $(sed -n 's/^# block: //p' "$prm"); do mkdir -p "$path"; done
  for kv in $(sed -n 's/^# env: //p' "$prm"); do export "$kv"; done
else
  expect="cannot open the parameter file"
fi
if [ "$np" -gt 1 ]; then
  flags=()
  [ "$(id -u)" -eq 0 ] && flags+=(--allow-run-as-root)
  [ "$(nproc)" -lt "$np" ] && flags+=(--oversubscribe)
  mpirun "${flags[@]}" -np "$np" "$exe" "$prm" >stdout.txt 2>stderr.txt
else
  "$exe" "$prm" >stdout.txt 2>stderr.txt
fi
status=$?
fail() { echo "FAIL: $1"; echo "--- stdout"; cat stdout.txt; echo "--- stderr"; cat stderr.txt; exit 1; }
[ "$status" -ne 0 ] || fail "exit status 0 for $prm"
grep -Eq "$expect" stderr.txt || fail "stderr does not match '$expect'"
grep -q "An error occurred in line" stderr.txt \
  && fail "the user sees a deal.II stack banner instead of a message"
grep -q "TimerOutput" stderr.txt stdout.txt \
  && fail "deal.II's TimerOutput notice is printed"
grep -Eq "wallclock time elapsed|^\| Section " stderr.txt stdout.txt \
  && fail "a timer table is printed after the error"
if [ "$np" -gt 1 ]; then
  n_error=$(grep -c "Error:" stderr.txt)
  n_expect=$(grep -Ec "$expect" stderr.txt)
  [ "$n_error" -eq 1 ] || fail "$n_error lines hold 'Error:' (expected 1)"
  [ "$n_expect" -eq 1 ] || fail "$n_expect lines match '$expect' (expected 1)"
  grep -q "Error:.*Error:" stderr.txt && fail "two messages on one line"
fi
if [ -f "$prm" ] && grep -q '^# allow: partial results' "$prm"; then
  # A solver failure after the run started: what was written must be valid
  # CSV (a header line, then complete rows of as many fields).
  for f in $(find . -type f -name '*.csv'); do
    awk -F, 'NR == 1 { n = NF } NF != n { bad = 1 } END { exit bad || NR < 1 }' "$f" \
      || { echo "FAIL: $f is not a valid CSV after the error"; cat "$f"; exit 1; }
  done
elif find . -type f -name '*.csv' | grep -q .; then
  fail "results were written for a bad input: $(find . -type f -name '*.csv')"
fi
echo "ok: exit $status on $np rank(s), message: $(head -c 400 stderr.txt)"
