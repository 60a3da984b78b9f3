"""What the run checkers share: collecting the checks that fail, reading a
CSV file's rows, the verdict with the exit status, and a run on 2 ranks
with the debug output."""
import csv
import os
import subprocess
import sys

failures = []


def check(condition, message):
    """Record @p message if @p condition is false; return the condition."""
    if not condition:
        failures.append(message)
    return condition


def rows(path):
    """The rows of a one-header-line CSV file as dicts of strings."""
    with open(path) as f:
        return list(csv.DictReader(f))


def verdict(passed="all checks passed", shown=30):
    """Print the failed checks (the first @p shown) or @p passed; the exit
    status: 1 if any check failed, else 0."""
    if failures:
        print(f"{len(failures)} check(s) failed:")
        for f in failures[:shown]:
            print("  ", f)
        return 1
    print(passed)
    return 0


def run_debug(exe, prm, out):
    """Run @p exe on @p prm on 2 ranks with CYCLOID_DEBUG=1, stdout and
    stderr into out.log; exit naming the log if the run fails, else return
    the log's text."""
    flags = ["--allow-run-as-root"] if os.getuid() == 0 else []
    env = dict(os.environ, CYCLOID_DEBUG="1")
    with open(out + ".log", "w") as log:
        rc = subprocess.call(["mpirun"] + flags + ["-np", "2", exe, prm],
                             stdout=log, stderr=subprocess.STDOUT, env=env)
    text = open(out + ".log").read()
    if rc != 0:
        sys.exit("%s failed (see %s.log):\n%s" % (prm, out, text[-2000:]))
    return text


def merge_csv(path, columns, new, key, replaced):
    """Write @p new (dicts) to the CSV file @p path with @p columns, after
    the rows already in it whose @p key is not in @p replaced; return
    @p path. A benchmark that re-runs some of its cases keeps the others."""
    kept = rows(path) if os.path.exists(path) else []
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        w.writerows([r for r in kept if r[key] not in replaced] + new)
    return path
