#!/usr/bin/python3
"""The same prm on 1, 2, 4 and 8 MPI ranks (issue #14 item 3): do the
results agree, and how does each rank's peak memory fall with the ranks?

Usage: benchmarks/ranks/run.py [--case NAME[,NAME]] [--ranks 1,2,4,8]
           [--mesh shared[,distributed]] [--repeat K] [--exe EXE]
           [--out DIR] [--csv NAME]

Cases (prm files of the repository, run as they are, no VTU output):
  3d-one-disc    tests/runs/quasi-static-3d.prm: one disc, elastic pins on
                 their axes, 100 650 DoFs, 300 and 1000 N m
  3d-housing     tests/runs/quasi-static-3d-housing.prm: two discs, pins in
                 the housing, 300 and 1000 N m
  3d-290k        benchmarks/ml_aggregation/two-discs-3d.prm: two discs,
                 290 244 DoFs, one state (the memory benchmark's case)
  3d-seed        prm/quasi-static-3d.prm: the 3D seed case, 1.5 M DoFs, one
                 state (not in the default list: about 20 minutes on 2
                 and 4 ranks; run it with --case 3d-seed --ranks 2,4)

--mesh picks `Mesh/Triangulation`: shared (every rank holds every cell)
or distributed (p4est: each refined cell on one rank); each case runs on
every mesh given, the rank counts within, and every run is compared with
the case's first run.

More ranks than the machine's cores run oversubscribed (--oversubscribe):
that checks the answers, not the speed. Each rank runs under GNU time, so
every rank's peak resident memory is read, not only their sum
(`peak_memory_MB` of stiffness.csv).

Every run is compared with the first rank count by the comparison of the
test run.quasi-static-3d.ranks=4,8 (tests/check_ranks.py): the rotation beta,
K_secant and K_tangent (relative), every pin force (relative to the state's
largest), and whether the states have the same active set (active contact
nodes of every pin, engaged pins, active-set iterations).

Outputs in --out (doc/ranks): --csv (ranks.csv), one row per case, rank count and repeat; rows of other
cases already in it are kept. For the speed-up of 2 ranks over 1, run
`--ranks 1,2 --repeat 2 --csv speedup.csv` on an idle machine: the rank
counts alternate, so neighbouring runs compare.
"""
import argparse
import csv
import glob
import os
import sys
from pathlib import Path

ROOT = os.path.abspath(os.path.join(os.path.dirname(__file__), "..", ".."))
sys.path.insert(0, os.path.join(ROOT, "tests"))
from check_ranks import compare, prm_into, read  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402
CASES = {
    "3d-one-disc": "tests/runs/quasi-static-3d.prm",
    "3d-housing": "tests/runs/quasi-static-3d-housing.prm",
    "3d-290k": "benchmarks/ml_aggregation/two-discs-3d.prm",
    "3d-seed": "prm/quasi-static-3d.prm",
}
WORK = "/tmp/cycloid-ranks"


def run(case, ranks, exe, mesh):
    """Run CASES[case] on @p ranks ranks on the @p mesh triangulation;
    return the whole command's wall time, every rank's peak RSS [MB] and
    the output directory."""
    out = os.path.join(WORK, "%s-%s-np%d" % (case, mesh, ranks))
    prm = prm_into(os.path.join(ROOT, CASES[case]), out, mesh == "distributed")
    load = os.getloadavg()[0]
    # One file per rank: the ranks' stderr lines interleave.
    peak_file = out + ".peak."
    for old in glob.glob(peak_file + "*"):
        os.remove(old)
    rank_cmd = ('exec /usr/bin/time -f %%M -o %s$OMPI_COMM_WORLD_RANK %s %s' %
                (peak_file, exe, prm))
    p = run_cycloid(ranks, "sh", "-c", rank_cmd, peak_memory=True)
    if p.returncode != 0:
        sys.exit("%s on %d ranks failed:\n%s" %
                 (case, ranks, p.stdout[-3000:] + p.stderr[-3000:]))
    wall = p.wall_s
    peaks = [int(open(peak_file + str(r)).read().split()[-1]) / 1024.
             for r in range(ranks)]
    return wall, peaks, load, out


def measure(case, n, exe, ref, mesh):
    """Run @p case on @p n ranks on the @p mesh triangulation; its row of
    the CSV and its results."""
    wall, peaks, load, out = run(case, n, exe, mesh)
    result = read(out)
    d = compare(ref or result, result)
    states = result[0]
    row = {"case": case, "triangulation": mesh, "ranks": n,
           "dofs": states[0]["dofs"],
           "states": len(states), "load_average": round(load, 2),
           "wall_s": wall,
           "peak_memory_MB": float(states[-1]["peak_memory_MB"]),
           "largest_rank_MB": round(max(peaks), 1),
           "mean_rank_MB": round(sum(peaks) / n, 1),
           "active_set_iterations": " ".join(
               s["active_set_iterations"] for s in states),
           "pins_in_contact": " ".join(s["pins_in_contact"] for s in states),
           "d_beta": d["beta"], "d_K_secant": d["K_secant"],
           "d_K_tangent": d["K_tangent"], "d_pin_forces": d["pin_forces"],
           "same_active_set": d["same_active_set"]}
    print("  %-12s %s np%d: %s DoFs, %.1f s (load %.2f before), ranks' peak "
          "%.0f MB largest, %.0f MB mean (sum %.0f); against the first run: "
          "beta %.1e, K_sec %.1e, K_tan %.1e, pins %.1e, same set %d" %
          (case, mesh, n, row["dofs"], wall, load, row["largest_rank_MB"],
           row["mean_rank_MB"], row["peak_memory_MB"], d["beta"],
           d["K_secant"], d["K_tangent"], d["pin_forces"],
           d["same_active_set"]), flush=True)
    return row, result


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--case", default="3d-one-disc,3d-housing,3d-290k")
    ap.add_argument("--ranks", default="1,2,4,8")
    ap.add_argument("--mesh", default="shared",
                    help="Mesh/Triangulation values, comma separated")
    ap.add_argument("--repeat", type=int, default=1,
                    help="run the rank counts this many times, interleaved")
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "cycloid-contact"))
    ap.add_argument("--out", default=os.path.join(ROOT, "doc", "ranks"))
    ap.add_argument("--csv", default="ranks.csv")
    args = ap.parse_args()
    os.makedirs(WORK, exist_ok=True)
    os.makedirs(args.out, exist_ok=True)
    rows = []
    for case in args.case.split(","):
        ref = None
        for mesh in args.mesh.split(","):
            for k in range(args.repeat):
                for n in [int(x) for x in args.ranks.split(",")]:
                    row, result = measure(case, n, args.exe, ref, mesh)
                    ref = ref or result
                    rows.append(dict(row, repeat=k))
    # Keep the rows of the cases, meshes and rank counts not run now (the
    # seed case is run apart); rows from before the distributed mesh are
    # shared ones.
    path = os.path.join(args.out, args.csv)
    old = read_csv(path, missing_ok=True)
    now = {(r["case"], r["triangulation"], str(r["ranks"])) for r in rows}
    old = [dict(r, repeat=r.get("repeat", 0),
                triangulation=r.get("triangulation") or "shared") for r in old]
    rows = [r for r in old
            if (r["case"], r["triangulation"], r["ranks"]) not in now] + rows
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[-1]))
        w.writeheader()
        w.writerows(rows)
    print("wrote", path)


if __name__ == "__main__":
    main()
