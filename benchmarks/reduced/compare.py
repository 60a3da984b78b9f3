#!/usr/bin/python3
"""Compare runs state by state against a reference run (doc/reduced-model.md,
"Against the finer 3D reference").

Usage: benchmarks/reduced/compare.py REFERENCE_DIR RUN_DIR [RUN_DIR ...]
           [--csv OUT --case NAME]

Each directory is a run's output (stiffness.csv, pin_forces.csv). States are
matched by their torque. Per state: K_secant, K_tangent and the largest pin
force relative to the reference, the largest pin-force difference relative
to the reference's largest pin force (the measure of the issues: every pin
force as a fraction of the largest), the engaged pins (above 1e-3 of the
largest force) of both, and, where the run has it, its contact-resolution
indicator (`resolution_error`) and its nodes across the Hertz width. With
--csv the rows are appended to OUT (written with a header if new).
"""
import argparse
import csv
import os


def states(directory):
    stiffness = list(csv.DictReader(open(os.path.join(directory, "stiffness.csv"))))
    pins = list(csv.DictReader(open(os.path.join(directory, "pin_forces.csv"))))
    out = {}
    for s in stiffness:
        forces = {(r["disc"], r["pin"]): float(r["Fn_N"]) for r in pins if r["step"] == s["step"]}
        out[float(s["torque_Nm"])] = (s, forces)
    return out


def compare(reference, run):
    rows = []
    for torque, (s, f) in sorted(reference.items()):
        if torque not in run:
            continue
        so, fo = run[torque]
        largest = max(f.values())
        worst = max(f, key=lambda k: abs(fo[k] - f[k]))
        rel = lambda c: float(so[c]) / float(s[c]) - 1
        engaged = lambda g: sum(1 for v in g.values() if v > 1e-3 * largest)
        res = so.get("resolution_error", "nan") or "nan"
        rows.append({
            "torque_Nm": torque,
            "K_secant_error": rel("K_secant_Nm_per_rad"),
            "K_tangent_error": rel("K_tangent_Nm_per_rad"),
            "max_pin_force_error": rel("max_pin_force_N"),
            "worst_pin_error": abs(fo[worst] - f[worst]) / largest,
            "worst_pin": "disc %s pin %s" % worst,
            "engaged_run": engaged(fo), "engaged_reference": engaged(f),
            "resolution_error": float(res), "hertz_nodes": float(so.get("hertz_nodes", "nan") or "nan"),
            "dofs": int(so["dofs"]), "reference_dofs": int(s["dofs"]),
        })
    return rows


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("reference")
    parser.add_argument("runs", nargs="+")
    parser.add_argument("--csv")
    parser.add_argument("--case", default="")
    args = parser.parse_args()
    reference = states(args.reference)
    table = []
    for run in args.runs:
        for row in compare(reference, states(run)):
            row = dict(case=args.case, run=os.path.basename(os.path.normpath(run)), **row)
            table.append(row)
            print("%s T=%g: K_secant %+.2f %%, K_tangent %+.2f %%, F_max %+.2f %%, worst pin %.2f %% of "
                  "the largest (%s), engaged %d/%d, resolution indicator %.2f %%, DoFs %d" % (
                      row["run"], row["torque_Nm"], 100 * row["K_secant_error"],
                      100 * row["K_tangent_error"], 100 * row["max_pin_force_error"],
                      100 * row["worst_pin_error"], row["worst_pin"], row["engaged_run"],
                      row["engaged_reference"], 100 * row["resolution_error"], row["dofs"]))
    if args.csv and table:
        new = not os.path.exists(args.csv)
        with open(args.csv, "a", newline="") as f:
            w = csv.DictWriter(f, fieldnames=list(table[0]))
            if new:
                w.writeheader()
            w.writerows(table)


if __name__ == "__main__":
    main()
