#!/usr/bin/python3
"""Preconditioner reuse against a new pattern and hierarchy per active set
(issue #14 item 1), side by side in one run.

Usage: benchmarks/solver_reuse/run.py [--3d] [--repeat N] [--out CSV]

Cases (2 ranks, the whole command timed):
  qs-2d        prm/quasi-static-2d.prm as shipped (3 torques, Target
               accuracy 0.01, the error estimate's levels).
  transient-2d prm/transient-2d.prm to 3e-4 s (30 steps, 10 after the
               ramp), no checkpoints.
  qs-3d        (--3d) prm/quasi-static-3d.prm at Contact refinements 1 on
               both sides (the ladder's "p25 ax1 cr1", 0.5 M DoFs, one state).
Each case runs with Solver/Preconditioner reuse = true and = false,
interleaved, N times (median). Columns: wall time, the sums over the states
of active-set iterations, CG iterations and preconditioner builds, the
largest relative difference of K_secant and of the pin forces between the
two, and the timer's sections (assembly, preconditioner, linear solves,
active-set updates) from the console table.
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
EXE = os.path.join(ROOT, "build", "cycloid-contact")
WORK = "/tmp/cycloid-solver-reuse"
SECTIONS = {"assembly": "contact: constraints and assembly", "preconditioner": "contact: preconditioner",
            "solves": "contact: linear solves", "update": "contact: active-set update"}


def prm_text(case):
    if case == "qs-2d":
        return open(os.path.join(ROOT, "prm", "quasi-static-2d.prm")).read()
    if case == "transient-2d":
        text = open(os.path.join(ROOT, "prm", "transient-2d.prm")).read()
        return text + "subsection Transient\n  set End time = 3e-4\n  set Checkpoint interval = 0\nend\n"
    text = open(os.path.join(ROOT, "prm", "quasi-static-3d.prm")).read()
    text = re.sub(r"set Contact refinement side.*\n", "", text)
    return text + "subsection Mesh\n  set Contact refinements = 1\nend\n"


def run(case, reuse, k):
    out = os.path.join(WORK, "%s-%s-%d" % (case, "reuse" if reuse else "rebuild", k))
    os.makedirs(WORK, exist_ok=True)
    with open(out + ".prm", "w") as f:
        f.write(prm_text(case))
        f.write("set Output directory = %s\n" % out)
        f.write("subsection Solver\n  set Preconditioner reuse = %s\nend\n" % ("true" if reuse else "false"))
    log = run_cycloid(2, EXE, out + ".prm")
    if log.returncode != 0:
        sys.exit("%s failed:\n%s" % (out, log.stdout[-2000:] + log.stderr[-2000:]))
    rows = read_csv(os.path.join(out, "stiffness.csv"))
    pins = [float(p["Fn_N"]) for p in read_csv(os.path.join(out, "pin_forces.csv"))]
    result = {"wall_s": log.wall_s, "states": len(rows),
              "active_set_iterations": sum(int(r["active_set_iterations"]) for r in rows),
              "linear_iterations": sum(int(r["linear_iterations"]) for r in rows),
              "preconditioner_setups": sum(int(r["preconditioner_setups"]) for r in rows),
              "dofs": rows[-1]["dofs"], "K": [float(r["K_secant_Nm_per_rad"]) for r in rows], "pins": pins}
    for key, name in SECTIONS.items():
        m = re.search(re.escape(name) + r"\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s", log.stdout)
        result[key + "_s"] = float(m.group(1)) if m else float("nan")
    return result


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--3d", dest="three", action="store_true")
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--out", default=os.path.join(ROOT, "doc", "solver-reuse.csv"))
    args = ap.parse_args()
    cases = ["qs-2d", "transient-2d"] + (["qs-3d"] if args.three else [])
    load = os.getloadavg()[0]
    table = []
    for case in cases:
        runs = {True: [], False: []}
        for k in range(args.repeat):
            for reuse in (False, True):
                runs[reuse].append(run(case, reuse, k))
        for reuse in (False, True):
            r = dict(runs[reuse][-1])
            r["wall_s"] = statistics.median(x["wall_s"] for x in runs[reuse])
            a, b = runs[True][-1], runs[False][-1]
            r["K_secant_diff"] = max(abs(x / y - 1) for x, y in zip(a["K"], b["K"]))
            r["pin_force_diff"] = max(abs(x - y) for x, y in zip(a["pins"], b["pins"])) / max(b["pins"])
            r.update(case=case, reuse=str(reuse).lower(), load_at_start=load)
            table.append(r)
            print("%-13s reuse %-5s %7.1f s  sets %4d  CG %6d  builds %4d  assembly %.1f  precond %.1f  solves %.1f"
                  % (case, r["reuse"], r["wall_s"], r["active_set_iterations"], r["linear_iterations"],
                     r["preconditioner_setups"], r["assembly_s"], r["preconditioner_s"], r["solves_s"]),
                  flush=True)
    cols = ["case", "reuse", "dofs", "states", "wall_s", "active_set_iterations", "linear_iterations",
            "preconditioner_setups", "assembly_s", "preconditioner_s", "solves_s", "update_s",
            "K_secant_diff", "pin_force_diff", "load_at_start"]
    with open(args.out, "w") as f:
        w = csv.DictWriter(f, fieldnames=cols, extrasaction="ignore")
        w.writeheader()
        for r in table:
            w.writerow(r)
    print("wrote", args.out)


if __name__ == "__main__":
    main()
