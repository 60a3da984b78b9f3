#!/usr/bin/python3
"""Where the first active set starts: `Contact/First active set = overlap`
(every flank node the analytical rotation closes) against `= hertz` (only
those within the Hertz half-width of the analytical pin force plus half a
node spacing), side by side on the same prm (issue #14: time of a 3D state).

Usage: benchmarks/first_set/run.py [--case NAME[,NAME]] [--repeat K]
           [--exe EXE] [--out DIR]

Cases (prm files of the repository, run as they are, no VTU output, 2 ranks):
  2d        tests/runs/first-active-set.prm: 2D, one disc, elastic pins,
            1000 N m, three contact refinements at the loaded pins
  3d-290k   benchmarks/ml_aggregation/two-discs-3d.prm: two discs, pins in
            the housing, 290 244 DoFs, 200 N m
  3d-seed   prm/quasi-static-3d.prm: the 3D seed case, 1.5 M DoFs, 1000 N m
            (not in the default list: about 10-17 minutes a pair)

The two starts alternate (overlap, hertz, overlap, ...), so neighbouring runs
compare on a shared machine. Each run is the one of the test
run.first-active-set.mpirun=2 (tests/check_first_set.py): CYCLOID_DEBUG=1,
the first set's size read from the debug output. Output: --out/first-set.csv
(doc/ first-set.csv), one row per case, start and repeat; rows of other cases
already in it are kept. Times are for the whole command.
"""
import os
import sys
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(os.path.dirname(HERE))
sys.path.insert(0, os.path.join(ROOT, "tests"))
import check_first_set  # noqa: E402
from checker import alternate  # noqa: E402

CASES = {
    "2d": "tests/runs/first-active-set.prm",
    "3d-290k": "benchmarks/ml_aggregation/two-discs-3d.prm",
    "3d-seed": "prm/quasi-static-3d.prm",
}
COLUMNS = ["case", "start", "repeat", "wall_s", "first_set", "active_nodes", "active_set_iterations",
           "linear_iterations", "preconditioner_setups", "dofs", "K_secant_Nm_per_rad",
           "K_tangent_Nm_per_rad", "max_pin_force_N", "peak_memory_MB", "load_before"]


def one(exe, case, start, repeat, work):
    text = open(os.path.join(ROOT, CASES[case])).read() + "\nset Write solution = false\n"
    load = os.getloadavg()[0]
    t0 = time.time()
    state, pins, first = check_first_set.run(exe, text, os.path.join(work, case, str(repeat)), start)
    wall = time.time() - t0
    row = {k: state[k] for k in COLUMNS if k in state}
    row.update(case=case, start=start, repeat=repeat, wall_s="%.1f" % wall, first_set=first,
               active_nodes=sum(int(p["active_nodes"]) for p in pins.values()),
               load_before="%.2f" % load)
    print("%-8s %-7s #%d: %7.1f s, first set %5d -> %5d nodes, %s active-set iterations, %s CG, K_secant %s"
          % (case, start, repeat, wall, first, row["active_nodes"], row["active_set_iterations"],
             row["linear_iterations"], row["K_secant_Nm_per_rad"]), flush=True)
    return row


def main():
    alternate(__doc__, "2d,3d-290k", ("overlap", "hertz"), one, "first-set.csv", COLUMNS,
              os.path.join("/tmp", "cycloid-first-set"))


if __name__ == "__main__":
    main()
