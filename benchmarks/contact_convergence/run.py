#!/usr/bin/python3
"""Convergence of the 2D FE stiffness with the a-priori contact refinement.

Seed geometry with Delta rp = -0.01, Delta rrp = +0.01 mm, one disc,
elastic pins held at their cores, crank angle 1 deg, T = 300 and 1000 N m,
on 2 MPI ranks, Mesh/Contact refinements = 0 ... 4 (radius 0.3 mm). Records
K_secant_elastic, K_tangent, engaged pins, DoFs and wall time per state, and
the analytical line-contact model of the same scene, in
doc/contact-convergence.csv.
Usage: benchmarks/contact_convergence/run.py [path/to/cycloid-contact]
"""
import csv
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "cycloid-contact")
PRM = """set Run = {run}
set Output directory = {out}
subsection Geometry
  set Pin circle radius modification = -0.01
  set Pin radius modification = 0.01
end
subsection Scene
  set Number of discs = 1
  set Pins = elastic
end
subsection Loading
  set Torque = 300, 1000
  set Crank angle = 1
end
subsection Mesh
  set Contact refinements = {n}
  set Contact refinement radius = 0.3
  set Target accuracy = 0
end
"""


def run(tmp, run_mode, n):
    out = f"{tmp}/{run_mode}-{n}"
    with open(f"{out}.prm", "w") as f:
        f.write(PRM.format(run=run_mode, out=out, n=n))
    run_cycloid(2, EXE, f"{out}.prm", check=True)
    return read_csv(f"{out}/stiffness.csv")


def main():
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for r in run(tmp, "analytic", 0):
            rows.append(["analytic line-contact", "-", r["torque_Nm"], r["K_secant_elastic_Nm_per_rad"],
                         r["K_tangent_Nm_per_rad"], r["pins_in_contact"], 0, r["wall_s"], 0])
        for n in range(5):
            for r in run(tmp, "quasi-static", n):
                rows.append(["FE 2D elastic pins", n, r["torque_Nm"], r["K_secant_elastic_Nm_per_rad"],
                             r["K_tangent_Nm_per_rad"], r["pins_in_contact"], r["dofs"], r["wall_s"],
                             r["active_set_iterations"]])
                print(f"refinements {n}: T {r['torque_Nm']} N m, K_secant_elastic {float(r['K_secant_elastic_Nm_per_rad']):.4e},"
                      f" K_tangent {float(r['K_tangent_Nm_per_rad']):.4e} N m/rad, pins {r['pins_in_contact']},"
                      f" dofs {r['dofs']}, {float(r['wall_s']):.2f} s, iterations {r['active_set_iterations']}", flush=True)
    path = os.path.join(ROOT, "doc", "contact-convergence.csv")
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(["model", "contact_refinements", "torque_Nm", "K_secant_elastic_Nm_per_rad",
                    "K_tangent_Nm_per_rad", "pins_in_contact", "dofs", "wall_s", "active_set_iterations"])
        w.writerows(rows)
    print("written", path)


if __name__ == "__main__":
    main()
