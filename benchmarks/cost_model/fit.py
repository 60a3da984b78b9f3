#!/usr/bin/env python3
"""Fit the cost model of source/stage/cost_estimate.cc to the measured runs.

Reads doc/ladder/ladder.csv (one state per run, seed case, idle machine,
DoFs, program_wall_s = the state's solve, peak_memory_MB = VmHWM summed
over the ranks) and prints, per scene family (2D; 3D one disc; 3D two
discs):

* peak memory at 2 ranks = 300 MB + a * DoFs, a by least squares with the
  intercept fixed at 150 MB per rank (the analytic runs' 151 MB);
* the per-DoF memory on 1 rank relative to 2 (1- and 2-rank pairs);
* time of a state at 2 ranks = c * DoFs^p, a log-log least-squares fit
  over the a-priori meshes (no adaptive cycles);
* each run's error against the fit, and the rms error.

Usage: python3 benchmarks/cost_model/fit.py [doc/ladder/ladder.csv]
"""
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import fit_power, read_csv  # noqa: E402


def rms(errors):
    return math.sqrt(sum(e * e for e in errors) / len(errors))


def main(path):
    families = {}
    for r in read_csv(path):
        if r["dofs"] == "0" or not r["peak_memory_MB"]:
            continue  # analytic rows; contact-speed rows carry no memory
        family = "2D" if r["scene"].startswith("2D") else r["scene"]
        families.setdefault(family, []).append(r)
    for family, rows in families.items():
        two = [r for r in rows if r["ranks"] == "2"]
        n = [float(r["dofs"]) for r in two]
        m = [float(r["peak_memory_MB"]) for r in two]
        a = sum(x * (y - 300) for x, y in zip(n, m)) / sum(x * x for x in n)
        err_m = [100 * ((300 + a * x) / y - 1) for x, y in zip(n, m)]
        print(f"{family}: memory 2 ranks = 300 MB + {a * 1e3:.3f} kB/DoF; "
              f"{len(two)} runs, error {min(err_m):+.0f} .. {max(err_m):+.0f} %, rms {rms(err_m):.0f} %")
        ones = [r for r in rows if r["ranks"] == "1"]
        if ones:
            ratios = [(float(r["peak_memory_MB"]) - 150) / float(r["dofs"]) / a for r in ones]
            print(f"  1 rank: per-DoF memory {min(ratios):.2f} .. {max(ratios):.2f} of 2 ranks")
        apriori = [r for r in two if "+ad" not in r["mesh"]]
        n = [float(r["dofs"]) for r in apriori]
        t = [float(r["program_wall_s"]) for r in apriori]
        c, p = fit_power(n, t)
        err_t = [100 * (c * x ** p / y - 1) for x, y in zip(n, t)]
        print(f"  time 2 ranks = {c:.4g} DoFs^{p:.3f} s; {len(apriori)} runs, "
              f"error {min(err_t):+.0f} .. {max(err_t):+.0f} %, rms {rms(err_t):.0f} %")
        for r, e in zip(apriori, err_t):
            print(f"    {r['mesh']:22s} {int(float(r['dofs'])):8d} DoFs {float(r['program_wall_s']):8.2f} s  fit {e:+4.0f} %")


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else "doc/ladder/ladder.csv")
