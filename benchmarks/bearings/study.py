#!/usr/bin/python3
"""Where the seed stage's twist comes from once its discs ride on crank
needle bearings (issue #52 items 6 and 7).

Usage: benchmarks/bearings/study.py [--exe EXE] [--ranks R] [--model reduced|analytic]

The seed case (prm/seed-case.prm: 3D, two discs, elastic pins in the
housing, the unmodified profile) with the reduced model, crank angle 0:
- rigid supports against needle bearings of auto size (17 rollers of
  3.75 x 16 mm in each 15 mm crank hole) at 300 and 1000 N m: the
  rotation, its breakdown (compliance_breakdown.csv), the pin forces and
  how they shift when the discs can translate, the bearing forces; and the
  cost of the two runs side by side (each state's wall_s after the first,
  and the whole run);
- the catalogue cycle (rated 1000 N m) with a radial clearance of 0, 5, 10
  and 20 um: rigidity, lost motion, backlash;
- 2 crankshafts against 3 (Number of crank holes), rigid and on bearings;
- the analytical model's cost, rigid against needle, 19 phases x 3
  torques (the median of the states' wall_s; the reduced model's too, over
  30 further torques).
Writes doc/bearings/{breakdown,pins,clearance,cranks,cost}.csv. Run it on
an idle machine; about 3 minutes on 2 ranks. --only-cost: the cost rows.
"""
import argparse
import csv
import os
import re
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.join(HERE, "..", "..")
sys.path.insert(0, os.path.join(ROOT, "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

OUT = os.path.join(ROOT, "doc", "bearings")


def stage(model, extra):
    base = open(os.path.join(ROOT, "prm", "seed-case.prm")).read()
    base = re.sub(r"(?m)^set Output directory.*$", "", base)
    base = re.sub(r"(?m)^set Run .*$", "set Run = %s" % model, base)
    base = re.sub(r"(?ms)^subsection Loading.*?^end\n", "", base)
    return base + "\nsubsection Reduced\n  set Error estimate = false\nend\n" + extra


def solve(args, work, name, text):
    path = os.path.join(work, name + ".prm")
    with open(path, "w") as f:
        f.write(text + "\nset Output directory = %s\n" % name)
    start = time.time()
    r = run_cycloid(args.ranks, args.exe, path, cwd=work, log=os.path.join(work, name + ".log"))
    wall = time.time() - start
    if r.returncode != 0:
        sys.exit("%s failed:\n%s" % (path, r.stdout[-3000:]))
    print("  %s: %.1f s" % (name, wall), flush=True)
    return os.path.join(work, name), wall


def write(name, columns, table):
    with open(os.path.join(OUT, name), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        w.writerows(table)


def loading(torques, cycle=False):
    if cycle:
        return ("subsection Loading\n  set Torque cycle = true\n  set Rated torque = 1000\n"
                "  set Crank angle = 0\nend\n")
    return "subsection Loading\n  set Torque = %s\n  set Crank angle = 0\nend\n" % torques


def bearings(clearance, cranks=None):
    text = ("subsection Crank bearings\n  set Model = needle\n  set Radial clearance = %g\nend\n"
            % clearance)
    return text + (geometry(cranks) if cranks else "")


def geometry(cranks):
    return "subsection Geometry\n  set Number of crank holes = %d\nend\n" % cranks


def main():
    p = argparse.ArgumentParser()
    p.add_argument("--exe", default=os.path.join(ROOT, "build", "cycloid-contact"))
    p.add_argument("--ranks", type=int, default=2)
    p.add_argument("--model", default="reduced")
    p.add_argument("--only-cost", action="store_true")
    args = p.parse_args()
    args.exe = os.path.abspath(args.exe)
    os.makedirs(OUT, exist_ok=True)
    work = tempfile.mkdtemp(prefix="bearings-study-")
    print("work in", work, "load", os.getloadavg()[0])

    # Rigid against needle, 300 and 1000 N m; cost side by side.
    # 300 and 1000 N m first (the breakdown), then 30 more torques whose
    # median wall_s is a state's cost (a state takes milliseconds: a mean
    # of a few is noise).
    torques = ", ".join(["300", "1000"] + ["%d" % (100 * k) for k in range(1, 31)])
    runs = {}
    for name, extra in [("rigid", ""), ("needle", bearings(0))]:
        runs[name] = solve(args, work, name, stage(args.model, loading(torques) + extra))
    breakdown, pins, cost = [], [], []
    for name, (out, wall) in runs.items():
        states = read_csv(os.path.join(out, "stiffness.csv"))
        parts = read_csv(os.path.join(out, "compliance_breakdown.csv"))
        per_state = sorted(float(s["wall_s"]) for s in states[2:])
        cost.append({"model": args.model, "supports": name, "ranks": args.ranks,
                     "run_s": "%.2f" % wall,
                     "state_ms": "%.3f" % (1e3 * per_state[len(per_state) // 2]),
                     "load": "%.2f" % os.getloadavg()[0]})
        for s, part in list(zip(states, parts))[:2]:
            total = float(part["total_rad"])
            row = {"supports": name, "torque_Nm": s["torque_Nm"], "rotation_rad": s["rotation_rad"],
                   "K_secant_Nm_per_arcmin": s["K_secant_Nm_per_arcmin"],
                   "K_tangent_Nm_per_arcmin": s["K_tangent_Nm_per_arcmin"],
                   "pins_in_contact": s["pins_in_contact"], "max_pin_force_N": s["max_pin_force_N"]}
            for k in ["contacts", "bodies", "bearings"]:
                row[k + "_share"] = "%.4f" % (float(part[k + "_rad"]) / total)
            if name == "needle":
                b = read_csv(os.path.join(out, "bearing_forces.csv"))
                b = [x for x in b if x["step"] == s["step"]]
                row["max_bearing_force_N"] = max(float(x["F_N"]) for x in b)
                row["max_roller_load_N"] = max(float(x["max_roller_load_N"]) for x in b)
                row["max_bearing_deflection_um"] = max(float(x["deflection_um"]) for x in b)
            breakdown.append(row)
    rigid_pins = read_csv(os.path.join(runs["rigid"][0], "pin_forces.csv"))
    needle_pins = read_csv(os.path.join(runs["needle"][0], "pin_forces.csv"))
    for a, b in zip(rigid_pins, needle_pins):
        if a["step"] in ("0", "1"):
            pins.append({"torque_Nm": "300" if a["step"] == "0" else "1000", "disc": a["disc"],
                         "pin": a["pin"], "rigid_N": a["Fn_N"], "needle_N": b["Fn_N"]})
    for name, extra in [("rigid", ""), ("needle", bearings(0))]:
        sweep = ("subsection Loading\n  set Torque = 300, 1000, 3000\n"
                 "  set Number of phases = 19\nend\n")
        out, wall = solve(args, work, "analytic-" + name,
                          "set Run = analytic\n" + sweep + extra)
        per_state = sorted(float(s["wall_s"])
                           for s in read_csv(os.path.join(out, "stiffness.csv")))
        cost.append({"model": "analytic", "supports": name, "ranks": args.ranks,
                     "run_s": "%.2f" % wall,
                     "state_ms": "%.3f" % (1e3 * per_state[len(per_state) // 2]),
                     "load": "%.2f" % os.getloadavg()[0]})
    write("cost.csv", list(cost[0].keys()), cost)
    if args.only_cost:
        return
    write("breakdown.csv", list(breakdown[-1].keys()), breakdown)
    write("pins.csv", list(pins[0].keys()), pins)

    # Clearance: the catalogue cycle.
    clearance = []
    for c in [None, 0, 5, 10, 20]:
        name = "cycle-rigid" if c is None else "cycle-%g" % c
        out, _ = solve(args, work, name,
                       stage(args.model, loading(None, True) + ("" if c is None else bearings(c))))
        r = read_csv(os.path.join(out, "rigidity.csv"))[0]
        clearance.append({"supports": "rigid" if c is None else "needle",
                          "clearance_um": "" if c is None else c,
                          "rigidity_Nm_per_arcmin": r["torsional_rigidity_Nm_per_arcmin"],
                          "lost_motion_arcmin": r["lost_motion_arcmin"],
                          "backlash_arcmin": r["backlash_arcmin"]})
    write("clearance.csv", list(clearance[0].keys()), clearance)

    # 2 crankshafts against 3.
    cranks = []
    for n in [3, 2]:
        for name, extra in [("rigid", geometry(n)), ("needle", bearings(0, n))]:
            out, _ = solve(args, work, "cranks-%d-%s" % (n, name),
                           stage(args.model, loading("300, 1000") + extra))
            states = read_csv(os.path.join(out, "stiffness.csv"))
            parts = read_csv(os.path.join(out, "compliance_breakdown.csv"))
            for s, part in zip(states, parts):
                row = {"cranks": n, "supports": name, "torque_Nm": s["torque_Nm"],
                       "rotation_rad": s["rotation_rad"],
                       "K_secant_Nm_per_arcmin": s["K_secant_Nm_per_arcmin"],
                       "bearings_share": "%.4f" % (float(part["bearings_rad"]) /
                                                   float(part["total_rad"])),
                       "max_pin_force_N": s["max_pin_force_N"], "max_bearing_force_N": ""}
                if name == "needle":
                    b = [x for x in read_csv(os.path.join(out, "bearing_forces.csv"))
                         if x["step"] == s["step"]]
                    row["max_bearing_force_N"] = max(float(x["F_N"]) for x in b)
                cranks.append(row)
    write("cranks.csv", list(cranks[0].keys()), cranks)
    print("wrote", OUT)


if __name__ == "__main__":
    main()
