#!/usr/bin/python3
"""Are two builds' results the same to the last bit?

Runs each prm file with two executables (2 ranks, no solution files) and
compares every number of every CSV file the runs write, skipping only the
columns that measure the machine (wall_s, peak_memory_MB). Prints, per
prm, the largest relative difference and where it is, over the columns
both builds write, and the columns only the new build writes (a new
output column is not a changed result); row counts, the old build's
columns and text columns must match exactly.

A refactoring that must leave results unchanged is checked with it against
the build before it, e.g. (from tests/runs/):

    /usr/bin/python3 ../../benchmarks/bit_identity/compare.py \\
        /tmp/base-build/cycloid-contact ../../build/cycloid-contact \\
        /tmp/bit-identity analytic-sweep.prm quasi-static-3d.prm

Exit status 1 if any prm differs or fails.
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

MACHINE_COLUMNS = ("wall_s", "peak_memory_MB")


def run(exe, prm, out):
    """Run @p prm with @p exe into @p out (a copy of the prm sets it)."""
    copy = out.parent / (out.name + ".prm")
    copy.write_text(Path(prm).read_text() +
                    f"\nset Output directory = {out}\n"
                    "set Write solution = false\n")
    return run_cycloid(2, exe, str(copy))


def relative(u, v):
    """Relative difference of two CSV texts (0 for equal texts)."""
    if u == v:
        return 0.0
    try:
        a, b = float(u), float(v)
    except ValueError:
        return math.inf
    if math.isnan(a) and math.isnan(b):
        return 0.0
    return abs(a - b) / max(abs(a), abs(b), 1e-300)


def compare(old, new):
    """Largest relative difference over the CSV files of two directories,
    and where it is, over the columns both have; and the columns only the
    new build writes (a new output column is not a changed result). A
    column the old build wrote and the new one does not, or a different
    row count, is a difference (inf)."""
    worst, where, added = 0.0, "", []
    for f in sorted(old.glob("*.csv")):
        a, b = read_csv(f), read_csv(new / f.name, missing_ok=True)
        if len(a) != len(b) or (a and not set(a[0]) <= set(b[0])):
            return math.inf, f"{f.name}: columns or rows differ", added
        if a:
            added += [f"{f.name}:{c}" for c in b[0] if c not in a[0]]
        for x, y in zip(a, b):
            for col in x:
                if col in MACHINE_COLUMNS:
                    continue
                d = relative(x[col], y[col])
                if d > worst:
                    worst, where = d, f"{f.name}:{col}"
    return worst, where, added


def main():
    old, new, work = sys.argv[1], sys.argv[2], Path(sys.argv[3])
    work.mkdir(parents=True, exist_ok=True)
    failed = False
    for prm in sys.argv[4:]:
        name = Path(prm).stem
        a = run(old, prm, work / f"{name}-old")
        b = run(new, prm, work / f"{name}-new")
        if a.returncode or b.returncode:
            print(f"{name}: exit {a.returncode} / {b.returncode}")
            failed = True
            continue
        worst, where, added = compare(work / f"{name}-old", work / f"{name}-new")
        failed |= worst > 0
        print(f"{name:34s} largest relative difference {worst:.3g} "
              f"({where or 'none'}); {a.wall_s:.1f} s / {b.wall_s:.1f} s"
              + (f"; new columns: {', '.join(added)}" if added else ""),
              flush=True)
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())
