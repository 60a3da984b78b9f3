#!/usr/bin/python3
"""What the estimate leaves out: the error of the bulk mesh (doc/error-estimate.md §5).

The estimate compares contact levels, which refine the cells at the
contacts only. The bulk mesh (Flank, Pin and Coarse element size, Q1) is
the same on every level, so its error is in none of the differences, nor
in validate.py's reference (Contact refinements 5 on the same bulk mesh).
This script measures it on validate.py's 2D cases: the reference
(Q1, Contact refinements 5) against
  * Q1 with one global refinement and Contact refinements 4: the same
    contact node spacing, every bulk cell halved;
  * Q2 with Contact refinements 3: every cell of higher order.
Each difference is relative: K_secant and K_tangent to the reference's,
the pin forces as the largest |F - F_ref| over the pins relative to the
reference's largest (the measure of validate.py).

  /usr/bin/python3 benchmarks/error_estimate/bulk.py [--ranks 2]

Runs are cached in validate.py's folder (/tmp/cycloid-error-estimate).
Writes doc/error-estimate/bulk.csv.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import validate  # noqa: E402

ROOT = validate.ROOT
# name -> (Contact refinements, Mesh entries added to the case's body)
VARIANTS = {"Q1, global refinement 1, Contact refinements 4": (4, "  set Global refinements = 1\n"),
            "Q2, Contact refinements 3": (3, "  set Polynomial degree = 2\n")}


def variant(name, body, label, ranks):
    cr, extra = VARIANTS[label]
    tag = "bulk_" + "".join(c if c.isalnum() else "_" for c in label)
    # validate.run writes its own Mesh subsection; a second one adds to it.
    s, p = validate.run(name + " " + tag, body + "subsection Mesh\n" + extra + "end\n", cr, False, ranks)
    return s, p


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ranks", type=int, default=2)
    args = ap.parse_args()
    cases = validate.cases_2d()
    rows = []
    for name, (body, _, ref_cr) in cases.items():
        rs, rp = validate.run(name, body, ref_cr, False, args.ranks)
        fmax = max(rp.values())
        for label in VARIANTS:
            s, p = variant(name, body, label, args.ranks)
            row = {"case": name, "variant": label, "dofs": s["dofs"], "reference_dofs": rs["dofs"]}
            for q in ["K_secant", "K_tangent"]:
                key = f"{q}_Nm_per_rad"
                row[f"{q}_change_pct"] = 100 * (float(s[key]) / float(rs[key]) - 1)
            row["pin_forces_change_pct"] = 100 * max(abs(p[k] - rp[k]) for k in rp) / fmax
            row["wall_s"] = s["wall_s"]
            rows.append(row)
            print(f"{name:44s} {label:46s} K_secant {row['K_secant_change_pct']:+7.3f} %"
                  f"  K_tangent {row['K_tangent_change_pct']:+7.3f} %  pins {row['pin_forces_change_pct']:6.3f} %",
                  flush=True)
    with open(os.path.join(ROOT, "doc", "error-estimate", "bulk.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    sys.exit(main())
