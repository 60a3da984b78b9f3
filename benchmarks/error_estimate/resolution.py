#!/usr/bin/python3
"""The contact-resolution indicator against the true error (doc/error-estimate.md §6).

A state without an estimate from nested levels (3D by default, transient
steps, Error estimate = false) is judged by its contact resolution: n, the
contact nodes across the Hertz width of its most loaded pin
(stiffness.csv hertz_nodes), and the indicator C / n^2 (resolution_error,
C = results::resolution_constant). This script measures the true pin-force
error against n on the cases of validate.py, solved with the estimate off
at Contact refinements 0..4 (3D: 1..2) against the same reference
(Contact refinements 5; 3D: 3), and adds the 3D two-disc ladder
(doc/ladder/ladder.csv), whose n follows from its mesh (contact element
size / 2^refinements) and its F_max (the Hertz half-width grows as
sqrt(F): scaled from the live 3D run's most loaded pin).

  /usr/bin/python3 benchmarks/error_estimate/resolution.py [--ranks 2] [--no-3d]

The indicator is computed here from n and CONSTANT (the program's
resolution_error column is the same figure; run.error-estimate checks
that), so that a change of the constant needs no new runs.

Writes doc/error-estimate/resolution.csv: per run n, the indicator, the true
error of the largest pin force (max |F - F_ref| over the pins, relative to
the reference's largest) and of K_secant and K_tangent, and C_needed =
true pin error x n^2, the constant that would just cover that run. The
constant is fitted on the 2D runs (their largest C_needed) and checked on
the 3D runs, which it was not fitted to. The runs
are cached in /tmp/cycloid-error-estimate (validate.py's folder).
"""
import argparse
import csv
import math
import os
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import validate  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv  # noqa: E402

ROOT = validate.ROOT
LEVELS_2D = [0, 1, 2, 3, 4]
# Held out of the fit (C is fitted on validate.CASES_2D): validate.OTHER_2D,
# a reducer of other proportions.
HELD_OUT_2D = validate.OTHER_2D
LEVELS_3D = [1, 2]
# The ladder's 3D two-disc meshes: name -> (contact element size [mm],
# contact refinements at the loaded pins).
LADDER = {"c1 ax1 cr0": (1.0, 0), "c1 ax1 cr1": (1.0, 1), "c1 ax1 cr2": (1.0, 2),
          "c0.5 ax1 cr2": (0.5, 2), "c0.5 ax1 cr3": (0.5, 3),
          "p25 ax1 cr1": (0.25, 1), "p25 ax1 cr2 loaded": (0.25, 2)}


def measured(name, body, levels, ref_cr, ranks):
    rs, rp = validate.run(name, body, ref_cr, False, ranks)
    fmax = max(rp.values())
    rows = []
    for cr in levels:
        s, p = validate.run(name, body, cr, False, ranks)
        n = float(s["hertz_nodes"])
        pin = max(abs(p[k] - rp[k]) for k in rp) / fmax
        rows.append({
            "case": name, "mesh": f"Contact refinements {cr}", "source": "run",
            "dofs": s["dofs"], "hertz_nodes": n,
            "indicator_pct": 100 * CONSTANT / n ** 2,
            "true_pin_error_pct": 100 * pin,
            "true_K_secant_error_pct": 100 * abs(float(s["K_secant_Nm_per_rad"]) / float(rs["K_secant_Nm_per_rad"]) - 1),
            "true_K_tangent_error_pct": 100 * abs(float(s["K_tangent_Nm_per_rad"]) / float(rs["K_tangent_Nm_per_rad"]) - 1),
            "C_needed": pin * n * n, "mesh_warning": s["mesh_warning"]})
    ref = {"hertz_nodes": float(rs["hertz_nodes"]), "fmax": fmax}
    return rows, ref


def hertz_width_scale(body, ref_cr, ranks):
    """(2a, F) of the most loaded pin of the live 3D reference run."""
    out = read_csv(os.path.join(
        validate.WORK, "".join(c if c.isalnum() else "_" for c in body) + f"_cr{ref_cr}_ref", "pin_forces.csv"))
    most = max(out, key=lambda r: float(r["Fn_N"]))
    return 2e-3 * float(most["hertz_halfwidth_um"]), float(most["Fn_N"])


def ladder(width, force):
    table = read_csv(os.path.join(ROOT, "doc", "ladder", "ladder.csv"))
    rows = []
    for mesh, (size, cr) in LADDER.items():
        r = next(x for x in table if x["scene"] == "3D two discs" and x["mesh"] == mesh)
        f = float(r["max_pin_force_N"])
        n = width * math.sqrt(f / force) / (size / 2 ** cr)
        pin = abs(float(r["err_Fmax_pct"])) / 100
        rows.append({
            "case": "3D two discs, seed, 1000 N m (ladder)", "mesh": mesh, "source": "ladder",
            "dofs": r["dofs"], "hertz_nodes": n, "indicator_pct": 100 * CONSTANT / n ** 2,
            "true_pin_error_pct": 100 * pin,
            "true_K_secant_error_pct": abs(float(r["err_K_secant_pct"])),
            "true_K_tangent_error_pct": abs(float(r["err_K_tangent_pct"])),
            "C_needed": pin * n * n, "mesh_warning": ""})
    return rows


CONSTANT = 0.25  # results::resolution_constant


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--no-3d", dest="three", action="store_false")
    args = ap.parse_args()
    rows = []
    for name, (body, _, ref_cr) in validate.CASES_2D.items():
        r, ref = measured(name, body, LEVELS_2D, ref_cr, args.ranks)
        rows += r
        print(f"{name}: reference n = {ref['hertz_nodes']:.2f}", flush=True)
    for name, (body, _, ref_cr) in HELD_OUT_2D.items():
        r, ref = measured(name, body, LEVELS_2D, ref_cr, args.ranks)
        for x in r:
            x["case"] = "held out: " + x["case"]
        rows += r
        print(f"{name}: reference n = {ref['hertz_nodes']:.2f}", flush=True)
    if args.three:
        for name, (body, _, ref_cr) in validate.CASES_3D.items():
            r, ref = measured(name, body, LEVELS_3D, ref_cr, args.ranks)
            rows += r
            print(f"{name}: reference n = {ref['hertz_nodes']:.2f}", flush=True)
            width, force = hertz_width_scale(name, ref_cr, args.ranks)
            rows += ladder(width, force)
    for r in rows:
        print(f"{r['case']:40s} {r['mesh']:24s} n {r['hertz_nodes']:6.2f}  indicator {r['indicator_pct']:7.2f} %"
              f"  true pin {r['true_pin_error_pct']:7.2f} %  K_sec {r['true_K_secant_error_pct']:6.2f} %"
              f"  K_tan {r['true_K_tangent_error_pct']:6.2f} %  C needed {r['C_needed']:.3f}")
    dest = os.path.join(ROOT, "doc", "error-estimate")
    with open(os.path.join(dest, "resolution.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    for label, part in (("2D (fitted)", [r for r in rows if r["case"].startswith("2D")]),
                        ("2D other reducer (checked)", [r for r in rows if r["case"].startswith("held out")]),
                        ("3D (checked)", [r for r in rows if r["case"].startswith("3D")])):
        if not part:
            continue
        covered = sum(1 for r in part if r["indicator_pct"] >= r["true_pin_error_pct"])
        over = [r["indicator_pct"] / r["true_pin_error_pct"] for r in part]
        print(f"{label}: indicator >= true pin error in {covered}/{len(part)} runs; C needed "
              f"{min(r['C_needed'] for r in part):.3f}..{max(r['C_needed'] for r in part):.3f} "
              f"(C = {CONSTANT}); indicator / error {min(over):.2f}..{max(over):.2f}")


if __name__ == "__main__":
    sys.exit(main())
