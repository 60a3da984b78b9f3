#!/usr/bin/python3
"""Loose CG solves while the active set changes: `Solver/Inner tolerance =
0` (every solve to Relative tolerance, 1e-10), `= 1e-6` (every loose solve
at 1e-6, the auto of 2026-12-04) and `= auto` (in 3D the first loose solve
of a state at 1e-4, each next one ten times tighter down to 1e-6, until the
set repeats or moves by at most 1 % of its nodes, then tight), side by side
on the same prm (issue #14 item 1 and the time of a 3D state).

Usage: benchmarks/inner_tolerance/run.py [--case NAME[,NAME]] [--repeat K]
           [--settings S[,S]] [--exe EXE] [--out DIR]

Cases (prm files of the repository, run as they are, no VTU output, 2 ranks):
  3d-test   tests/runs/quasi-static-3d-housing.prm: two discs, pins in the
            housing, coarse, two torques
  3d-290k   benchmarks/ml_aggregation/two-discs-3d.prm: two discs, pins in
            the housing, 290 244 DoFs, 200 N m
  3d-seed   prm/quasi-static-3d.prm: the 3D seed case, 1.5 M DoFs, 1000 N m
            (not in the default list: about 8 minutes for the three
            settings)

The settings alternate (0, 1e-6, auto, 0, ...; --settings chooses others,
any value the entry takes), so neighbouring runs compare on a shared
machine. Each run has CYCLOID_DEBUG=1; the tight and loose solves are
counted from its debug output. Output: --out/inner-tolerance.csv (doc/
inner-tolerance.csv), one row per case, setting and repeat; rows of other
cases already in it are kept. Times are for the whole command.
"""
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests"))
import check_inner_tolerance  # noqa: E402
from checker import alternate, rows  # noqa: E402

CASES = {
    "3d-test": "tests/runs/quasi-static-3d-housing.prm",
    "3d-290k": "benchmarks/ml_aggregation/two-discs-3d.prm",
    "3d-seed": "prm/quasi-static-3d.prm",
}
COLUMNS = ["case", "inner_tolerance", "repeat", "wall_s", "states", "loose_solves", "tight_solves",
           "active_set_iterations", "linear_iterations", "preconditioner_setups", "dofs",
           "K_secant_Nm_per_rad", "K_tangent_Nm_per_rad", "max_pin_force_N", "peak_memory_MB",
           "load_before"]
SUMMED = ("active_set_iterations", "linear_iterations", "preconditioner_setups")


def one(exe, case, setting, repeat, work):
    text = open(os.path.join(ROOT, CASES[case])).read() + "\nset Write solution = false\n"
    load = os.getloadavg()[0]
    t0 = time.time()
    out, log = check_inner_tolerance.run(exe, text, os.path.join(work, case, str(repeat)), setting,
                                         "subsection Solver\n  set Inner tolerance = %s\nend" % setting)
    wall = time.time() - t0
    states = rows(os.path.join(out, "stiffness.csv"))
    last = states[-1]
    tags = [t for t, *_ in check_inner_tolerance.solves(log)]
    row = {k: last[k] for k in COLUMNS if k in last}
    row.update({k: sum(int(s[k]) for s in states) for k in SUMMED})
    row.update(case=case, inner_tolerance=setting, repeat=repeat, wall_s="%.1f" % wall, states=len(states),
               loose_solves=tags.count("loose"), tight_solves=tags.count("tight"),
               load_before="%.2f" % load)
    print("%-8s %-5s #%d: %7.1f s, %d loose + %d tight solves, %s active-set iterations, %s CG, K_secant %s"
          % (case, setting, repeat, wall, row["loose_solves"], row["tight_solves"],
             row["active_set_iterations"], row["linear_iterations"], row["K_secant_Nm_per_rad"]), flush=True)
    return row


def main():
    alternate(__doc__, "3d-test,3d-290k", ("0", "1e-6", "auto"), one, "inner-tolerance.csv", COLUMNS,
              os.path.join("/tmp", "cycloid-inner-tolerance"))


if __name__ == "__main__":
    main()
