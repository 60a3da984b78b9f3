#!/usr/bin/python3
"""Compare finished runs state by state with a reference run, by the measures
of validate.py (doc/reduced-model.md, "Against the finer 3D reference").

Usage: benchmarks/reduced/compare.py REFERENCE_DIR RUN_DIR [RUN_DIR ...]
           [--csv OUT --case NAME]

Each directory is a run's output (stiffness.csv, pin_forces.csv); states are
matched by their torque (validate.compare). Per state: K_secant and
K_tangent relative to the reference, the largest pin-force difference over
the reference's largest pin force (`max_pin_force_error`), F_max relative to
the reference's, the engaged pins of both and the run's contact-resolution
indicator. The column names are validate.py's: `*_reduced` is the run,
`*_fe` the reference. With --csv the rows are appended to OUT (a header if
new).
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from validate import compare, read  # noqa: E402

KEYS = ['case', 'run', 'torque_Nm', 'K_secant_error', 'K_tangent_error', 'F_max_error',
        'max_pin_force_error', 'same_engaged_pins', 'engaged_reduced', 'engaged_fe',
        'resolution_error', 'hertz_nodes', 'reduced_dofs', 'fe_dofs']


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("reference")
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--csv")
    parser.add_argument("--case", default="")
    args = parser.parse_args()
    reference = read(args.reference)
    table = []
    for run in args.runs:
        for r in compare(read(run), reference):
            r.update(case=args.case, run=os.path.basename(os.path.normpath(run)))
            table.append({k: r[k] for k in KEYS})
            print("%s T=%s: K_secant %+.2f %%, K_tangent %+.2f %%, F_max %+.2f %%, every pin within "
                  "%.2f %% of the largest, engaged %d/%d, resolution indicator %.2f %%" % (
                      r["run"], r["torque_Nm"], 100 * r["K_secant_error"], 100 * r["K_tangent_error"],
                      100 * r["F_max_error"], 100 * r["max_pin_force_error"], r["engaged_reduced"],
                      r["engaged_fe"], 100 * r["resolution_error"]))
    if args.csv and table:
        new = not os.path.exists(args.csv)
        with open(args.csv, "a", newline="") as f:
            w = csv.DictWriter(f, fieldnames=KEYS)
            if new:
                w.writeheader()
            w.writerows(table)


if __name__ == "__main__":
    main()
