#!/usr/bin/python3
"""Checks of a `Run = quasi-static` run on 1 and 2 MPI ranks.

Usage: check_quasi_static.py FILE.prm DIR_1_RANK DIR_2_RANKS EXECUTABLE
           [--stiffer DIR] [--close DIR TOL]

* torque balance: the reaction torque at the crank holes equals the target,
  and the sum of pin force x arm equals it (to round-off: 1e-8);
* the same K, rotation and engaged pins on 1 and 2 ranks (1e-6);
* monotonicity with torque: engaged pins and K_secant do not decrease;
* every FE state set up its preconditioner at least once and at most once
  per active-set iteration (preconditioner_setups);
* at the highest torque the FE model engages the same pins as the
  analytical model of the same scene (run here with Run = analytic);
* with --stiffer DIR (the same scene with rigid pins): that run is stiffer
  (smaller rotation, larger K_secant_elastic and K_tangent) at every torque;
* with --close DIR TOL (the same scene on another mesh or element degree):
  K_secant_elastic and K_tangent agree with that run's to TOL (relative)
  at every torque, and the same pins are engaged.
"""
import argparse
import os
import sys
import tempfile
from pathlib import Path

from checker import check, rows, verdict

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402


def main(prm, dir1, dir2, exe, stiffer=None, close=None):
    s1, s2 = rows(f"{dir1}/stiffness.csv"), rows(f"{dir2}/stiffness.csv")
    p2 = rows(f"{dir2}/pin_forces.csv")
    check(len(s1) == len(s2) and len(s1) > 1, "state counts")
    for a, b in zip(s1, s2):
        for key in ("rotation_rad", "K_tangent_Nm_per_rad", "K_secant_Nm_per_rad"):
            x, y = float(a[key]), float(b[key])
            check(abs(x - y) <= 1e-6 * abs(x), f"{key} differs on 1 and 2 ranks: {x} vs {y}")
        check(a["pins_in_contact"] == b["pins_in_contact"], "engaged pins differ on 1 and 2 ranks")
    previous_pins, previous_k = 0, 0.0
    for s in s2:
        t = float(s["torque_Nm"])
        check(abs(float(s["reaction_torque_Nm"]) - t) <= 1e-8 * t, f"reaction torque {s['reaction_torque_Nm']} != {t}")
        total = sum(float(r["Fn_N"]) * float(r["arm_mm"]) * 1e-3 for r in p2 if r["step"] == s["step"])
        check(abs(total - t) <= 1e-8 * t, f"sum F arm = {total} != {t}")
        setups = int(s["preconditioner_setups"])
        check(1 <= setups <= int(s["active_set_iterations"]),
              f"{setups} preconditioner set-ups for {s['active_set_iterations']} active-set iterations")
        check(int(s["pins_in_contact"]) >= previous_pins, "engaged pins decrease with torque")
        check(float(s["K_secant_Nm_per_rad"]) >= previous_k, "K_secant decreases with torque")
        previous_pins, previous_k = int(s["pins_in_contact"]), float(s["K_secant_Nm_per_rad"])
        print(f"T {t:g} N m: beta {float(s['rotation_rad']):.6e} rad, K_secant {float(s['K_secant_Nm_per_rad']):.4e}, "
              f"K_tangent {float(s['K_tangent_Nm_per_rad']):.4e} N m/rad, pins {s['pins_in_contact']}, "
              f"active-set iterations {s['active_set_iterations']}")

    # The analytical model of the same scene.
    with tempfile.TemporaryDirectory() as tmp:
        text = open(prm).read().replace("set Run = quasi-static", "set Run = analytic")
        text = text.replace("set Output directory", f"set Output directory = {tmp}/a\n# ")
        with open(f"{tmp}/a.prm", "w") as f:
            f.write(text)
        run_cycloid(None, exe, f"{tmp}/a.prm", check=True)
        pa = rows(f"{tmp}/a/pin_forces.csv")
    last = s2[-1]["step"]
    fe = sorted(int(r["pin"]) for r in p2 if r["step"] == last and float(r["Fn_N"]) > 0)
    an = sorted(int(r["pin"]) for r in pa if r["step"] == last and float(r["Fn_N"]) > 0)
    print("engaged pins at the highest torque: FE", fe, "analytic", an)
    check(fe == an, "FE and analytical models engage different pins at the highest torque")
    if stiffer:
        for a, b in zip(rows(f"{stiffer}/stiffness.csv"), s2):
            print(f"T {b['torque_Nm']} N m: K_tangent rigid pins {float(a['K_tangent_Nm_per_rad']):.4e}, "
                  f"this run {float(b['K_tangent_Nm_per_rad']):.4e}")
            check(float(a["rotation_rad"]) < float(b["rotation_rad"]), "rigid pins do not turn less")
            check(float(a["K_tangent_Nm_per_rad"]) > float(b["K_tangent_Nm_per_rad"]), "rigid pins not stiffer (tangent)")
            check(float(a["K_secant_elastic_Nm_per_rad"]) > float(b["K_secant_elastic_Nm_per_rad"]), "rigid pins not stiffer (secant)")
    if close:
        other, tol = close[0], float(close[1])
        po = rows(f"{other}/pin_forces.csv")
        for a, b in zip(rows(f"{other}/stiffness.csv"), s2):
            for key in ("K_secant_elastic_Nm_per_rad", "K_tangent_Nm_per_rad"):
                x, y = float(a[key]), float(b[key])
                print(f"T {b['torque_Nm']} N m: {key} {y:.5e} (dofs {b['dofs']}) vs {x:.5e} (dofs {a['dofs']}): {y / x - 1:+.2e}")
                check(abs(y - x) <= tol * abs(x), f"{key} {y} not within {tol} of {x}")
            engaged = lambda rs, st: sorted((r["disc"], r["pin"]) for r in rs if r["step"] == st and float(r["Fn_N"]) > 0)
            check(engaged(po, a["step"]) == engaged(p2, b["step"]), f"engaged pins differ from {other} at T {b['torque_Nm']}")
    return verdict("all checks passed")


if __name__ == "__main__":
    parser = argparse.ArgumentParser()
    parser.add_argument("prm")
    parser.add_argument("dir1")
    parser.add_argument("dir2")
    parser.add_argument("exe")
    parser.add_argument("--stiffer")
    parser.add_argument("--close", nargs=2, metavar=("DIR", "TOL"))
    a = parser.parse_args()
    sys.exit(main(a.prm, a.dir1, a.dir2, a.exe, a.stiffer, a.close))
