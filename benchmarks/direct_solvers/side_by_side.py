#!/usr/bin/python3
"""The factorisations behind elasticity::DirectSolver side by side
(issue #49 item 3; doc/solver-reuse.md, "One direct-solver interface").

Every case runs with each factorisation (`Solver/Direct solver`), one after
the other on an idle machine, 2 ranks, the whole command timed from outside:

  3d-reduced    prm/seed-case.prm: the reduced model of the 3D seed stage
                (417 k coarse DoFs, 84 load cases, 3 torques)
  2d-reduced    the reduced model, 2D, one disc, pins on their axes,
                1000 N m (59 k coarse DoFs)
  2d-transient  prm/transient-2d.prm cut to 20 steps (139 k DoFs), every
                active set factorised (Contact Schur complement = false)
  3d-fe-cr2     the full 3D FE state the reduced model is judged against
                (p25 ax1 cr2 loaded, 1000 N m, default solver): the ratio
                of issue #49's target

Per run: wall time of the whole command, the time of the stage the
factorisation serves (the reduced model's "reduced: solves", the transient
run's "time step" total, the FE state's whole run), peak memory summed over
the ranks (the first state's peak_memory_MB), the console's factorisation
line and K_secant of the last state (the factorisations must agree to
rounding). --from-logs rebuilds the table from the logs of --work (and the
wall times the runs left beside them) without running.

    /usr/bin/python3 benchmarks/direct_solvers/side_by_side.py \
        [--exe build/cycloid-contact] [--out doc] [--cases 3d-reduced,...]
        [--kinds mumps,auto] [--work DIR] [--from-logs]

Output: direct-solvers.csv in --out.
"""
import argparse
import csv
import os
import re
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[2]
sys.path.insert(0, str(ROOT / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

SOLVER = "subsection Solver\n  set Direct solver = %s\nend\n"
REDUCED_2D = ("set Run = reduced\nsubsection Scene\n  set Dimension = 2\n"
              "  set Pins = elastic\n  set Pin support = axis\nend\n"
              "subsection Loading\n  set Torque = 1000\n  set Crank angle = 0\nend\n")
TRANSIENT_CUT = ("subsection Transient\n  set End time = 2e-4\n"
                 "  set Output interval = 0\n  set Checkpoint interval = 0\nend\n"
                 "subsection Solver\n  set Contact Schur complement = false\nend\n")
FE_CR2 = ("set Run = quasi-static\nsubsection Scene\n  set Dimension = 3\n"
          "  set Number of discs = 2\n  set Pins = elastic\n"
          "  set Pin support = housing\nend\n"
          "subsection Loading\n  set Torque = 1000\n  set Crank angle = 0\nend\n"
          "subsection Mesh\n  set Axial layers per disc = 1\n"
          "  set Contact refinements = 2\n  set Contact refinement radius = 0.3\n"
          "  set Contact refinement side = loaded\n"
          "  set Triangulation = distributed\nend\n")

CASES = [
    ("3d-reduced", (ROOT / "prm/seed-case.prm").read_text(),
     ["mumps", "cholmod-supernodal", "mumps-unsymmetric"]),
    ("2d-reduced", REDUCED_2D,
     ["cholmod", "cholmod-supernodal", "mumps", "mumps-unsymmetric", "klu"]),
    ("2d-transient", (ROOT / "prm/transient-2d.prm").read_text() + TRANSIENT_CUT,
     ["cholmod", "cholmod-supernodal", "mumps", "klu"]),
    ("3d-fe-cr2", FE_CR2, ["auto"]),
]


def factorisation_line(log):
    """The console's line on the factorisation (reduced runs), or ''."""
    for line in log.splitlines():
        if re.search(r"^\s+(MUMPS|CHOLMOD)", line):
            return line.strip()
    return ""


def stage_seconds(case, log):
    """The time of the stage the factorisation serves, from the log [s]."""
    if case.endswith("reduced"):
        m = re.search(r"reduced: solves ([0-9.e+-]+) s", log)
    elif case.endswith("transient"):
        m = re.search(r"\| time step\s+\|\s+\d+ \|\s+([0-9.e+-]+)s", log)
    else:
        m = re.search(r"\| Total wallclock time elapsed since start\s+\|\s+([0-9.e+-]+)s", log)
    return float(m.group(1)) if m else float("nan")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default="build/cycloid-contact")
    ap.add_argument("--out", default="doc")
    ap.add_argument("--work", default="/tmp/direct-solvers")
    ap.add_argument("--cases", default=None)
    ap.add_argument("--kinds", default=None,
                    help="only these factorisations (comma-separated)")
    ap.add_argument("--from-logs", action="store_true")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rows = []
    for case, text, kinds in CASES:
        if args.cases and case not in args.cases.split(","):
            continue
        for kind in kinds:
            if args.kinds and kind not in args.kinds.split(","):
                continue
            out = os.path.join(args.work, "%s-%s" % (case, kind))
            prm = out + ".prm"
            load, wall = "", float("nan")
            if not args.from_logs:
                with open(prm, "w") as f:
                    f.write(text + (SOLVER % kind if kind != "auto" else "") +
                            "set Output directory = %s\nset Write solution = false\n" % out)
                load = "%.2f" % os.getloadavg()[0]
                wall = run_cycloid(2, os.path.abspath(args.exe), prm, log=out + ".log",
                                   check=True).wall_s
                Path(out + ".wall").write_text("%.2f %s\n" % (wall, load))
            elif os.path.exists(out + ".wall"):
                wall, load = Path(out + ".wall").read_text().split()
                wall = float(wall)
            log = Path(out + ".log").read_text()
            states = read_csv(os.path.join(out, "stiffness.csv"))
            row = dict(case=case, direct_solver=kind, dofs=states[0]["dofs"],
                       wall_s="%.2f" % wall if wall == wall else "",
                       stage_s="%.2f" % stage_seconds(case, log),
                       peak_memory_MB="%.0f" % float(states[0]["peak_memory_MB"]),
                       K_secant_last=states[-1].get("K_secant_Nm_per_rad", ""),
                       factorisation=factorisation_line(log),
                       load_avg_at_start=load)
            rows.append(row)
            print(row, flush=True)
    with open(os.path.join(args.out, "direct-solvers.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
