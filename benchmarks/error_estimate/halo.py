#!/usr/bin/python3
"""The bulk part of the estimate after Target accuracy's cycles (doc/error-estimate.md §5).

prm/quasi-static-2d.prm (2D, one disc, elastic pins, modified profile,
100, 500 and 1000 N m) is solved under Target accuracy on several bulk
meshes, with the estimate and its bulk part at their defaults, and each
state is compared with Q2 at Contact refinements 4 on the default mesh
(estimate off), whose bulk and contact errors are both far smaller. A
value counts as covered when its distance from Q2 is at most its
estimate: K_secant, K_tangent, and the pin forces as the largest
|F - F_ref| over the pins relative to Q2's largest (validate.py's
measure) against max_pin_force_error.

The target's cycles refine at the contacts and leave a graded halo of
intermediate levels around them, which the contact levels' estimate
(it coarsens the two finest levels) does not see. The bulk level refines
every cell below those two levels, on the first mesh and again on the
last: this script is the check that the halo's error is in the estimate.

  /usr/bin/python3 benchmarks/error_estimate/halo.py [--ranks 2]

Runs are cached in /tmp/cycloid-halo (a folder with stiffness.csv is not
run again). Writes doc/error-estimate/halo.csv.
"""
import argparse
import csv
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = os.path.join(ROOT, "build", "cycloid-contact")
PRM = os.path.join(ROOT, "prm", "quasi-static-2d.prm")
WORK = "/tmp/cycloid-halo"
REFERENCE = ("Q2, Contact refinements 4",
             {"Polynomial degree": 2, "Contact refinements": 4, "Error estimate": "false",
              "Target accuracy": 0})
# name -> Mesh entries added to prm/quasi-static-2d.prm
VARIANTS = {
    "default sizes, Target accuracy auto (0.02)": {"Target accuracy": "auto"},
    "default sizes, Target accuracy 0.01": {},
    "Size grading 0.125": {"Size grading": 0.125},
    "Size grading 0.125, Fine zone radius 1": {"Size grading": 0.125, "Fine zone radius": 1},
}


def tag(name):
    return "".join(c if c.isalnum() else "_" for c in name)


def run(name, entries, ranks):
    out = os.path.join(WORK, tag(name))
    if not os.path.exists(os.path.join(out, "stiffness.csv")):
        text = open(PRM).read().replace("output/quasi-static-2d", out)
        text += "subsection Mesh\n" + "".join("  set %s = %s\n" % kv for kv in entries.items()) + "end\n"
        with open(out + ".prm", "w") as f:
            f.write(text)
        r = run_cycloid(ranks, EXE, out + ".prm", log=out + ".log")
        if r.returncode != 0:
            sys.exit("%s failed, see %s.log" % (name, out))
        print("%s: %.0f s" % (name, r.wall_s), flush=True)
    states = read_csv(os.path.join(out, "stiffness.csv"))
    pins = read_csv(os.path.join(out, "pin_forces.csv"))
    return states, pins


def compare(state, pins, ref, ref_pins):
    def forces(rows, step):
        return {(r["disc"], r["pin"]): float(r["Fn_N"]) for r in rows if r["step"] == step}
    f, fr = forces(pins, state["step"]), forces(ref_pins, ref["step"])
    rel = lambda q: abs(float(state[q]) / float(ref[q]) - 1)  # noqa: E731
    return {"K_secant": (rel("K_secant_Nm_per_rad"), float(state["K_secant_error"])),
            "K_tangent": (rel("K_tangent_Nm_per_rad"), float(state["K_tangent_error"])),
            "pin_forces": (max(abs(f[k] - fr[k]) for k in fr) / max(fr.values()),
                           float(state["max_pin_force_error"]))}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--ranks", type=int, default=2)
    args = ap.parse_args()
    os.makedirs(WORK, exist_ok=True)
    ref, ref_pins = run(REFERENCE[0], REFERENCE[1], args.ranks)
    rows, covered, total = [], 0, 0
    for name, entries in VARIANTS.items():
        states, pins = run(name, entries, args.ranks)
        for s, r in zip(states, ref):
            for q, (err, est) in compare(s, pins, r, ref_pins).items():
                total += 1
                covered += err <= est
                rows.append({"mesh": name, "torque_Nm": s["torque_Nm"], "quantity": q,
                             "dofs": s["dofs"], "error_pct": "%.4g" % (100 * err),
                             "estimate_pct": "%.4g" % (100 * est),
                             "bulk_part_pct": "%.4g" % (100 * float(s["bulk_error"])),
                             "covered": int(err <= est)})
                print("%-42s %5s N m %-10s error %6.3f %%  estimate %6.3f %%  bulk part %6.3f %%%s"
                      % (name, s["torque_Nm"], q, 100 * err, 100 * est, 100 * float(s["bulk_error"]),
                         "" if err <= est else "  ABOVE"))
    print("covered: %d of %d" % (covered, total))
    path = os.path.join(ROOT, "doc", "error-estimate", "halo.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("wrote", path)


if __name__ == "__main__":
    sys.exit(main())
