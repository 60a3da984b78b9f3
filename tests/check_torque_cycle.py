#!/usr/bin/python3
"""Checks of an FE catalogue torque cycle (Loading/Torque cycle = true).

Usage: check_torque_cycle.py FILE.prm DIR_1_RANK DIR_2_RANKS EXECUTABLE

* rigidity.csv equals the figures recomputed here from torsion_curve.csv
  (rigidity b/a between 50 and 100 % of the rated torque in both
  directions, lost motion between the +-3 % states, backlash = the spread
  of the rotations at zero torque);
* the zero-torque states carry no force and sit at the rigid take-up of
  their side, and the backlash is the clearance part of the lost motion;
* the elastic twist theta - takeup is mirror-symmetric at crank angle 0
  (to 0.1 %, the mesh is not exactly symmetric), the same on the loading
  and unloading branches (no friction, 1e-6), and grows from zero at the
  zero-torque limit to +-3 % and to the rated torque;
* at the rated torque, the FE peak contact pressure of every pin whose
  Hertz zone the refined mesh resolves (half-width >= 30 um) is within 5 %
  of Hertz's p0 at its force;
* the analytical model of the same scene has the same backlash (the same
  exact geometry) and a larger rigidity (it lacks the bodies' compliance).
"""
import os
import re
import sys
import tempfile
from pathlib import Path

from catalogue_figures import ARCMIN, catalogue
from checker import check, rows as read_csv, verdict

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402


def analytic_backlash_and_rigidity(prm, exe):
    """Run the same prm as Run = analytic; its rigidity.csv row."""
    with tempfile.TemporaryDirectory() as tmp:
        text = open(prm).read().replace("set Run = quasi-static", "set Run = analytic")
        text = re.sub(r"set Output directory *=.*", "set Output directory = analytic", text)
        path = os.path.join(tmp, "analytic.prm")
        open(path, "w").write(text)
        run_cycloid(None, exe, path, cwd=tmp, check=True)
        return read_csv(os.path.join(tmp, "analytic", "rigidity.csv"))[0]


def main(prm, dir1, dir2, exe):
    curve = read_csv(f"{dir2}/torsion_curve.csv")
    figures = read_csv(f"{dir2}/rigidity.csv")[0]
    pins = read_csv(f"{dir2}/pin_forces.csv")
    rated = float(figures["rated_torque_Nm"])
    points = [(float(c["torque_Nm"]), float(c["rotation_rad"])) for c in curve]
    rigidity, lost, backlash = catalogue(points, rated, check)
    print(f"rigidity {rigidity:.6g} N m/arcmin, lost motion {lost:.6g} arcmin, backlash {backlash:.6g} arcmin")
    for name, value in (("torsional_rigidity_Nm_per_arcmin", rigidity), ("lost_motion_arcmin", lost),
                        ("backlash_arcmin", backlash)):
        check(abs(float(figures[name]) - value) <= 1e-9 * abs(value), f"rigidity.csv {name} {figures[name]} vs {value}")
    check(abs(float(figures["lost_motion_clearance_arcmin"]) - backlash) <= 1e-9 * backlash,
          "the clearance part of the lost motion is not the backlash")

    by_step = {}
    for row in pins:
        by_step.setdefault(int(row["step"]), []).append(row)
    for i, c in enumerate(curve):
        T, theta = float(c["torque_Nm"]), float(c["rotation_rad"])
        if T == 0:
            check(all(float(r["Fn_N"]) == 0 for r in by_step[i]), f"state {i}: force at zero torque")
            check(theta == float(c["takeup_rad"]), f"state {i}: zero-torque rotation is not the take-up")
    # The elastic twist theta - takeup: mirror-symmetric at crank 0 (to
    # 1e-3, the mesh is not exactly symmetric), the same on the loading and
    # unloading branch (no friction), growing from the zero-torque limit.
    twist = [(float(c["torque_Nm"]), float(c["rotation_rad"]) - float(c["takeup_rad"])) for c in curve]
    for T, w in twist:
        mirror = [v for U, v in twist if U == -T]
        if T > 0 and mirror:
            check(abs(w + mirror[0]) <= 1e-3 * abs(w), f"T = {T}: twist {w} vs -twist(-T) {-mirror[0]}")
        same = [v for U, v in twist if U == T]
        check(all(abs(v - w) <= 1e-6 * abs(w) + 1e-15 for v in same), f"T = {T}: the branches differ: {same}")
    for sign in (1, -1):
        small = [sign * w for T, w in twist if T == sign * 0.03 * rated]
        large = [sign * w for T, w in twist if T == sign * rated]
        check(small and large and 0 < min(small) < min(large), f"side {sign}: the twist does not grow from the zero limit")

    # Peak pressures where the refined contact mesh resolves the zone: at
    # the rated torque, Hertz half-widths of 30 um or more (>= 5 nodes
    # across at this mesh's ~12 um contact spacing).
    worst, n = 0, 0
    for i, c in enumerate(curve):
        if abs(float(c["torque_Nm"])) != rated:
            continue
        for r in by_step[i]:
            if float(r["hertz_halfwidth_um"]) >= 30:
                fe, p0 = float(r["max_contact_pressure_MPa"]), float(r["hertz_pressure_MPa"])
                worst = max(worst, abs(fe - p0) / p0)
                n += 1
    print(f"largest FE peak pressure deviation from Hertz p0 over {n} resolved pins: {worst:.3g}")
    check(n >= 10, f"only {n} resolved pins to compare pressures at")
    check(worst <= 0.05, f"FE peak pressure {worst:.3g} off Hertz p0 (> 5 %)")

    a = analytic_backlash_and_rigidity(prm, exe)
    check(abs(float(a["backlash_arcmin"]) - backlash) <= 1e-9 * backlash, "backlash differs from the analytical model's")
    check(float(a["torsional_rigidity_Nm_per_arcmin"]) > rigidity, "the FE model is not softer than the analytical one")
    return verdict("all checks passed")


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
