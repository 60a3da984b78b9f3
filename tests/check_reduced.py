#!/usr/bin/python3
"""The reduced model against the full FE model, across ranks and load
widths.

Usage: check_reduced.py FILE.prm EXECUTABLE WORKDIR [--3d]

FILE.prm is a `Run = reduced` case (its output directory named like the
file). The script runs
* the case on 1 and 2 ranks: beta, K and every pin force agree to 1e-8
  (relative; the same coarse model, a direct solver);
* (2D) the case with `Reduced/Load half-width` 0.125, 0.25 (the default
  at Contact refinements 2) and 0.5 mm (0.125 with Contact refinements 3):
  K_secant within 0.3 %, K_tangent and the pin forces within 0.5 % (of the
  largest). The near-field law turns the coarse model's response to width w
  into the response to the Hertz width; if it were left out (or counted
  twice), doubling w moves K_secant by 0.9-1.7 % and K_tangent by 2-8 %
  (measured with the law built as 0), so the check fails then;
* (2D) a sweep of 5 crank angles over one mesh period with the compliance
  interpolated from 3 anchor angles (`Reduced/Anchor angles`, the default)
  against condensing at every angle (0): K and pin forces within 1e-3
  (measured 1e-4 on 19 phases);
* the full FE model of the same scene (`Run = quasi-static`) on 2 ranks,
  the same engaged pins and
  - 2D: Contact refinements 4 within 0.3 mm (cr3 and cr4 agree to 0.02 %
    in K_secant and 0.4 % in K_tangent and pin forces at crank angle 0;
    at 4.5 deg and 300 N m cr3 still misses the sixth pin and is 8 % low in
    K_tangent): K_secant within 1 %, K_tangent within 1.5 % (issue #13's
    1 % plus the FE's own 0.4 %), every pin force within 2 % of the
    largest;
  - 3D (--3d): one axial layer, Contact refinements 2 at the loaded pins
    within 0.3 mm, the cheapest 3D FE mesh within 0.3 % of the seed case's
    3D reference in K_secant but +1.5 % in K_tangent and +5 % in the
    largest pin force (doc/scene-guide.md): K_secant within 1 %, K_tangent
    within 2.5 %, pin forces within 5 % of the largest.
* the reduced model's own error estimate (`Reduced/Error estimate`, on by
  default): every state has K_secant_error, K_tangent_error and
  max_pin_force_error, positive and not the same in every state, the same
  on 1 and 2 ranks (1e-6), and each loaded pin its Fn_error_N; with
  `Error estimate = false` every other column is the same string and the
  estimates are empty. 2D: against the FE model, each state's difference
  in K_secant is within the reduced model's estimate alone, and in
  K_tangent and every pin force within the two estimates together (the FE
  reference is not exact: its own estimate is 0.2-1.9 %). The K_secant
  check fails if the near-field law's part of the estimate (5 (a/R)^2) is
  left out: the companion's part alone is 0.03-0.07 % where the FE differs
  by 0.06-0.24 %.
"""
import argparse
import math
import os
import sys
from pathlib import Path

OUTPUT = ""

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402


def run(exe, prm_text, work, name, ranks):
    out = os.path.join(work, name)
    prm = out + ".prm"
    with open(prm, "w") as f:
        f.write(prm_text.replace("set Output directory = " + OUTPUT,
                                 "set Output directory = " + out))
    if run_cycloid(ranks, exe, prm, log=out + ".log").returncode != 0:
        sys.exit("%s failed, see %s.log" % (name, out))
    return rows(os.path.join(out, "stiffness.csv")), rows(os.path.join(out, "pin_forces.csv"))


def forces(pins, step):
    return {(p["disc"], p["pin"]): float(p["Fn_N"]) for p in pins if p["step"] == step}


def compare(name, a, b, k_sec, k_tan, force_tol, same_pins=True):
    worst = {"K_secant": 0, "K_tangent": 0, "force": 0}
    for sa, sb in zip(a[0], b[0]):
        step = sa["step"]
        for key, tol, label in [("K_secant_Nm_per_rad", k_sec, "K_secant"),
                                ("K_tangent_Nm_per_rad", k_tan, "K_tangent")]:
            e = abs(float(sa[key]) / float(sb[key]) - 1)
            worst[label] = max(worst[label], e)
            check(e <= tol, "%s: %s of state %s off by %.3g (tolerance %g)"
                  % (name, label, step, e, tol))
        fa, fb = forces(a[1], step), forces(b[1], step)
        fmax = max(fb.values())
        dev = max(abs(fa.get(k, 0) - fb.get(k, 0)) for k in set(fa) | set(fb)) / fmax
        worst["force"] = max(worst["force"], dev)
        check(dev <= force_tol, "%s: a pin force of state %s off by %.3g of the "
              "largest (tolerance %g)" % (name, step, dev, force_tol))
        if same_pins:
            ea = sorted(k for k, v in fa.items() if v > 0)
            eb = sorted(k for k, v in fb.items() if v > 0)
            check(ea == eb, "%s: engaged pins of state %s differ: %s vs %s"
                  % (name, step, ea, eb))
    check(len(a[0]) == len(b[0]) and len(a[0]) > 0, "%s: state counts differ" % name)
    print("%-34s K_secant %.2e  K_tangent %.2e  pin force %.2e" % (
        name, worst["K_secant"], worst["K_tangent"], worst["force"]))


ESTIMATES = ["K_secant_error", "K_tangent_error", "max_pin_force_error"]


def number(text):
    return float(text) if text not in ("", None) else math.nan


def check_estimates(name, a, other=None):
    """The estimate of run @p a is there in every state, positive and not
    the same everywhere; with @p other (the same run on other ranks) equal
    to 1e-6."""
    values = []
    for k, sa in enumerate(a[0]):
        e = [number(sa[q]) for q in ESTIMATES]
        values.append(e)
        check(all(x > 0 for x in e), "%s: state %s has no estimate: %s" % (name, sa["step"], e))
        for p in a[1]:
            if p["step"] == sa["step"] and float(p["Fn_N"]) > 0:
                check(number(p["Fn_error_N"]) > 0, "%s: pin %s of state %s has no Fn_error_N"
                      % (name, p["pin"], sa["step"]))
        if other is not None:
            for q, x in zip(ESTIMATES, e):
                y = number(other[0][k][q])
                check(abs(x - y) <= 1e-6 * abs(y), "%s: %s of state %s differs: %g vs %g"
                      % (name, q, sa["step"], x, y))
    check(len(values) < 2 or any(v != values[0] for v in values[1:]),
          "%s: the same estimate in every state: %s" % (name, values))


def check_off_switch(a, b):
    """Run @p b (Error estimate = false) against @p a: every column but
    the estimates, the warning flag and the costs the same string; no
    estimates."""
    skip = set(ESTIMATES) | {"mesh_warning", "wall_s", "peak_memory_MB", "Fn_error_N"}
    for ra, rb in zip(a[0] + a[1], b[0] + b[1]):
        for key in ra:
            if key not in skip:
                check(ra[key] == rb[key], "Error estimate = false changed %s: %s vs %s"
                      % (key, ra[key], rb[key]))
    for rb in b[0]:
        check(all(math.isnan(number(rb[q])) for q in ESTIMATES),
              "Error estimate = false still has an estimate in state %s" % rb["step"])


def check_coverage(red, fe):
    """Per state: |K_secant difference| <= the reduced estimate; K_tangent
    and every pin force within the reduced and the FE estimates together."""
    for sa, sb in zip(red[0], fe[0]):
        for key, q, alone in [("K_secant_Nm_per_rad", "K_secant_error", True),
                              ("K_tangent_Nm_per_rad", "K_tangent_error", False)]:
            d = abs(float(sa[key]) / float(sb[key]) - 1)
            band = number(sa[q]) + (0 if alone else number(sb[q]))
            check(d <= band, "state %s: %s differs from the FE by %.3g, outside %s %.3g"
                  % (sa["step"], key, d, "the estimate" if alone else "the two estimates", band))
        fa, fb = forces(red[1], sa["step"]), forces(fe[1], sb["step"])
        d = max(abs(fa.get(k, 0) - fb.get(k, 0)) for k in set(fa) | set(fb)) / max(fb.values())
        band = number(sa["max_pin_force_error"]) + number(sb["max_pin_force_error"])
        check(d <= band, "state %s: a pin force differs from the FE by %.3g of the largest, "
              "outside the two estimates %.3g" % (sa["step"], d, band))
        print("state %s: K_secant %.3f %% (estimate %.3f %%), pins %.3f %% (estimates %.3f %%)"
              % (sa["step"], 100 * abs(float(sa["K_secant_Nm_per_rad"]) /
                                       float(sb["K_secant_Nm_per_rad"]) - 1),
                 100 * number(sa["K_secant_error"]), 100 * d, 100 * band))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("prm")
    ap.add_argument("exe")
    ap.add_argument("work")
    ap.add_argument("--3d", dest="three_d", action="store_true")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    text = open(args.prm).read()
    global OUTPUT
    OUTPUT = os.path.splitext(os.path.basename(args.prm))[0]

    base = run(args.exe, text, args.work, "reduced-np2", 2)
    one = run(args.exe, text, args.work, "reduced-np1", 1)
    compare("1 vs 2 ranks", one, base, 1e-8, 1e-8, 1e-8)
    check_estimates("reduced", base, one)
    if not args.three_d:
        check_off_switch(base, run(args.exe, text + "subsection Reduced\n"
                                   "  set Error estimate = false\nend\n",
                                   args.work, "reduced-no-estimate", 2))

    for w, cr in ([] if args.three_d else [("0.125", 3), ("0.5", 2)]):
        variant = text + ("subsection Reduced\n  set Load half-width = %s\n"
                          "  set Contact refinements = %d\nend\n" % (w, cr))
        compare("load half-width %s vs 0.25 mm" % w,
                run(args.exe, variant, args.work, "reduced-w" + w, 2), base,
                3e-3, 5e-3, 5e-3)

    if not args.three_d:
        sweep = text.replace("  set Crank angle = 4.5", "  set Crank angle = 0\n  set Number of phases = 5")
        every = sweep + "subsection Reduced\n  set Anchor angles = 0\nend\n"
        compare("3 anchor angles vs every angle",
                run(args.exe, sweep, args.work, "sweep-anchors", 2),
                run(args.exe, every, args.work, "sweep-every", 2), 1e-3, 1e-3, 1e-3)

    fe = text.replace("set Run              = reduced",
                      "set Run = quasi-static\nset Write solution = false")
    if args.three_d:
        fe += ("subsection Mesh\n  set Axial layers per disc = 1\n"
               "  set Contact refinements = 2\n  set Contact refinement radius = 0.3\n"
               "  set Contact refinement side = loaded\n"
               "  set Error estimate = false\nend\n")  # (the reference only)
        tolerances = (1e-2, 2.5e-2, 5e-2)
    else:
        fe += ("subsection Mesh\n  set Contact refinements = 4\n"
               "  set Contact refinement radius = 0.3\n"
               "  set Target accuracy = 0\nend\n")  # (the mesh asked for)
        tolerances = (1e-2, 1.5e-2, 2e-2)
    reference = run(args.exe, fe, args.work, "fe", 2)
    compare("reduced vs full FE", base, reference, *tolerances)
    if not args.three_d:
        check_coverage(base, reference)
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
