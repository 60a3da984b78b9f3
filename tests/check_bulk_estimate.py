#!/usr/bin/python3
"""The bulk mesh's part of the error estimate (Mesh/Bulk error estimate).

Usage: check_bulk_estimate.py FILE.prm EXECUTABLE WORKDIR

FILE.prm is issue #15's new-user case (tests/runs/error-estimate.prm: the
2D slab, modified profile, 1000 N m). At Contact refinements 2, with the
estimate on and no target, the script solves it
* with Bulk error estimate = false and at its default (auto: on in 2D):
  the state is the same (the
  bulk level refines the bulk, solves, and coarsens back to the mesh asked
  for: same DoFs, K and pin forces to 1e-9), every estimate grows by the
  bulk part and no more than bulk_error, bulk_error is reported
  (stiffness.csv, console);
* with Polynomial degree = 2 on the same mesh, whose bulk error is far
  smaller: the state's K_secant lies within its estimate of Q2's (the
  contact levels alone, which share the bulk mesh, state 0.003 % there),
  and the bulk part of the K_secant estimate is within a factor of 2 of
  the distance from Q2 (twice the change of one bulk refinement, against
  the change to Q2: measured 1.4-1.7 on five 2D cases). It fails if the
  bulk level does not refine the bulk or the factor is wrong;
* with Target accuracy 0.005, below the bulk part (0.86 %): the target's
  cycles still refine at the contacts (the state ends above contact level
  2), the target is reported NOT reached, and the console names the bulk
  part and its cure.
"""
import argparse
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, verdict  # noqa: E402
from check_error_estimate import run, estimates  # noqa: E402

BASE = {"Contact refinements": 2, "Target accuracy": 0, "Error estimate": "true"}


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("prm")
    ap.add_argument("exe")
    ap.add_argument("work")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    text = open(args.prm).read()
    s0, p0, _ = run(args.exe, text, args.work, "bulk-off", dict(BASE, **{"Bulk error estimate": "false"}))
    # Bulk error estimate at its default, auto: on in 2D.
    s1, p1, log1 = run(args.exe, text, args.work, "bulk-on", BASE)
    sq, pq, _ = run(args.exe, text, args.work, "q2", dict(BASE, **{"Polynomial degree": 2, "Error estimate": "false"}))

    check(s0["dofs"] == s1["dofs"], "bulk level: %s DoFs after it, not %s" % (s1["dofs"], s0["dofs"]))
    fmax = max(p0.values())
    same = max([abs(float(s1[k]) / float(s0[k]) - 1) for k in ("K_secant_Nm_per_rad", "K_tangent_Nm_per_rad")]
               + [abs(p1[k] - p0[k]) / fmax for k in p0])
    print("state with and without the bulk level: largest difference %.2g" % same)
    check(same <= 1e-9, "the bulk level changed the state by %.2g" % same)

    bulk = float(s1["bulk_error"])
    check(s0["bulk_error"] == "nan", "bulk_error reported without Bulk error estimate: %s" % s0["bulk_error"])
    check(bulk > 0, "bulk_error %s not positive" % s1["bulk_error"])
    check("of these the bulk mesh's part up to" in log1, "console: no bulk part on the estimate line")
    e0, e1 = estimates(s0), estimates(s1)
    for q in e0:
        grown = e1[q] - e0[q]
        print("%-10s estimate %.4g %% -> %.4g %% with the bulk part (bulk_error %.4g %%)"
              % (q, 100 * e0[q], 100 * e1[q], 100 * bulk))
        check(-1e-12 <= grown <= bulk + 1e-12, "%s: the estimate grew by %.4g, not in [0, bulk_error %.4g]"
              % (q, grown, bulk))

    ks1, ksq = float(s1["K_secant_Nm_per_rad"]), float(sq["K_secant_Nm_per_rad"])
    distance = abs(ks1 / ksq - 1)
    part = e1["K_secant"] - e0["K_secant"]
    print("K_secant: Q1 %.7g, Q2 %.7g: distance %.4g %%; estimate %.4g %% (bulk part %.4g %%, contact levels %.4g %%)"
          % (ks1, ksq, 100 * distance, 100 * e1["K_secant"], 100 * part, 100 * e0["K_secant"]))
    check(distance <= e1["K_secant"], "K_secant %.4g %% from Q2, above its estimate %.4g %%"
          % (100 * distance, 100 * e1["K_secant"]))
    check(0.5 * distance <= part <= 2 * distance,
          "the bulk part of the K_secant estimate, %.4g %%, is not within a factor 2 of the distance from Q2, %.4g %%"
          % (100 * part, 100 * distance))

    st, _, logt = run(args.exe, text, args.work, "target",
                      dict(BASE, **{"Target accuracy": 0.005}))
    level = re.search(r"target accuracy 0.005: NOT reached at contact level (\d+)", logt)
    print("target 0.005 with the bulk part %.3g %%: %s" % (100 * float(st["bulk_error"]),
                                                         level.group(0) if level else "no NOT reached line"))
    check(level is not None, "target 0.005: not reported NOT reached")
    check(level is not None and int(level.group(1)) > 2,
          "target 0.005: the cycles did not refine at the contacts")
    check("the bulk mesh's part of the estimate is" in logt, "target 0.005: the bulk part and its cure not named")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
