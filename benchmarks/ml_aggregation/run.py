#!/usr/bin/python3
"""ML aggregating whole nodes against single DoFs in 3D (issue #14 item 1),
side by side in one run.

Usage: benchmarks/ml_aggregation/run.py --before EXE [--exe EXE]
           [--repeat N] [--out CSV]

Runs benchmarks/ml_aggregation/two-discs-3d.prm (290 k DoFs, one state) on
2 ranks with two builds, interleaved, N times each: --exe (default
build/cycloid-contact: in 3D ML is told that a node's three rows belong
together, "PDE equations" = 3) and --before, a build of commit 5763e09 or
earlier (single-DoF aggregates; e.g. `git worktree add /tmp/before 5763e09`
and build it as scripts/setup.sh does). Per run: the
whole command's wall time, the peak resident memory of the largest rank
(GNU time), CG iterations, active-set iterations, K_secant, K_tangent and
the timer's solve and preconditioner sections; then the median ratio
nodes / dofs and the largest relative difference of K. The load
average at the start is printed and written: on a shared machine only the
ratio of neighbouring runs means much.
"""
import argparse
import csv
import os
import re
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
PRM = os.path.join(os.path.dirname(os.path.abspath(__file__)), "two-discs-3d.prm")
WORK = "/tmp/cycloid-ml-aggregation"
SOLVERS = ("nodes", "dofs")


def section(log, name):
    m = re.search(r"\| %s\s*\|\s*\d+\s*\|\s*([\d.]+)s" % re.escape(name), log)
    return float(m.group(1)) if m else float("nan")


def run(exes, solver, k):
    exe = exes[solver]
    out = os.path.join(WORK, "%s-%d" % (solver, k))
    os.makedirs(WORK, exist_ok=True)
    with open(out + ".prm", "w") as f:
        f.write(open(PRM).read())
        f.write("set Output directory = %s\n" % out)
    load = os.getloadavg()[0]
    p = run_cycloid(2, exe, out + ".prm", peak_memory=True)
    if p.returncode != 0:
        sys.exit("%s failed:\n%s" % (out, p.stdout[-2000:] + p.stderr[-2000:]))
    row = read_csv(os.path.join(out, "stiffness.csv"))[0]
    return {"solver": solver, "repeat": k, "load_average": load, "wall_s": p.wall_s,
            "peak_rss_largest_rank_MB": p.peak_rss_MB,
            "linear_iterations": int(row["linear_iterations"]),
            "active_set_iterations": int(row["active_set_iterations"]),
            "K_secant_Nm_per_rad": float(row["K_secant_Nm_per_rad"]),
            "K_tangent_Nm_per_rad": float(row["K_tangent_Nm_per_rad"]),
            "solves_s": section(p.stdout, "contact: linear solves"),
            "preconditioner_s": section(p.stdout, "contact: preconditioner")}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=2)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "cycloid-contact"))
    ap.add_argument("--before", required=True)
    ap.add_argument("--out", default=os.path.join(ROOT, "doc", "ml-aggregation.csv"))
    args = ap.parse_args()
    rows = []
    for k in range(args.repeat):
        for solver in (SOLVERS if k % 2 == 0 else SOLVERS[::-1]):
            r = run({"nodes": args.exe, "dofs": args.before}, solver, k)
            rows.append(r)
            print("%-12s run %d (load %.2f): %.1f s, %.0f MB, %d CG its, solves %.1f s, "
                  "preconditioner %.1f s, K_secant %.10g" %
                  (solver, k, r["load_average"], r["wall_s"], r["peak_rss_largest_rank_MB"],
                   r["linear_iterations"], r["solves_s"], r["preconditioner_s"],
                   r["K_secant_Nm_per_rad"]), flush=True)
    with open(args.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    med = {s: {c: statistics.median(r[c] for r in rows if r["solver"] == s)
               for c in ("wall_s", "peak_rss_largest_rank_MB", "solves_s", "preconditioner_s")}
           for s in SOLVERS}
    for c in ("wall_s", "peak_rss_largest_rank_MB", "solves_s", "preconditioner_s"):
        print("median %-26s nodes / dofs = %.3f" % (c, med["nodes"][c] / med["dofs"][c]))
    for c in ("K_secant_Nm_per_rad", "K_tangent_Nm_per_rad"):
        ref = rows[0][c]
        print("largest relative difference of %s: %.2e" % (c, max(abs(r[c] - ref) for r in rows) / abs(ref)))
    print("written", args.out)


if __name__ == "__main__":
    main()
