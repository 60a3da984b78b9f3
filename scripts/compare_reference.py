#!/usr/bin/python3
"""Print how far a run's states are from the full FE model's reference.

Usage: compare_reference.py OUTPUT_DIR REFERENCE.csv

REFERENCE.csv (e.g. doc/reduced/seed-reference.csv) has the columns
crank_deg, torque_Nm, K_secant_Nm_per_rad, K_tangent_Nm_per_rad,
max_pin_force_N and source (which FE run gave them). Every state of
OUTPUT_DIR/stiffness.csv at a reference's crank angle and torque gets one
line with its relative differences; states without a reference are named.
"""
import os
import sys

from cycloid_tools import read_csv


def main():
    if len(sys.argv) != 3:
        sys.exit(__doc__)
    out, ref_path = sys.argv[1], sys.argv[2]
    states = read_csv(os.path.join(out, "stiffness.csv"))
    refs = read_csv(ref_path)
    print("Distance from the full FE model (%s):" % os.path.relpath(ref_path))
    for s in states:
        match = [r for r in refs
                 if abs(float(r["crank_deg"]) - float(s["crank_deg"])) < 1e-9
                 and abs(float(r["torque_Nm"]) - float(s["torque_Nm"])) < 1e-9]
        if not match:
            print("  %8s N m: no FE reference at this state" % s["torque_Nm"])
            continue
        r = match[0]
        parts = []
        for key, label in [("K_secant_Nm_per_rad", "K_secant"),
                           ("K_tangent_Nm_per_rad", "K_tangent"),
                           ("max_pin_force_N", "largest pin force")]:
            parts.append("%s %+.2f %%" % (label, 100 * (float(s[key]) / float(r[key]) - 1)))
        print("  %8s N m: %s  (FE: %s)" % (s["torque_Nm"], ", ".join(parts), r["source"]))


if __name__ == "__main__":
    main()
