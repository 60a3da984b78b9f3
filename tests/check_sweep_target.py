#!/usr/bin/python3
"""A phase sweep under `Mesh/Target accuracy` answers for its fluctuation.

Usage: check_sweep_target.py FILE.prm EXECUTABLE WORKDIR

Runs FILE.prm (a sweep with Target accuracy whose first pass leaves the
K_tangent fluctuation unresolved) on 2 ranks and checks:
* the sweep was repeated: one "sweeping again at Contact refinements N"
  line per repeat, N one beyond the finest contact level the pass before
  reached (its "finest contact level" line), at most Mesh/Maximum sweep
  refinements repeats;
* the files are the last pass's: stiffness.csv has one row per phase and
  load, and its DoFs are above those of the first pass (read from the
  console's first pass);
* the closing verdict agrees with the files: "resolved" only if every
  load's fluctuation in fluctuation.csv exceeds twice its floor and the
  resolved column is 1; otherwise a line saying NOT resolved or CANNOT;
* the printed noise ratio of the last pass equals max(floor / fluctuation)
  recomputed from fluctuation.csv (1e-3), and, if the sweep stopped early
  for the rate, the rate argument is right: the ratio fell by less than
  needed to reach 0.5 in the passes left.
"""
import math
import os
import re
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import parameter_getter, parameter_values, run_cycloid  # noqa: E402


def main(prm, exe, work):
    os.makedirs(work, exist_ok=True)
    r = run_cycloid(2, exe, os.path.abspath(prm), cwd=work, oversubscribe=True)
    print(r.stdout[-4000:])
    if r.returncode != 0:
        print(r.stderr)
        raise SystemExit("the run failed")
    get = parameter_getter(parameter_values(prm, exe))
    out = os.path.join(work, get("", "Output directory"))
    base = int(get("Mesh", "Contact refinements"))
    cap = int(get("Mesh", "Maximum sweep refinements", 2))
    n_states = int(get("Loading", "Number of phases")) * len(get("Loading", "Torque").split(","))

    again = [int(x) for x in re.findall(r"sweeping again at Contact refinements (\d+)", r.stdout)]
    check(len(again) >= 1, "the sweep was not repeated (the first pass should leave it unresolved)")
    finest = [int(x) for x in re.findall(r"its finest contact level (\d+)", r.stdout)]
    check(len(finest) == len(again) + 1 and again == [f + 1 for f in finest[:-1]] and again[0] > base,
          f"repeats at levels {again}, the passes' finest levels {finest}")
    check(len(again) <= cap, f"{len(again)} repeats, Maximum sweep refinements {cap}")
    ratios = [float(x) for x in re.findall(r"the noise floor is ([0-9.e+-]+) of it", r.stdout)]
    resolved_line = "the sweep's fluctuation is resolved" in r.stdout
    final_ratio = (float(re.search(r"its largest noise floor ([0-9.e+-]+) of the fluctuation", r.stdout).group(1))
                   if resolved_line else ratios[-1])

    st = rows(f"{out}/stiffness.csv")
    check(len(st) == n_states, f"{len(st)} rows in stiffness.csv, expected {n_states} (one pass's)")
    first_dofs = [int(x) for x in re.findall(r"(\d+) DoFs \(Q", r.stdout)]
    dofs = max(int(x["dofs"]) for x in st)
    print(f"repeats at {again} (finest levels {finest}); noise ratios {ratios} then {final_ratio}; DoFs first pass "
          f"{first_dofs[:1]}, last pass's files {dofs}")
    check(first_dofs and dofs > first_dofs[0], "the files do not hold the refined pass")

    fl = rows(f"{out}/fluctuation.csv")
    recomputed = max(float(x["K_tangent_noise_floor"]) / float(x["K_tangent_fluctuation"]) for x in fl)
    check(abs(recomputed / final_ratio - 1) < 1e-3,
          f"printed ratio {final_ratio} vs fluctuation.csv {recomputed}")
    all_resolved = all(x["K_tangent_fluctuation_resolved"] == "1" for x in fl)
    check(resolved_line == all_resolved and resolved_line == (recomputed < 0.5),
          f"verdict resolved={resolved_line}, fluctuation.csv resolved={all_resolved}, ratio {recomputed}")
    if not resolved_line:
        check("NOT resolved" in r.stdout or "CANNOT" in r.stdout, "no verdict when unresolved")
        if "at the last pass's rate" in r.stdout:
            fall = ratios[-2] / ratios[-1]
            left = cap - len(again)
            check(fall > 1 and math.log(2 * ratios[-1]) / math.log(fall) > left,
                  f"stopped for the rate: fall {fall}, {left} passes left")
    return verdict()


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:4]))
