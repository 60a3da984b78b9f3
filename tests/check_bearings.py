#!/usr/bin/python3
"""Crank bearings in the analytic and reduced models (issue #52), checked
from the written files alone.

Usage: check_bearings.py RUN.prm EXECUTABLE WORKDIR

RUN.prm is a `Run = analytic` file with `Crank bearings/Model = needle`.
It is run as given, with a 5 um radial clearance, with the reduced model
(2D, one disc) and on rigid supports. Checks, per state:
- each disc in equilibrium: its pins' forces (pin_forces.csv) plus its
  bearings' (bearing_forces.csv) sum to zero, and so do their moments
  about the disc centre (the crank holes placed from the parameters);
- the bearings' moments sum to the output torque;
- each bearing's deflection against Palmgren's law at its largest roller
  load: the roller on the line of the deflection is compressed by
  delta_r - c; the largest-loaded one, at most half a pitch off it, by
  between (delta_r cos(pi/Z) - c) and (delta_r - c);
- with no clearance, the largest roller load against Stribeck's share
  Q_max = 4.08 F / Z, within the spread of Z discrete rollers (+-15 %);
- compliance_breakdown.csv: the parts sum to the total, and the bearings'
  part is the twist the bearings add to the rigid stage (beta on bearings
  minus beta on rigid supports) within 5 % (the rest: the pins' load
  shifts when the discs move);
- a clearance adds lost motion: the take-up grows by 0.5 to 2 times
  c / crank circle radius;
- rigid supports write no bearing_forces.csv and a zero bearings part;
- the catalogue cycle of the unmodified profile (no clearance at the pins)
  on bearings with clearance c: its backlash is the bearings' alone,
  2 c / crank circle radius (slightly more: the discs may also follow the
  stage's own kinematic motion, which keeps every pin touching).
"""
import math
import os
import shutil
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402
from cycloid_tools import parameter_getter, parameter_values, run_cycloid  # noqa: E402

PALMGREN = 3.84e-5


def roller_approach(q, length):
    """Two contacts' approach [mm] at roller load q [N] (Palmgren)."""
    return 2 * PALMGREN * q ** 0.9 / length ** 0.8


def solve(exe, work, name, text):
    path = os.path.join(work, name + ".prm")
    with open(path, "w") as f:
        f.write(text + "\nset Output directory = %s\n" % name)
    r = run_cycloid(1, exe, path, cwd=work, log=os.path.join(work, name + ".log"))
    if r.returncode != 0:
        sys.exit("%s failed:\n%s" % (path, r.stdout[-3000:]))
    return os.path.join(work, name)


def hole_arm(get, disc, crank, psi):
    """Crank hole @p crank of disc @p disc from the disc centre, housing
    frame [mm], at crank angle @p psi [rad] (nominal stage)."""
    zc = int(get("Geometry", "Number of cycloid teeth", 0)) or int(
        get("Geometry", "Number of pins")) - 1
    n = int(get("Geometry", "Number of crank holes"))
    radius = float(get("Geometry", "Crank hole circle radius"))
    offset = 0 if disc == 0 else math.pi
    turn = -(psi + offset) / zc + 2 * math.pi * crank / n
    return radius * math.cos(turn), radius * math.sin(turn)


def check_run(out, name, clearance_um):
    get = parameter_getter(parameter_values(out))
    length = float(get("Geometry", "Tooth width"))
    z = int(get("Crank bearings", "Number of rollers", "17"))
    states = rows(os.path.join(out, "stiffness.csv"))
    pins = rows(os.path.join(out, "pin_forces.csv"))
    bearings = rows(os.path.join(out, "bearing_forces.csv"))
    parts = rows(os.path.join(out, "compliance_breakdown.csv"))
    c = clearance_um * 1e-3
    worst = {"force": 0, "moment": 0, "torque": 0, "stribeck": 0}
    for s, part in zip(states, parts):
        step, psi = s["step"], math.radians(float(s["crank_deg"]))
        torque = float(s["torque_Nm"]) * 1e3
        total_moment = 0
        for d in sorted({p["disc"] for p in pins}):
            fx = fy = m = 0
            scale = 0
            for p in pins:
                if p["step"] == step and p["disc"] == d:
                    fx += float(p["Fx_N"])
                    fy += float(p["Fy_N"])
                    m -= float(p["Fn_N"]) * float(p["arm_mm"])
                    scale = max(scale, float(p["Fn_N"]))
            for b in bearings:
                if b["step"] == step and b["disc"] == d:
                    bx, by = float(b["Fx_N"]), float(b["Fy_N"])
                    ax, ay = hole_arm(get, int(d), int(b["crank"]), psi)
                    fx += bx
                    fy += by
                    m += ax * by - ay * bx
                    total_moment += ax * by - ay * bx
                    scale = max(scale, float(b["F_N"]))
                    q = float(b["max_roller_load_N"])
                    delta = float(b["deflection_um"]) * 1e-3
                    if q > 0:
                        lo = delta * math.cos(math.pi / z) - c
                        hi = delta - c
                        check(lo * (1 - 1e-9) <= roller_approach(q, length) <= hi * (1 + 1e-9),
                              "%s step %s disc %s crank %s: Palmgren at %.1f N gives %.4g um, "
                              "the deflection %.4g um" % (name, step, d, b["crank"], q,
                                                          1e3 * roller_approach(q, length),
                                                          1e3 * delta))
                        if c == 0:
                            ratio = q * z / float(b["F_N"]) / 4.08
                            worst["stribeck"] = max(worst["stribeck"], abs(ratio - 1))
                    check(int(b["rollers_loaded"]) <= z, "%s: more rollers loaded than Z" % name)
            worst["force"] = max(worst["force"], math.hypot(fx, fy) / scale)
            worst["moment"] = max(worst["moment"], abs(m) / (scale * 65))
        worst["torque"] = max(worst["torque"], abs(total_moment - torque) / abs(torque))
        total = sum(float(part[k]) for k in ["contacts_rad", "bodies_rad", "bearings_rad"])
        check(abs(total - float(part["total_rad"])) <= 1e-10 * abs(float(part["total_rad"])),
              "%s step %s: the breakdown sums to %r, not %r" % (name, step, total,
                                                             part["total_rad"]))
    print("%s: equilibrium %.1e (force), %.1e (moment), torque %.1e; Q_max Z / F against "
          "Stribeck's 4.08: %s" % (name, worst["force"], worst["moment"], worst["torque"],
                                    "%.1f %%" % (100 * worst["stribeck"]) if c == 0 else "-"))
    check(worst["force"] < 1e-8, "%s: a disc's forces are off balance by %.2e" % (name, worst["force"]))
    check(worst["moment"] < 1e-8, "%s: a disc's moments are off balance by %.2e" % (name, worst["moment"]))
    check(worst["torque"] < 1e-8, "%s: the bearings' moments miss the torque by %.2e" % (name, worst["torque"]))
    check(worst["stribeck"] < 0.15, "%s: Q_max Z / F is %.1f %% off Stribeck's 4.08" % (name, 100 * worst["stribeck"]))
    return states, parts


def added_twist(name, parts, rigid_states):
    for part, rigid in zip(parts, rigid_states):
        added = float(part["total_rad"]) - float(rigid["rotation_rad"])
        share = float(part["bearings_rad"])
        print("  %s T = %s N m: bearings' part %.4g rad, beta - beta_rigid %.4g rad (%+.2f %%), "
              "%.0f %% of beta" % (name, part["torque_Nm"], share, added, 100 * (share / added - 1),
                                   100 * share / float(part["total_rad"])))
        check(abs(share / added - 1) < 0.05,
              "%s T = %s: the bearings' part %.4g against the twist they add %.4g"
              % (name, part["torque_Nm"], share, added))


def main():
    prm, exe, work = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    text = open(prm).read()
    rigid_text = text.replace("set Model = needle", "set Model = rigid")
    reduced = """
set Run = reduced
subsection Scene
  set Dimension       = 2
  set Number of discs = 1
end
subsection Reduced
  set Error estimate = false
end
"""
    clearance = "\nsubsection Crank bearings\n  set Radial clearance = 5\nend\n"

    _, parts = check_run(solve(exe, work, "analytic", text), "analytic", 0)
    rigid = solve(exe, work, "rigid", rigid_text)
    check(not os.path.exists(os.path.join(rigid, "bearing_forces.csv")),
          "rigid supports wrote bearing_forces.csv")
    rigid_parts = rows(os.path.join(rigid, "compliance_breakdown.csv"))
    check(all(float(p["bearings_rad"]) == 0 for p in rigid_parts),
          "rigid supports: a bearings part is not zero")
    rigid_states = rows(os.path.join(rigid, "stiffness.csv"))
    added_twist("analytic", parts, rigid_states)

    loose_states, _ = check_run(solve(exe, work, "clearance", text + clearance), "clearance", 5)
    for a, b in zip(rows(os.path.join(work, "analytic", "stiffness.csv")), loose_states):
        grown = abs(float(b["takeup_rad"])) - abs(float(a["takeup_rad"]))
        print("  clearance 5 um: take-up grows by %.3g rad (5 um / 65 mm = %.3g)" % (grown, 5e-3 / 65))
        check(0.5 * 5e-3 / 65 < grown < 2 * 5e-3 / 65,
              "T = %s: a 5 um clearance grows the take-up by %.3g rad" % (a["torque_Nm"], grown))

    cycle = solve(exe, work, "cycle", """set Run = analytic
subsection Geometry
  set Crank hole radius        = 15
  set Crank hole circle radius = 65
end
subsection Loading
  set Torque cycle = true
  set Rated torque = 1000
end
subsection Crank bearings
  set Model            = needle
  set Radial clearance = 3
end
""")
    backlash = float(rows(os.path.join(cycle, "rigidity.csv"))[0]["backlash_arcmin"])
    closed = 2 * 3e-3 / 65 * 180 * 60 / math.pi
    print("catalogue cycle, no pin clearance, 3 um in the bearings: backlash %.5f arcmin, "
          "2 c / R = %.5f (%+.2f %%)" % (backlash, closed, 100 * (backlash / closed - 1)))
    check(closed * (1 - 1e-6) <= backlash <= 1.01 * closed,
          "backlash %.5f arcmin against 2 c / R = %.5f" % (backlash, closed))

    _, parts = check_run(solve(exe, work, "reduced", text + reduced), "reduced", 0)
    rigid_reduced = solve(exe, work, "reduced-rigid", rigid_text + reduced)
    added_twist("reduced", parts, rows(os.path.join(rigid_reduced, "stiffness.csv")))
    check(all(float(p["bodies_rad"]) / float(p["total_rad"]) > 0 for p in parts),
          "reduced: no elastic bodies' part")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
