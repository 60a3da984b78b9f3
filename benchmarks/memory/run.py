#!/usr/bin/python3
"""Where a state's memory goes (issue #14 item 2): rank 0's resident memory
after each stage of every active-set iteration, side by side for one or two
builds.

Usage: benchmarks/memory/run.py [--prm PRM] [--exe EXE] [--before EXE]
           [--before-env NAME=VALUE] [--ranks N] [--repeat K] [--out CSV]

Runs PRM (default benchmarks/ml_aggregation/two-discs-3d.prm: 3D, two
discs, 290 k DoFs, one state) with CYCLOID_DEBUG=1 on N ranks (default 2)
and reads the debug lines of the contact solver: per iteration rank 0's
resident memory after the assembly, the AMG set-up and the solves, the heap
in use (glibc's mallinfo2) and the peak so far. With --before, a second
build runs interleaved with --exe, K times each (its debug lines may lack
the memory figures; then only the whole-run figures are compared).
--before-env runs the "before" side with NAME=VALUE in its environment
(with --exe unless --before is given), e.g. CYCLOID_MMAP_THRESHOLD=0 for
the heap as the libraries leave it (doc/solver-reuse.md). Per run
it prints `peak_memory_MB` of stiffness.csv (VmHWM summed over the ranks),
the largest rank's peak (GNU time), kB per DoF with and without 150 MB per
rank for the program and its libraries, the state's wall_s, CG iterations
and K_secant. The load average at the start of each run is printed: on a
shared machine only neighbouring runs compare.
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
PRM = os.path.join(ROOT, "benchmarks", "ml_aggregation", "two-discs-3d.prm")
WORK = "/tmp/cycloid-memory"
LIBRARIES_MB = 150.  # an analytic run peaks at 151 MB per rank
ITERATION = re.compile(
    r"iteration (\d+) \((?:tight|loose[^)]*)\):.*rank 0 resident after assembly "
    r"([\d.]+) MB, preconditioner ([\d.]+) MB, solves ([\d.]+) MB, heap in use "
    r"([\d.]+) MB, peak ([\d.]+) MB")


def run(name, exe, prm, ranks, k, extra_env=None):
    out = os.path.join(WORK, "%s-%d" % (name, k))
    os.makedirs(WORK, exist_ok=True)
    with open(out + ".prm", "w") as f:
        f.write(open(prm).read())
        f.write("\nset Output directory = %s\n" % out)
    load = os.getloadavg()[0]
    env = dict(os.environ, CYCLOID_DEBUG="1", **(extra_env or {}))
    p = run_cycloid(ranks, exe, out + ".prm", env=env, peak_memory=True,
                    export=[key for key in env if key.startswith("CYCLOID_")])
    if p.returncode != 0:
        sys.exit("%s failed:\n%s" % (out, p.stdout[-2000:] + p.stderr[-2000:]))
    row = read_csv(os.path.join(out, "stiffness.csv"))[0]
    dofs = int(row["dofs"])
    peak = float(row["peak_memory_MB"])
    its = [tuple(float(x) for x in m.groups()) for m in ITERATION.finditer(p.stderr)]
    return {"build": name, "repeat": k, "load_average": load, "wall_s": p.wall_s,
            "state_wall_s": float(row["wall_s"]), "dofs": dofs,
            "peak_memory_MB": peak, "peak_rss_largest_rank_MB": p.peak_rss_MB,
            "kB_per_dof": 1024. * peak / dofs,
            "kB_per_dof_without_libraries": 1024. * (peak - ranks * LIBRARIES_MB) / dofs,
            "linear_iterations": int(row["linear_iterations"]),
            "K_secant_Nm_per_rad": float(row["K_secant_Nm_per_rad"]),
            "iterations": its}


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--prm", default=PRM)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "cycloid-contact"))
    ap.add_argument("--before")
    ap.add_argument("--before-env", metavar="NAME=VALUE")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(WORK, "memory.csv"))
    a = ap.parse_args()
    before_env = dict([a.before_env.split("=", 1)]) if a.before_env else None
    before_exe = a.before or (a.exe if before_env else None)
    builds = [("now", a.exe, None)] + (
        [("before", before_exe, before_env)] if before_exe else [])
    rows = []
    for k in range(a.repeat):
        for name, exe, extra_env in builds:
            r = run(name, exe, a.prm, a.ranks, k, extra_env)
            rows.append(r)
            print("%s #%d (load %.2f): %d DoFs, peak %.0f MB summed (%.2f kB/DoF, "
                  "%.2f without libraries), largest rank %.0f MB, state %.1f s, "
                  "%d CG its, K_secant %.10g"
                  % (name, k, r["load_average"], r["dofs"], r["peak_memory_MB"],
                     r["kB_per_dof"], r["kB_per_dof_without_libraries"],
                     r["peak_rss_largest_rank_MB"], r["state_wall_s"],
                     r["linear_iterations"], r["K_secant_Nm_per_rad"]))
            for it in r["iterations"]:
                print("  iteration %d: rank 0 resident %.0f after assembly, %.0f after "
                      "AMG, %.0f after solves; heap in use %.0f; peak %.0f MB" % it)
    if before_exe:
        for key in ("peak_memory_MB", "state_wall_s"):
            now = statistics.median(r[key] for r in rows if r["build"] == "now")
            old = statistics.median(r[key] for r in rows if r["build"] == "before")
            print("median %s: now / before = %.3f" % (key, now / old))
    keys = [k for k in rows[0] if k != "iterations"]
    with open(a.out, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        w.writerows(rows)
    print("wrote", a.out)


if __name__ == "__main__":
    main()
