#!/usr/bin/python3
"""The FE error estimate, its warning and Mesh/Target accuracy (issue #15).

Usage: check_error_estimate.py FILE.prm EXECUTABLE WORKDIR

FILE.prm is the new-user case of issue #15: the 2D slab, modified profile,
1000 N m, every Mesh entry at its default. The script runs it
* as it is: Mesh/Target accuracy = auto resolves to the Warning threshold
  (0.02), announced; the estimate includes the bulk mesh's part
  (Mesh/Bulk error estimate = auto, on in 2D), said on the console; the
  state refines until its estimates are below it,
  so it is not flagged, and it lands within 2 % of the reference in
  K_secant, K_tangent and every pin force (of the largest), and within its
  estimate plus the reference's band;
* with Target accuracy 0 (Contact refinements 0, which the estimate raises
  to 2): the state is flagged (mesh_warning 1, a console WARNING naming
  pins and the cure): the change from level 0 to 1 is tens of per cent;
* at Contact refinements 3 (Target accuracy 0), the mesh that agrees with
  an independent FE model to 0.9 % in every pin force: not flagged;
* at Contact refinements 2 and 3 (Target accuracy 0) against the reference
  (Contact refinements 2 + 4 adaptive cycles, estimate off; its own error
  band is its distance from Contact refinements 3 + 3 adaptive cycles, the
  same contact level on another mesh; the bulk part left out, as the
  reference shares the bulk mesh): the estimate is on the safe side of
  the true error of K_secant, K_tangent and every pin force (true error <=
  estimate + band), and at Contact refinements 3 at most BRACKET times the
  true error plus the band. (At Contact refinements 2 half the change from
  level 0 to 1 dominates the estimate, 10-300 times the error: measured in
  doc/error-estimate.md, not checked);
* with Error estimate = false at Contact refinements 1 and 3: the
  contact-resolution indicator (C / n^2, n the nodes across the Hertz width
  of the most loaded pin) covers the true pin-force error, n follows the
  node spacing (a quarter from level 1 to 3), and it flags level 1 but
  not level 3; the n announced before the solve for the analytical
  model's most loaded pin is the solved n of that pin at that force;
* with Mesh/Target accuracy 0.01 from Contact refinements 0, the bulk part
  left out (the default bulk's own is 0.86 %): it reports
  the target reached, and lands within 1 % of the reference in K_secant,
  K_tangent and every pin force (of the largest);
* the Target accuracy 0.01 run again on the distributed mesh
  (Mesh/Triangulation = distributed) on 3 ranks: the same DoFs, K, pin
  forces and estimates within 1e-8;
* the default run again with the memory the run may use
  (CYCLOID_AVAILABLE_MEMORY_MB) set 1 MB above the cost model's estimate
  for its first mesh: that mesh is solved, its first refinement would not
  fit, so the run says "refinement stopped", reports the target NOT
  reached, exits normally and reports the state of the first mesh (its
  DoFs, and K as the Target accuracy 0 run on the same mesh has them),
  flagged; the bulk level, larger still, is skipped and said so.
"""
import argparse
import os
import re
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402

BRACKET = 10.0
RESOLUTION_CONSTANT = 0.25  # results::resolution_constant


def run(exe, text, work, name, mesh, env=None, ranks=2):
    out = os.path.join(work, name)
    prm = out + ".prm"
    with open(prm, "w") as f:
        f.write(text.replace("set Output directory = error-estimate",
                             "set Output directory = " + out))
        f.write("subsection Mesh\n" + "".join("  set %s = %s\n" % kv for kv in mesh.items()) + "end\n")
    r = run_cycloid(ranks, exe, prm, log=out + ".log", env=env)
    if r.returncode != 0:
        sys.exit("%s failed, see %s.log" % (name, out))
    s = rows(os.path.join(out, "stiffness.csv"))[0]
    pins = {(p["disc"], p["pin"]): float(p["Fn_N"]) for p in rows(os.path.join(out, "pin_forces.csv"))}
    return s, pins, r.stdout


def errors(a, b):
    """Relative distance of state a from state b: K_secant, K_tangent, every
    pin force relative to b's largest."""
    (sa, pa), (sb, pb) = a, b
    fmax = max(pb.values())
    return {"K_secant": abs(float(sa["K_secant_Nm_per_rad"]) / float(sb["K_secant_Nm_per_rad"]) - 1),
            "K_tangent": abs(float(sa["K_tangent_Nm_per_rad"]) / float(sb["K_tangent_Nm_per_rad"]) - 1),
            "pin_forces": max(abs(pa[k] - pb[k]) for k in pb) / fmax}


def estimates(s):
    return {"K_secant": float(s["K_secant_error"]), "K_tangent": float(s["K_tangent_error"]),
            "pin_forces": float(s["max_pin_force_error"])}


def check_resolution(args, text, ref, band):
    """Without the estimate, the contact-resolution indicator: n halves
    with the spacing (two levels: the spacing at the most loaded pin / 4),
    the indicator covers the true pin-force error, and it flags
    Contact refinements 1 (n about 1.3, indicator 14 %) but not 3 (n about
    4.5, indicator 1.2 %)."""
    got = {}
    for cr in (1, 3):
        s, p, log = run(args.exe, text, args.work, "resolution-cr%d" % cr,
                        {"Contact refinements": cr, "Target accuracy": 0, "Error estimate": "false"})
        pins = rows(os.path.join(args.work, "resolution-cr%d" % cr, "pin_forces.csv"))
        most = max(pins, key=lambda r: float(r["Fn_N"]))
        n, indicator = float(s["hertz_nodes"]), float(s["resolution_error"])
        spacing = 2 * float(most["hertz_halfwidth_um"]) / float(most["hertz_nodes"])
        true = errors((s, p), ref)["pin_forces"]
        got[cr] = (s, log, spacing)
        print("no estimate, cr%d: %.2f nodes across the Hertz width (spacing %.1f um), indicator %.3g %%, "
              "true pin-force error %.3g %%" % (cr, n, spacing, 100 * indicator, 100 * true))
        check(n == float(most["hertz_nodes"]), "cr%d: stiffness.csv hertz_nodes is not the most loaded pin's" % cr)
        check(abs(indicator * n * n / RESOLUTION_CONSTANT - 1) < 1e-9,
              "cr%d: resolution_error %.6g is not C / n^2" % (cr, indicator))
        check(true <= indicator + band["pin_forces"],
              "cr%d: pin-force error %.3g above the resolution indicator %.3g" % (cr, true, indicator))
        # Announced before the solve for the analytical model's most
        # loaded pin: the same pin's n in the solved state, scaled by the
        # square root of the two forces (the Hertz width's law; the node
        # spacing is the same mesh's), to the 2 digits printed.
        expected = re.search(r"contact resolution expected at [0-9.e+-]+ N m: ([0-9.e+-]+) node\(s\) "
                             r"across the Hertz width of the most loaded pin \(disc (\d+) pin (\d+), "
                             r"(\d+) N in the analytical model\)", log)
        check(expected is not None, "cr%d: no expected resolution before the solve" % cr)
        if expected:
            n_exp, disc, pin, f_exp = expected.groups()
            same = next(r for r in pins if r["disc"] == disc and r["pin"] == pin)
            n_same = float(same["hertz_nodes"]) * (float(f_exp) / float(same["Fn_N"])) ** 0.5
            print("cr%d: expected n %s before the solve (disc %s pin %s, %s N); that pin's n after, at the "
                  "analytical force, %.3g; the most loaded pin's %.3g" % (cr, n_exp, disc, pin, f_exp, n_same, n))
            check(abs(float(n_exp) / n_same - 1) < 0.06,
                  "cr%d: expected n %s, the solved state's %.3g at that pin and force" % (cr, n_exp, n_same))
    ratio = got[1][2] / got[3][2]
    check(3.6 <= ratio <= 4.4, "node spacing at cr1 / cr3 is %.2f, not 4" % ratio)
    check(got[1][0]["mesh_warning"] == "1" and "the contact resolution exceeds" in got[1][1],
          "cr1 without the estimate: not flagged by its resolution")
    check(got[3][0]["mesh_warning"] == "0" and "WARNING" not in got[3][1],
          "cr3 without the estimate: flagged by its resolution")


def check_memory_stop(args, text, coarse, default_log):
    """A refinement that would not fit is not made; the state stays."""
    n0 = int(re.search(r"DoFs (\d+); estimated peak memory", default_log).group(1))
    # The cost model, 2D on 2 ranks: 150 MB a rank + 2.681 kB a DoF
    # (source/stage/cost_estimate.cc).
    limit = 300 + 2.681e-3 * n0 + 1
    s, _, log = run(args.exe, text, args.work, "memory-stop", {},
                    {"CYCLOID_AVAILABLE_MEMORY_MB": "%.3f" % limit})
    check("refinement stopped: the next refinement at the contacts" in log,
          "memory stop: no 'refinement stopped' line")
    check("NOT reached" in log, "memory stop: the target is not reported missed")
    check("no bulk error estimate: the bulk level's refinement" in log,
          "memory stop: the bulk level that does not fit is not said to be skipped")
    check(int(s["dofs"]) == n0, "memory stop: %s DoFs, not the first mesh's %d" % (s["dofs"], n0))
    check(s["mesh_warning"] == "1", "memory stop: the state is not flagged")
    for q in ("K_secant_Nm_per_rad", "K_tangent_Nm_per_rad"):
        a, b = float(s[q]), float(coarse[q])
        check(abs(a - b) <= 1e-9 * abs(b), "memory stop: %s %g, the first mesh gives %g" % (q, a, b))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("prm")
    ap.add_argument("exe")
    ap.add_argument("work")
    args = ap.parse_args()
    os.makedirs(args.work, exist_ok=True)
    text = open(args.prm).read()

    s0, p0, log0 = run(args.exe, text, args.work, "coarse", {"Target accuracy": 0})
    check(s0["mesh_warning"] == "1", "coarse mesh: not flagged (estimates %s)" % estimates(s0))
    check("WARNING" in log0 and "pin" in log0 and "Contact refinements" in log0,
          "coarse mesh: no console warning naming pins and the cure")
    check("Contact refinements raised from 0 to 2" in log0,
          "coarse mesh: the raised refinements are not announced")

    ref = run(args.exe, text, args.work, "reference",
              {"Contact refinements": 2, "Adaptive refinement cycles": 4, "Error estimate": "false"})
    twin = run(args.exe, text, args.work, "reference-twin",
               {"Contact refinements": 3, "Adaptive refinement cycles": 3, "Error estimate": "false"})
    band = errors(twin[:2], ref[:2])
    # The reference shares the bulk mesh (the cells no contact refinement
    # reaches), so it measures the contact discretisation's error alone:
    # the runs compared with it leave the bulk part out of their estimates
    # (run.bulk-estimate compares that part with Q2).
    for cr in (2, 3):
        s, p, log = run(args.exe, text, args.work, "cr%d" % cr,
                        {"Contact refinements": cr, "Target accuracy": 0, "Bulk error estimate": "false"})
        est, true = estimates(s), errors((s, p), ref[:2])
        for q in est:
            print("cr%d %-10s estimate %.3g %%  true %.3g %%  reference band %.3g %%"
                  % (cr, q, 100 * est[q], 100 * true[q], 100 * band[q]))
            check(true[q] <= est[q] + band[q],
                  "cr%d: %s error %.3g above its estimate %.3g" % (cr, q, true[q], est[q]))
            check(cr == 2 or est[q] <= BRACKET * (true[q] + band[q]),
                  "cr%d: %s estimate %.3g more than %g x its error %.3g"
                  % (cr, q, est[q], BRACKET, true[q]))
        if cr == 3:
            check(s["mesh_warning"] == "0", "cr3: flagged (estimates %s)" % est)
            check("WARNING" not in log, "cr3: console warning")

    check_resolution(args, text, ref[:2], band)

    sd, pd, logd = run(args.exe, text, args.work, "default", {})
    check("Target accuracy = auto: 0.02" in logd, "default run: the automatic target is not announced")
    check("of these the bulk mesh's part up to" in logd, "default run: no bulk part in the estimate")
    check(sd["mesh_warning"] == "0", "default run: flagged (estimates %s)" % estimates(sd))
    check(max(estimates(sd).values()) <= 0.02, "default run: estimate %s above 0.02" % estimates(sd))
    for q, e in errors((sd, pd), ref[:2]).items():
        print("default (auto target) %-10s error %.3g %% (estimate %.3g %%)"
              % (q, 100 * e, 100 * estimates(sd)[q]))
        check(e <= 0.02, "default run: %s off by %.3g from the reference" % (q, e))
        check(e <= estimates(sd)[q] + band[q],
              "default run: %s error %.3g above its estimate %.3g" % (q, e, estimates(sd)[q]))

    check_memory_stop(args, text, s0, logd)

    # The default bulk mesh's own part is 0.86 % (doc/error-estimate.md
    # section 5): a 1 % target is one for the contacts, on this bulk.
    st, pt, logt = run(args.exe, text, args.work, "target",
                       {"Target accuracy": 0.01, "Bulk error estimate": "false"})
    check("target accuracy 0.01: reached" in logt, "target run: target not reported reached")
    check(max(estimates(st).values()) <= 0.01, "target run: estimate %s above 0.01" % estimates(st))
    for q, e in errors((st, pt), ref[:2]).items():
        print("target 0.01 %-10s error %.3g %% (estimate %.3g %%)" % (q, 100 * e, 100 * estimates(st)[q]))
        check(e <= 0.01, "target run: %s off by %.3g from the reference" % (q, e))

    # The same run on the distributed mesh, on 3 ranks: its coarser level
    # coarsens and refines back the cells of every rank, and the target
    # refines again, where some rank may hold no cell to refine.
    sdist, pdist, _ = run(args.exe, text, args.work, "target-distributed",
                          {"Target accuracy": 0.01, "Bulk error estimate": "false",
                           "Triangulation": "distributed"},
                          ranks=3)
    check(sdist["dofs"] == st["dofs"], "distributed target run: %s DoFs, not %s"
          % (sdist["dofs"], st["dofs"]))
    same = errors((sdist, pdist), (st, pt))
    same.update({"estimate " + q: abs(e - estimates(st)[q])
                 for q, e in estimates(sdist).items()})
    print("target 0.01, distributed mesh against shared: largest difference %.2g"
          % max(same.values()))
    check(max(same.values()) <= 1e-8, "distributed target run differs: %s" % same)
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
