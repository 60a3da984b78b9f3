#!/usr/bin/python3
"""Rotation control against torque control.

Usage: check_rotation_control.py FILE.prm EXECUTABLE WORKDIR

Runs FILE.prm (Control = torque) on 2 ranks, then the same scene under
Control = rotation at each rotation beta that the torque run found. For a
given beta the contact problem has the same solution, so the reaction torque
must equal the target torque (1e-8), with the same K_tangent and the same
engaged pins.
"""
import math
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import read_csv as rows, run_cycloid  # noqa: E402


def run(exe, prm, cwd):
    run_cycloid(2, exe, prm, cwd=cwd, check=True, oversubscribe=True)


def main(prm, exe, work):
    os.makedirs(work, exist_ok=True)
    text = open(prm).read()
    out = [l for l in text.splitlines() if l.strip().startswith("set Output directory")][0]
    with open(f"{work}/torque.prm", "w") as f:
        f.write(text.replace(out, "set Output directory = torque\nset Write solution = false"))
    run(exe, "torque.prm", work)
    t_rows = rows(f"{work}/torque/stiffness.csv")
    betas = [float(r["rotation_rad"]) for r in t_rows]
    rot = text.replace(out, "set Output directory = rotation\nset Write solution = false")
    rot = rot.replace("subsection Loading", "subsection Loading\n  set Control = rotation\n  set Rotation = "
                      + ", ".join(repr(b * 180 / math.pi) for b in betas))
    with open(f"{work}/rotation.prm", "w") as f:
        f.write(rot)
    run(exe, "rotation.prm", work)
    r_rows = rows(f"{work}/rotation/stiffness.csv")
    failures = []
    for a, b in zip(t_rows, r_rows):
        ta, tb = float(a["torque_Nm"]), float(b["torque_Nm"])
        ka, kb = float(a["K_tangent_Nm_per_rad"]), float(b["K_tangent_Nm_per_rad"])
        print(f"beta {float(b['rotation_rad']):.6e} rad: torque control T {ta:g}, rotation control T {tb:.10g}; "
              f"K_tangent {ka:.6e} / {kb:.6e}; pins {a['pins_in_contact']} / {b['pins_in_contact']}")
        if abs(ta - tb) > 1e-8 * abs(ta) or abs(ka - kb) > 1e-8 * ka or a["pins_in_contact"] != b["pins_in_contact"]:
            failures.append(f"T {ta}: rotation control gives {tb}, K {kb} vs {ka}")
        if abs(float(b["reaction_torque_Nm"]) - tb) > 1e-8 * abs(tb):
            failures.append(f"sum F arm {b['reaction_torque_Nm']} != {tb}")
    print("\n".join(failures) if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
