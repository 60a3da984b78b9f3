#!/usr/bin/python3
"""What the error estimate costs (doc/error-estimate.md §4).

The 2D slab case of issue #15 (one disc, elastic pins, modified profile,
1000 N m) at Contact refinements 2, 3 and 4, with Mesh/Error estimate false
and true, and from the default mesh with Target accuracy 0.01; whole
`mpirun -np 2` command, interleaved, `--repeat` times (median), with the
load average at the start.

  /usr/bin/python3 benchmarks/error_estimate/cost.py [--repeat 2]

Writes doc/error-estimate/cost.csv.
"""
import argparse
import csv
import os
import statistics
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.path.join(ROOT, "build", "cycloid-contact")
WORK = "/tmp/cycloid-error-estimate-cost"
# The slab case of the validation, so that both measure the same scene.
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from validate import CASES_2D  # noqa: E402

SLAB = CASES_2D["2D slab, modified, 1000 N m"][0]
BODY = ("set Run = quasi-static\nset Output directory = {out}\nset Write solution = false\n"
        + SLAB.replace("{", "{{").replace("}", "}}") + "subsection Mesh\n{mesh}end\n")
VARIANTS = [(f"cr{c} estimate {e}", f"  set Contact refinements = {c}\n  set Error estimate = {e}\n"
             "  set Target accuracy = 0\n")
            for c in (2, 3, 4) for e in ("false", "true")]
VARIANTS.append(("default mesh, Target accuracy 0.01", "  set Target accuracy = 0.01\n"))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--repeat", type=int, default=2)
    args = ap.parse_args()
    os.makedirs(WORK, exist_ok=True)
    times = {name: [] for name, _ in VARIANTS}
    result = {}
    load = os.getloadavg()[0]
    for _ in range(args.repeat):
        for i, (name, mesh) in enumerate(VARIANTS):
            out = os.path.join(WORK, f"v{i}")
            with open(out + ".prm", "w") as f:
                f.write(BODY.format(out=out, mesh=mesh))
            times[name].append(run_cycloid(2, EXE, out + ".prm", check=True).wall_s)
            result[name] = read_csv(os.path.join(out, "stiffness.csv"))[0]
    rows = []
    for name, _ in VARIANTS:
        s = result[name]
        rows.append({"variant": name, "dofs": s["dofs"], "wall_s_median": statistics.median(times[name]),
                     "active_set_iterations": s["active_set_iterations"],
                     "K_secant_error": s["K_secant_error"], "K_tangent_error": s["K_tangent_error"],
                     "max_pin_force_error": s["max_pin_force_error"], "load_avg_at_start": load})
        print(f"{name:36s} dofs {s['dofs']:>7s}  {rows[-1]['wall_s_median']:6.2f} s  "
              f"iterations {s['active_set_iterations']:>3s}  estimates {s['K_secant_error']}, "
              f"{s['K_tangent_error']}, {s['max_pin_force_error']}")
    dest = os.path.join(ROOT, "doc", "error-estimate")
    os.makedirs(dest, exist_ok=True)
    with open(os.path.join(dest, "cost.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
