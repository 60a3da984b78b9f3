#!/usr/bin/python3
"""Cost of the reduced model (issue #13 item 3): the whole command
(`mpirun -np 2`, meshing and every precomputation included), timed from
outside, on an idle machine (the load average at the start is recorded).

    /usr/bin/python3 benchmarks/reduced/cost.py [--exe build/cycloid-contact] [--out doc/reduced]

Cases (seed case, unmodified profile unless named):
  2d-state        2D one disc, elastic pins on their axes, 1000 N m, crank 0
  3d-state        3D two discs, pins in the housing, 1000 N m, crank 0
  3d-3-torques    the same at 3, 300, 1000 N m (each further torque: its
                  state's wall_s in stiffness.csv)
  2d-sweep        2D, modified profile, 19 phases over 9 deg x 3 torques
  3d-sweep        3D, 19 phases over 9 deg x 3 torques
Output: cost.csv in --out.
"""
import argparse
import csv
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

SCENE_2D = "subsection Scene\n  set Dimension = 2\n  set Pins = elastic\n  set Pin support = axis\nend\n"
SCENE_3D = ("subsection Scene\n  set Dimension = 3\n  set Number of discs = 2\n"
            "  set Pins = elastic\n  set Pin support = housing\nend\n")
MODIFIED = ("subsection Geometry\n  set Pin circle radius modification = -0.01\n"
            "  set Pin radius modification = 0.01\nend\n")
CASES = [
    ("2d-state", SCENE_2D, "1000", 1),
    ("3d-state", SCENE_3D, "1000", 1),
    ("3d-3-torques", SCENE_3D, "3, 300, 1000", 1),
    ("2d-sweep", SCENE_2D + MODIFIED, "300, 500, 1000", 19),
    ("3d-sweep", SCENE_3D, "300, 500, 1000", 19),
]


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default="build/cycloid-contact")
    ap.add_argument("--out", default="doc/reduced")
    ap.add_argument("--work", default="/tmp/reduced-cost")
    ap.add_argument("--cases", default=None)
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    rows = []
    for name, scene, torques, phases in CASES:
        if args.cases and name not in args.cases.split(","):
            continue
        out = os.path.join(args.work, name)
        prm = out + ".prm"
        with open(prm, "w") as f:
            f.write("set Run = reduced\nset Output directory = %s\n%s"
                    "subsection Loading\n  set Torque = %s\n  set Crank angle = 0\n"
                    "  set Number of phases = %d\nend\n" % (out, scene, torques, phases))
        load = os.getloadavg()[0]
        wall = run_cycloid(2, os.path.abspath(args.exe), prm, log=out + ".log", check=True).wall_s
        states = read_csv(os.path.join(out, "stiffness.csv"))
        further = [float(s["wall_s"]) for s in states[1:]] if phases == 1 else []
        row = dict(case=name, states=len(states), dofs=states[0]["dofs"],
                   wall_s="%.2f" % wall,
                   further_torque_s="%.2e" % max(further) if further else "",
                   peak_memory_MB=states[0]["peak_memory_MB"],
                   load_avg_at_start="%.2f" % load)
        rows.append(row)
        print(row, flush=True)
    with open(os.path.join(args.out, "cost.csv"), "w") as f:
        w = csv.DictWriter(f, list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
