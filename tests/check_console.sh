#!/usr/bin/env bash
# Run the executable on a parameter file that must work and check its
# console: exit status 0, every "# console: REGEX" line of the file matches
# a line of stdout or stderr (extended regex), no "# absent: REGEX" line
# does. A "# first line: TEXT" line must be stdout's first line exactly.
# Usage: check_console.sh EXECUTABLE PRM WORKDIR
set -u
exe=$1 prm=$2 work=$3
rm -rf "$work" && mkdir -p "$work" && cd "$work" || exit 1
"$exe" "$prm" >stdout.txt 2>stderr.txt
status=$?
fail() { echo "FAIL: $1"; echo "--- stdout"; cat stdout.txt; echo "--- stderr"; cat stderr.txt; exit 1; }
[ "$status" -eq 0 ] || fail "exit status $status for $prm"
cat stdout.txt stderr.txt >console.txt
while IFS= read -r regex; do
  grep -Eq -- "$regex" console.txt || fail "no console line matches '$regex'"
done < <(sed -n 's/^# console: //p' "$prm")
while IFS= read -r regex; do
  grep -Eq -- "$regex" console.txt && fail "a console line matches '$regex'"
done < <(sed -n 's/^# absent: //p' "$prm")
first=$(sed -n 's/^# first line: //p' "$prm")
if [ -n "$first" ]; then
  [ "$(head -n 1 stdout.txt)" = "$first" ] \
    || fail "stdout's first line is '$(head -n 1 stdout.txt)', not '$first'"
fi
echo "ok: $prm"
