#!/usr/bin/python3
"""Run = tolerance (issue #50 item 2).

Usage: check_tolerance.py RUN.prm EXECUTABLE WORKDIR

Checks:
- 1 and 2 ranks: the same samples (samples.csv row by row, every column but
  wall_s and peak_memory_MB, to 1e-9 relative: the condensation's parallel
  solve differs in the last digits) and byte-identical extreme-sample files;
- tolerance_summary.csv recomputed from samples.csv (mean, std with n - 1,
  numpy's percentiles, min, max, standard error std / sqrt(n), load_sharing
  = K_secant over sample 0's) to 1e-9;
- the sensitivity's shares of each quantity sum to 1, and the samples vary;
- zero bands: every sample is the nominal stage (load_sharing 1, std 0),
  and the console warns that the bands draw nothing;
- a torque cycle at two crank angles: each sample's backlash (the spread of
  its rotations at zero torque) and transmission error peak-to-peak (the
  spread of its rotation over the crank angles, per torque) recomputed
  from samples.csv give the summary's rows.
"""
import filecmp
import math
import os
import shutil
import sys

import numpy as np

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402
from cycloid_tools import run_cycloid  # noqa: E402

SKIP = {"wall_s", "peak_memory_MB"}
FIGURES = ["K_secant_Nm_per_rad", "K_tangent_Nm_per_rad", "rotation_rad",
           "max_pin_force_N", "pins_in_contact"]


def run(exe, work, name, text, ranks):
    prm = os.path.join(work, name + ".prm")
    with open(prm, "w") as f:
        f.write(text + "\nset Output directory = %s\n" % name)
    r = run_cycloid(ranks, exe, prm, cwd=work, log=os.path.join(work, name + ".log"))
    if r.returncode != 0:
        sys.exit("%s failed:\n%s" % (prm, r.stdout[-3000:]))
    return os.path.join(work, name)


def close(a, b, tol):
    x, y = float(a), float(b)
    if math.isnan(x) or math.isnan(y):
        return math.isnan(x) and math.isnan(y)
    return abs(x - y) <= tol * max(abs(x), abs(y), 1e-300)


def check_ranks(one, two):
    a, b = rows(os.path.join(one, "samples.csv")), rows(os.path.join(two, "samples.csv"))
    check(len(a) == len(b) and len(a) > 0, "samples.csv: %d rows on 1 rank, %d on 2" % (len(a), len(b)))
    for x, y in zip(a, b):
        for k in x:
            if k not in SKIP and not close(x[k], y[k], 1e-9):
                check(False, "sample %s state %s: %s %s on 1 rank, %s on 2"
                      % (x["sample"], x["step"], k, x[k], y[k]))
    names = sorted(os.listdir(os.path.join(one, "extreme-samples")))
    check(len(names) == 9, "extreme-samples/: %s" % names)
    for n in names:
        if n.endswith("-pins.csv") or n.endswith("-discs.csv"):
            check(filecmp.cmp(os.path.join(one, "extreme-samples", n),
                              os.path.join(two, "extreme-samples", n), shallow=False),
                  "extreme-samples/%s differs between 1 and 2 ranks" % n)


def check_summary(out):
    samples = rows(os.path.join(out, "samples.csv"))
    summary = rows(os.path.join(out, "tolerance_summary.csv"))
    states = sorted({(r["crank_deg"], r["torque_Nm"]) for r in samples},
                    key=lambda s: (float(s[0]), float(s[1])))
    for crank, torque in states:
        at = [r for r in samples if r["crank_deg"] == crank and r["torque_Nm"] == torque]
        nominal = [r for r in at if r["sample"] == "0"][0]
        drawn = [r for r in at if r["sample"] != "0"]
        for q in FIGURES + ["load_sharing"]:
            if q == "load_sharing":
                v = np.array([float(r["K_secant_Nm_per_rad"]) for r in drawn]) / float(
                    nominal["K_secant_Nm_per_rad"])
                nom = 1.0
            else:
                v = np.array([float(r[q]) for r in drawn])
                nom = float(nominal[q])
            row = [s for s in summary if s["quantity"] == q
                   and close(s["crank_deg"], crank, 1e-9) and close(s["torque_Nm"], torque, 1e-9)]
            if not check(len(row) == 1, "summary: no row for %s at %s deg, %s N m" % (q, crank, torque)):
                continue
            s = row[0]
            want = {"nominal": nom, "mean": v.mean(), "std": v.std(ddof=1),
                    "p05": np.percentile(v, 5), "p50": np.percentile(v, 50),
                    "p95": np.percentile(v, 95), "min": v.min(), "max": v.max(),
                    "standard_error": v.std(ddof=1) / math.sqrt(len(v))}
            for k, w in want.items():
                # pins_in_contact's std may be exactly 0; 1e-9 of the mean then.
                tol = 1e-9 if w != 0 else 0
                check(abs(float(s[k]) - w) <= max(tol * abs(w), 1e-9 * abs(v.mean())),
                      "summary %s at %s N m: %s = %s, from samples.csv %r" % (q, torque, k, s[k], w))
    return samples, summary


def main():
    prm, exe, work = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3]
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    text = open(prm).read()
    one = run(exe, work, "one", text, 1)
    two = run(exe, work, "two", text, 2)
    check_ranks(one, two)
    samples, _ = check_summary(one)
    for name in ["tolerance_sensitivity.csv", "pin_force_summary.csv"]:
        check(len(rows(os.path.join(one, name))) > 0, name + " is empty")
    shares = {}
    for r in rows(os.path.join(one, "tolerance_sensitivity.csv")):
        shares.setdefault((r["quantity"], r["torque_Nm"]), 0.0)
        shares[(r["quantity"], r["torque_Nm"])] += float(r["share"])
    for k, v in shares.items():
        check(abs(v - 1) < 1e-9, "sensitivity shares of %s sum to %g" % (k, v))
    # The deviations vary the stage.
    k = [float(r["K_secant_Nm_per_rad"]) for r in samples if r["torque_Nm"] == "1000"]
    check(np.std(k) > 0.01 * np.mean(k), "K_secant hardly varies: %s" % np.std(k))

    # Zero bands: every sample is sample 0.
    zero = text
    for band in ["Pin position", "Pin radius", "Eccentricity", "Disc angle", "Profile"]:
        zero += "\nsubsection Tolerance study\n  set %s tolerance = 0\nend\n" % band
    zero += "subsection Tolerance study\n  set Number of samples = 5\nend\n"
    z = run(exe, work, "zero", zero, 1)
    check("WARNING: every band of Tolerance study is 0" in open(z + ".log").read(),
          "zero bands: no warning that every sample is the mean stage")
    zs = rows(os.path.join(z, "samples.csv"))
    check(len(zs) == 12, "zero bands: %d rows in samples.csv, 12 expected" % len(zs))
    for r in zs:
        r0 = [x for x in zs if x["sample"] == "0" and x["step"] == r["step"]][0]
        for k in r:
            check(k in SKIP | {"sample"} or r[k] == r0[k],
                  "zero bands: sample %s %s = %s, sample 0 %s" % (r["sample"], k, r[k], r0[k]))
    for s in rows(os.path.join(z, "tolerance_summary.csv")):
        if s["quantity"] == "load_sharing":
            check(float(s["min"]) == 1 and float(s["max"]) == 1,
                  "zero bands: load_sharing %s ... %s" % (s["min"], s["max"]))
        # The mean of equal numbers may differ from them in the last bit.
        check(float(s["std"]) <= 1e-12 * abs(float(s["mean"])),
              "zero bands: %s std %s" % (s["quantity"], s["std"]))
    check_cycle(exe, work, text)
    return verdict()


def check_cycle(exe, work, text):
    cycle = text + """
subsection Loading
  set Torque cycle       = true
  set Rated torque       = 1000
  set Torque cycle steps = 4
  set Crank angle        = 0
  set Number of phases   = 2
end
subsection Tolerance study
  set Number of samples = 12
  set Sensitivity       = false
end
"""
    out = run(exe, work, "cycle", cycle, 1)
    samples = rows(os.path.join(out, "samples.csv"))
    summary = rows(os.path.join(out, "tolerance_summary.csv"))
    ids = sorted({int(r["sample"]) for r in samples})
    cranks = sorted({float(r["crank_deg"]) for r in samples})
    torques = sorted({float(r["torque_Nm"]) for r in samples})

    def of(sample, pred):
        return [float(r["rotation_rad"]) for r in samples if int(r["sample"]) == sample and pred(r)]

    arcmin, arcsec = 180 * 60 / math.pi, 180 * 3600 / math.pi
    for crank in cranks:
        width = {s: arcmin * (max(v) - min(v)) for s in ids for v in [of(
            s, lambda r: float(r["crank_deg"]) == crank and float(r["torque_Nm"]) == 0)]}
        row = [x for x in summary if x["quantity"] == "backlash_arcmin"
               and close(x["crank_deg"], crank, 1e-9)]
        if check(len(row) == 1, "cycle: no backlash row at %g deg" % crank):
            drawn = np.array([width[s] for s in ids if s != 0])
            check(close(row[0]["nominal"], width[0], 1e-8), "cycle: backlash nominal %s against %r"
                  % (row[0]["nominal"], width[0]))
            check(close(row[0]["mean"], drawn.mean(), 1e-8), "cycle: backlash mean %s against %r"
                  % (row[0]["mean"], drawn.mean()))
        for q in ["lost_motion_arcmin", "torsional_rigidity_Nm_per_arcmin"]:
            check(sum(x["quantity"] == q and close(x["crank_deg"], crank, 1e-9) for x in summary) == 1,
                  "cycle: no %s row at %g deg" % (q, crank))
    def first(sample, crank, torque):
        # The cycle's first state of that torque (zero torque is passed from
        # both sides, the two ends of the backlash).
        at = [r for r in samples if int(r["sample"]) == sample and float(r["crank_deg"]) == crank
              and float(r["torque_Nm"]) == torque]
        return float(min(at, key=lambda r: int(r["step"]))["rotation_rad"])

    for torque in torques:
        pp = np.array([arcsec * (max(v) - min(v)) for s in ids if s != 0
                       for v in [[first(s, c, torque) for c in cranks]]])
        row = [x for x in summary if x["quantity"] == "transmission_error_pp_arcsec"
               and close(x["torque_Nm"], torque, 1e-9)]
        if check(len(row) == 1, "cycle: %d TE rows at %g N m" % (len(row), torque)):
            check(close(row[0]["max"], pp.max(), 1e-8), "cycle: TE p-p max %s against %r"
                  % (row[0]["max"], pp.max()))


if __name__ == "__main__":
    sys.exit(main())
