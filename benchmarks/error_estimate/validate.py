#!/usr/bin/python3
"""The FE error estimate against the true error (doc/error-estimate.md).

Each case is solved with the estimate on at Contact refinements 2..4
(fewer are raised to 2; 3D: 2) and once, estimate off, on a finer
reference mesh (Contact refinements 5; 3D: 3); the true error of
a run is its distance from the reference: K_secant, K_tangent and every pin
force relative to the reference's largest. The ratio estimate / true error
says whether the estimate brackets the error (0.5..2) and whether it is on
the safe side (>= 1).

  /usr/bin/python3 benchmarks/error_estimate/validate.py [--3d] [--ranks 2]
  /usr/bin/python3 benchmarks/error_estimate/validate.py --ladder
  /usr/bin/python3 benchmarks/error_estimate/validate.py --bulk

Writes doc/error-estimate/validation.csv (--3d: validation-3d.csv). With
--ladder nothing is run: the estimator's formula is applied to the nested
3D mesh sequences of the scene ladder (doc/ladder/ladder.csv), whose errors
against the ladder's reference are known, and doc/error-estimate/ladder-3d.csv
is written. With --bulk the 2D cases are solved with Mesh/Bulk error
estimate = true and compared with Q2 at Contact refinements 3 (bulk.py's
run), whose bulk error is small: the reference of validate.py shares the
bulk mesh of the runs and cannot see the bulk's error
(doc/error-estimate/validation-bulk.csv).
"""
import argparse
import csv
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.path.join(ROOT, "build", "cycloid-contact")
WORK = "/tmp/cycloid-error-estimate"

# name -> (prm body, refinements estimated, reference refinements)
CASES_2D = {
    "2D slab, modified, 1000 N m": ("""
subsection Geometry
  set Pin circle radius modification = -0.01
  set Pin radius modification = 0.005
end
subsection Scene
  set Number of discs = 1
end
subsection Loading
  set Torque = 1000
end
""", [2, 3, 4], 5),
    "2D elastic pins, seed, 500 N m": ("""
subsection Scene
  set Number of discs = 1
end
subsection Loading
  set Torque = 500
end
""", [2, 3, 4], 5),
    "2D rigid pins, seed, 500 N m": ("""
subsection Scene
  set Number of discs = 1
  set Pins = rigid
end
subsection Loading
  set Torque = 500
end
""", [2, 3, 4], 5),
    "2D slab, modified, 4.5 deg, 300 N m": ("""
subsection Geometry
  set Pin circle radius modification = -0.01
  set Pin radius modification = 0.01
end
subsection Scene
  set Number of discs = 1
end
subsection Loading
  set Torque = 300
  set Crank angle = 4.5
end
""", [2, 3, 4], 5),
}

# A reducer of other proportions (zp 30, rrp 4 mm,
# e 1.5 mm, K1 0.6, b 12 mm; the issue-15 "other reducer"), modified
# profile, elastic pins, 300 N m. resolution.py holds it out of the fit of
# its constant; here it is one more case.
OTHER_2D = {
    "2D other reducer (zp 30), modified, 300 N m": ("""
subsection Geometry
  set Number of pins = 30
  set Pin radius = 4
  set Eccentricity = 1.5
  set Shortening coefficient = 0.6
  set Tooth width = 12
  set Pin circle radius modification = -0.01
  set Pin radius modification = 0.005
end
subsection Scene
  set Number of discs = 1
end
subsection Loading
  set Torque = 300
end
""", [2, 3, 4], 5),
}


def cases_2d():
    """Every 2D case: CASES_2D and OTHER_2D."""
    return {**CASES_2D, **OTHER_2D}


CASES_3D = {
    "3D one disc, c0.5 ax1, 500 N m": ("""
subsection Scene
  set Dimension = 3
  set Number of discs = 1
end
subsection Loading
  set Torque = 500
end
subsection Mesh
  set Contact element size = 0.5
  set Axial layers per disc = 1
  set Contact refinement side = loaded
end
""", [2], 3),
}


def run(name, body, cr, estimate, ranks):
    tag = "".join(c if c.isalnum() else "_" for c in name) + f"_cr{cr}" + ("" if estimate else "_ref")
    out = os.path.join(WORK, tag)
    prm = out + ".prm"
    os.makedirs(WORK, exist_ok=True)
    mesh = f"""
subsection Mesh
  set Contact refinements = {cr}
  set Error estimate = {'true' if estimate else 'false'}
  set Target accuracy = 0
end
"""
    with open(prm, "w") as f:
        f.write(f"set Run = quasi-static\nset Output directory = {out}\n" + body + mesh)
    if not os.path.exists(os.path.join(out, "stiffness.csv")):
        run_cycloid(ranks, EXE, prm, check=True)
    s = read_csv(os.path.join(out, "stiffness.csv"))[0]
    p = read_csv(os.path.join(out, "pin_forces.csv"))
    return s, {(r["disc"], r["pin"]): float(r["Fn_N"]) for r in p}


# The ladder's nested 3D sequences: three contact levels of one family.
LADDER_3D = [("3D two discs", ["c1 ax1 cr0", "c1 ax1 cr1", "c1 ax1 cr2"]),
             ("3D two discs", ["p25 ax1 cr1", "p25 ax1 cr2 loaded", "p25 ax1 cr3 loaded"])]
WEIGHT = 0.5  # results::previous_change_weight


def ladder():
    table = read_csv(os.path.join(ROOT, "doc", "ladder", "ladder.csv"))
    rows = []
    for scene, meshes in LADDER_3D:
        lv = [next(r for r in table if r["scene"] == scene and r["mesh"] == m) for m in meshes]
        for key, err, q in [("K_secant", "err_K_secant_pct", "K_secant"),
                            ("max_pin_force_N", "err_Fmax_pct", "F_max")]:
            q0, q1, q2 = (float(r[key]) for r in lv)
            est = 100 * max(abs(q2 - q1), WEIGHT * abs(q1 - q0)) / abs(q2)
            true = abs(float(lv[2][err]))
            rows.append({"scene": scene, "levels": " / ".join(meshes), "quantity": q,
                         "estimate_pct": est, "true_error_pct": true, "ratio": est / true})
            print(f"{scene} {meshes[-1]:20s} {q:9s} est {est:7.3f} %  true {true:7.3f} %  ratio {est / true:7.2f}")
    dest = os.path.join(ROOT, "doc", "error-estimate")
    os.makedirs(dest, exist_ok=True)
    with open(os.path.join(dest, "ladder-3d.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


def bulk_validation(ranks):
    """The estimate with the bulk mesh's part against Q2 (see above)."""
    import bulk  # noqa: E402 (imports this module)
    cases = cases_2d()
    rows = []
    for name, (body, levels, _) in cases.items():
        rs, rp = bulk.variant(name, body, "Q2, Contact refinements 3", ranks)
        fmax = max(rp.values())
        with_bulk = body + "subsection Mesh\n  set Bulk error estimate = true\nend\n"
        for cr in levels:
            s, p = run(name + " bulk", with_bulk, cr, True, ranks)
            true = {
                "K_secant": abs(float(s["K_secant_Nm_per_rad"]) / float(rs["K_secant_Nm_per_rad"]) - 1),
                "K_tangent": abs(float(s["K_tangent_Nm_per_rad"]) / float(rs["K_tangent_Nm_per_rad"]) - 1),
                "pin_forces": max(abs(p[k] - rp[k]) for k in rp) / fmax,
            }
            est = {"K_secant": float(s["K_secant_error"]), "K_tangent": float(s["K_tangent_error"]),
                   "pin_forces": float(s["max_pin_force_error"])}
            for q in true:
                rows.append({"case": name, "contact_refinements": cr, "dofs": s["dofs"], "quantity": q,
                             "estimate_pct": 100 * est[q], "bulk_part_max_pct": 100 * float(s["bulk_error"]),
                             "true_error_pct": 100 * true[q], "ratio": est[q] / true[q],
                             "mesh_warning": s["mesh_warning"], "wall_s": s["wall_s"]})
                r = rows[-1]
                print(f"{name:44s} cr{cr} {q:10s} est {r['estimate_pct']:7.3f} %  true {r['true_error_pct']:7.3f} %"
                      f"  ratio {r['ratio']:6.2f}", flush=True)
    with open(os.path.join(ROOT, "doc", "error-estimate", "validation-bulk.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    n = len(rows)
    print(f"{sum(0.5 <= r['ratio'] <= 2 for r in rows)}/{n} within a factor 2, "
          f"{sum(r['ratio'] >= 1 for r in rows)}/{n} on the safe side")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--3d", dest="three", action="store_true")
    ap.add_argument("--ladder", action="store_true")
    ap.add_argument("--bulk", action="store_true")
    ap.add_argument("--ranks", type=int, default=2)
    args = ap.parse_args()
    if args.ladder:
        return ladder()
    if args.bulk:
        return bulk_validation(args.ranks)
    cases = cases_2d()
    if args.three:
        cases.update(CASES_3D)
    rows = []
    for name, (body, levels, ref_cr) in cases.items():
        rs, rp = run(name, body, ref_cr, False, args.ranks)
        fmax = max(rp.values())
        for cr in levels:
            s, p = run(name, body, cr, True, args.ranks)
            true = {
                "K_secant": abs(float(s["K_secant_Nm_per_rad"]) / float(rs["K_secant_Nm_per_rad"]) - 1),
                "K_tangent": abs(float(s["K_tangent_Nm_per_rad"]) / float(rs["K_tangent_Nm_per_rad"]) - 1),
                "pin_forces": max(abs(p[k] - rp[k]) for k in rp) / fmax,
            }
            est = {"K_secant": float(s["K_secant_error"]), "K_tangent": float(s["K_tangent_error"]),
                   "pin_forces": float(s["max_pin_force_error"])}
            for q in true:
                rows.append({"case": name, "contact_refinements": cr, "dofs": s["dofs"],
                             "reference_dofs": rs["dofs"], "quantity": q,
                             "estimate_pct": 100 * est[q], "true_error_pct": 100 * true[q],
                             "ratio": est[q] / true[q] if true[q] > 0 else float("inf"),
                             "mesh_warning": s["mesh_warning"], "wall_s": s["wall_s"]})
                r = rows[-1]
                print(f"{name:38s} cr{cr} {q:10s} est {r['estimate_pct']:7.3f} %  true {r['true_error_pct']:7.3f} %  ratio {r['ratio']:6.2f}", flush=True)
    dest = os.path.join(ROOT, "doc", "error-estimate")
    os.makedirs(dest, exist_ok=True)
    name = "validation-3d.csv" if args.three else "validation.csv"
    with open(os.path.join(dest, name), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    n = len(rows)
    inside = sum(1 for r in rows if 0.5 <= r["ratio"] <= 2)
    safe = sum(1 for r in rows if r["ratio"] >= 1)
    print(f"{inside}/{n} within a factor 2, {safe}/{n} on the safe side (estimate >= error)")


if __name__ == "__main__":
    sys.exit(main())
