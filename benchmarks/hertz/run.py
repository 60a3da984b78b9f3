#!/usr/bin/python3
"""Hertz verification study of the FE contact solver (doc/hertz.md).

Elastic cylinder (r1 = 10 mm, E1 = 30000 MPa, nu1 = 0.25) on a convex
cylinder or in a concave seat (r2 = 13 mm, E2 = 29120 MPa, nu2 = 0.3), plane
strain, against Hertz's closed form. Runs `hertz-study` for

  * convex,  F = 200 N/mm  (a/R* = 0.05)  mortar Q1, mortar Q2, node-to-surface Q1
  * convex,  F = 3200 N/mm (a/R* = 0.21)  the same three
  * concave, F = 100 N/mm                 the same three

with GLOBAL = 3 global refinements and contact refinements 0, 1, 2, ...
up to the finest level that took < ~60 s on the 2-core development machine
(table FINEST; with --max-seconds S instead: until the next level would take
longer than S, its time predicted as --growth x the last level's). Each
level is its own serial process; the nodal contact pressures (printed by
the library when CYCLOID_DEBUG is set) are kept too. Then one 2-rank run
per MPI_CHECKS entry is compared with the serial run of the same level.

Writes doc/hertz/hertz.csv (one row per run), doc/hertz/profiles.csv
(nodal pressures), doc/hertz/mpi_check.csv, doc/hertz/hertz_convergence.png,
doc/hertz/hertz_pressure.png and prints a summary.

Usage: benchmarks/hertz/run.py [--exe build/hertz-study] [--max-seconds 60]
       benchmarks/hertz/run.py --plot-only      (re-analyse the CSV files)
"""
import argparse
import csv
import math
import os
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
OUT = os.path.join(ROOT, "doc", "hertz")
MORTAR, NTS = "mortar", "node-to-surface"
# (seat, force N/mm, formulation, degree)
LINES = [(seat, force, form, deg)
         for seat, force in [("convex", 200), ("convex", 3200), ("concave", 100)]
         for form, deg in [(MORTAR, 1), (MORTAR, 2), (NTS, 1)]]
# Finest contact level per line: the last one under ~60 s (2 shared cores;
# the next level takes 4-6 x longer).
FINEST = {("convex", 200, MORTAR, 1): 8, ("convex", 200, MORTAR, 2): 6, ("convex", 200, NTS, 1): 8,
          ("convex", 3200, MORTAR, 1): 6, ("convex", 3200, MORTAR, 2): 4, ("convex", 3200, NTS, 1): 6,
          ("concave", 100, MORTAR, 1): 6, ("concave", 100, MORTAR, 2): 5, ("concave", 100, NTS, 1): 6}
# 2-rank checks: (seat, force, formulation, degree, contact level)
MPI_CHECKS = [("convex", 3200, MORTAR, 1, 5), ("convex", 3200, MORTAR, 2, 3),
              ("convex", 3200, NTS, 1, 4), ("concave", 100, MORTAR, 1, 5)]
FLOAT_COLS = ["force_N_per_mm", "h_contact_mm", "a_fe_mm", "a_exact_mm", "a_error", "p0_fe_MPa",
              "p0_exact_MPa", "p0_error", "force_balance_error", "wall_s"]
INT_COLS = ["degree", "global", "contact", "dofs", "n_active", "iterations"]
BALANCE_TOL = 1e-9   # |force_balance_error| above this is reported


def key(row):
    return (row["seat"], int(float(row["force_N_per_mm"])), row["formulation"], int(row["degree"]))


def label(k):
    seat, force, form, deg = k
    return f"{seat} F={force} {'mortar' if form == MORTAR else 'NTS'} Q{deg}"


def typed(row):
    r = dict(row)
    for c in FLOAT_COLS:
        r[c] = float(r[c])
    for c in INT_COLS:
        r[c] = int(r[c])
    return r


def run_level(exe, seat, force, form, deg, glob, level, ranks=1):
    env = {"CYCLOID_FORMULATION": NTS if form == NTS else None,
           "CYCLOID_DEBUG": "1" if ranks == 1 else None}
    p = run_cycloid(None if ranks == 1 else ranks, exe, seat, force, deg, glob, level, env=env)
    if p.returncode != 0:
        sys.exit(f"failed ({p.returncode}): {' '.join(p.args)}\n{p.stderr[-2000:]}")
    raw = read_csv(p.stdout.strip().splitlines())[0]
    row = typed(raw)
    profile = []
    for line in p.stderr.splitlines():
        try:
            vals = [float(x) for x in line.split()]
        except ValueError:
            continue
        if len(vals) == 4:
            profile.append(vals)  # arc s, pressure lambda/weight, lambda, weight
    return row, raw, sorted(profile)


def run_all(args):
    rows, raws, profiles = [], [], []
    for seat, force, form, deg in LINES:
        finest = FINEST[(seat, force, form, deg)] if args.max_seconds is None else args.max_level
        for level in range(finest + 1):
            row, raw, prof = run_level(args.exe, seat, force, form, deg, args.glob, level)
            rows.append(row)
            raws.append(raw)
            for s, p, lam, w in prof:
                profiles.append([seat, force, form, deg, level, s, p, lam, w])
            print(f"{label((seat, force, form, deg))} level {level}: h {row['h_contact_mm']:.4g} mm, "
                  f"active {row['n_active']}, a err {row['a_error']:+.4%}, p0 err {row['p0_error']:+.4%}, "
                  f"balance {row['force_balance_error']:.1e}, dofs {row['dofs']}, {row['wall_s']:.1f} s",
                  flush=True)
            if args.max_seconds is not None and row["wall_s"] * args.growth > args.max_seconds:
                break
    return rows, raws, profiles


def mpi_checks(args, rows):
    out = []
    serial = {(key(r), r["contact"]): r for r in rows}
    for seat, force, form, deg, level in MPI_CHECKS:
        k = (seat, force, form, deg)
        r1 = serial.get((k, level))
        if r1 is None:
            r1, _, _ = run_level(args.exe, seat, force, form, deg, args.glob, level)
        r2, _, _ = run_level(args.exe, seat, force, form, deg, args.glob, level, ranks=2)
        for ranks, r in [(1, r1), (2, r2)]:
            out.append({"seat": seat, "force_N_per_mm": force, "formulation": form, "degree": deg,
                        "contact": level, "ranks": ranks, "dofs": r["dofs"], "n_active": r["n_active"],
                        "iterations": r["iterations"], "a_error": r["a_error"], "p0_error": r["p0_error"],
                        "force_balance_error": r["force_balance_error"], "wall_s": r["wall_s"]})
    return out


def write_csv(path, header, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(header)
        w.writerows(rows)


# ---------------------------------------------------------------- analysis
def usable(rows):
    """Rows with at least two active nodes (a defined spacing)."""
    return [r for r in rows if r["n_active"] >= 2 and r["h_contact_mm"] < 1e100]


def fit_range(pts):
    """Pre-asymptotic range of one line (points (h, e) with >= 3 active nodes,
    coarse to fine): the levels from the coarsest on whose |error| is still
    above twice the finest level's |error| (the plateau: model error plus
    what the finest mesh leaves); at least the first two. Returns the points
    (h, |e|) used ([] if fewer than 3 levels)."""
    if len(pts) < 3:
        return []
    n = 0
    while n < len(pts) - 1 and abs(pts[n][1]) > 2 * abs(pts[-1][1]):
        n += 1
    return [(h, abs(e)) for h, e in pts[:max(n, 2)]]


def self_range(pts):
    """Self-convergence: |e_h - e_finest| for all but the finest level."""
    if len(pts) < 3:
        return []
    return [(h, abs(e - pts[-1][1])) for h, e in pts[:-1]]


def order(used):
    h = np.log([u[0] for u in used])
    e = np.log([max(u[1], 1e-16) for u in used])
    return float(np.polyfit(h, e, 1)[0])


def oscillation(prof, a):
    """Largest |p_i - (p_{i-1} + p_{i+1})/2| over the nodes with |s_i| <= 0.5 a
    (relative to the largest nodal pressure): the node-to-node jump of the
    nodal pressures. A smooth Hertz ellipse gives about (h/a)^2/2 here."""
    prof = sorted(prof)
    s = np.array([p[0] for p in prof])
    p = np.array([p[1] for p in prof])
    if len(p) < 5:
        return math.nan
    jumps = [abs(p[i] - 0.5 * (p[i - 1] + p[i + 1])) for i in range(1, len(p) - 1) if abs(s[i]) <= 0.5 * a]
    return max(jumps) / p.max() if jumps else math.nan


def analyse(rows, profiles, checks):
    lines = {}
    for r in rows:
        lines.setdefault(key(r), []).append(r)
    prof = {}
    for p in profiles:
        k = (p["seat"], int(float(p["force_N_per_mm"])), p["formulation"], int(p["degree"]), int(p["contact"]))
        prof.setdefault(k, []).append((float(p["s_mm"]), float(p["p_MPa"])))

    # ---- convergence figure
    colours = {("convex", 200): "tab:blue", ("convex", 3200): "tab:red", ("concave", 100): "tab:green"}
    styles = {(MORTAR, 1): ("-", "o"), (MORTAR, 2): ("--", "s"), (NTS, 1): (":", "^")}
    fig, axes = plt.subplots(1, 2, figsize=(13, 5.5), sharex=True)
    fits = {}
    for k, rs in lines.items():
        rs = sorted(usable(rs), key=lambda r: -r["h_contact_mm"])
        if not rs:
            continue
        h = np.array([r["h_contact_mm"] for r in rs])
        for ax, col in zip(axes, ["a_error", "p0_error"]):
            e = np.array([r[col] for r in rs])
            ls, mk = styles[k[2:]]
            lab = label(k)
            if k[2] == MORTAR:
                pts = [(r["h_contact_mm"], r[col]) for r in rs if r["n_active"] >= 3]
                used, selfc = fit_range(pts), self_range(pts)
                if used:
                    p, q = order(used), order(selfc)
                    fits[(k, col)] = (p, used, q, selfc)
                    lab += f": order {p:.1f} ({len(used)} pts), self {q:.1f}"
            ax.loglog(h, np.maximum(np.abs(e), 1e-6), ls=ls, marker=mk, color=colours[k[:2]], label=lab,
                      mfc="none" if k[2] == NTS else None)
    for ax, name in zip(axes, ["half-width a", "peak pressure p0"]):
        ax.axhline(0.01, color="grey", lw=0.8, ls="-.")
        href = np.array([0.02, 0.32])
        ax.loglog(href, 0.05 * (href / href[-1]) ** 2, color="k", lw=1.2, label="slope 2 (reference)")
        ax.set_xlabel("contact node spacing h [mm]")
        ax.set_ylabel(f"|relative error of {name}| vs Hertz")
        ax.set_title(f"{name} (GLOBAL = 3)")
        ax.grid(True, which="both", alpha=0.3)
        ax.invert_xaxis()
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "hertz_convergence.png"), dpi=130)
    plt.close(fig)

    # ---- pressure profiles at the finest level, F = 3200 and concave
    fig, axes = plt.subplots(1, 3, figsize=(15, 4.5))
    for ax, case in zip(axes, [("convex", 200), ("convex", 3200), ("concave", 100)]):
        for form, deg in [(MORTAR, 1), (MORTAR, 2), (NTS, 1)]:
            k = case + (form, deg)
            if k not in lines or not usable(lines[k]):
                continue
            fin = max(usable(lines[k]), key=lambda r: r["contact"])
            pr = sorted(prof.get(k + (fin["contact"],), []))
            if not pr:
                continue
            a, p0 = fin["a_exact_mm"], fin["p0_exact_MPa"]
            ls, mk = styles[(form, deg)]
            ax.plot([s / a for s, _ in pr], [p / p0 for _, p in pr], ls=ls, marker=mk, ms=3,
                    label=f"{label(k).split(' ', 2)[2]}, level {fin['contact']}")
        x = np.linspace(-1, 1, 201)
        ax.plot(x, np.sqrt(1 - x ** 2), color="k", lw=0.8, label="Hertz")
        ax.set_title(f"{case[0]} F = {case[1]} N/mm: nodal pressure (finest level)")
        ax.set_xlabel("s / a_Hertz")
        ax.set_ylabel("p / p0_Hertz")
        ax.grid(True, alpha=0.3)
        ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "hertz_pressure.png"), dpi=130)
    plt.close(fig)

    # ---- summary
    bad = [r for r in rows if abs(r["force_balance_error"]) > BALANCE_TOL]
    print("\n== finest level per line (GLOBAL = 3) ==")
    print(f"{'line':30s} {'lvl':>3s} {'h mm':>8s} {'a/h':>5s} {'dofs':>7s} {'a err':>9s} {'p0 err':>9s}"
          f" {'osc':>6s} {'wall s':>7s}")
    for k in LINES:
        if k not in lines or not usable(lines[k]):
            continue
        fin = max(usable(lines[k]), key=lambda r: r["contact"])
        osc = oscillation(prof.get(k + (fin["contact"],), []), fin["a_fe_mm"])
        print(f"{label(k):30s} {fin['contact']:3d} {fin['h_contact_mm']:8.4f} "
              f"{fin['a_exact_mm'] / fin['h_contact_mm']:5.1f} {fin['dofs']:7d} {fin['a_error']:+9.3%} "
              f"{fin['p0_error']:+9.3%} {osc:6.2%} {fin['wall_s']:7.1f}")
    print("\n== fitted orders (mortar): |error vs Hertz| over the pre-asymptotic range;"
          " self = |value - finest value| over all coarser levels ==")
    for (k, col), (p, used, q, selfc) in sorted(fits.items()):
        print(f"{label(k):30s} {col:9s} order {p:5.2f} over h = {used[0][0]:.3g} ... {used[-1][0]:.3g} mm"
              f" ({len(used)} points); self {q:5.2f} over h = {selfc[0][0]:.3g} ... {selfc[-1][0]:.3g} mm")
    print("\n== node-to-node pressure oscillation (max |p_i - mean of neighbours| / max p, |s| <= 0.5 a) ==")
    for k in LINES:
        if k not in lines:
            continue
        vals = []
        for r in sorted(usable(lines[k]), key=lambda r: r["contact"]):
            o = oscillation(prof.get(k + (r["contact"],), []), r["a_fe_mm"])
            if not math.isnan(o):
                vals.append(f"L{r['contact']} {o:.2%}")
        print(f"{label(k):30s} " + ", ".join(vals))
    if checks:
        print("\n== 1 vs 2 MPI ranks ==")
        for i in range(0, len(checks), 2):
            c1, c2 = checks[i], checks[i + 1]
            da = abs(float(c1["a_error"]) - float(c2["a_error"])) / (1 + float(c1["a_error"]))
            dp = abs(float(c1["p0_error"]) - float(c2["p0_error"])) / (1 + float(c1["p0_error"]))
            # resolution of the printed (6 significant digits) relative errors
            res = max(10 ** (math.floor(math.log10(abs(float(c[e])))) - 5)
                      for c in (c1, c2) for e in ("a_error", "p0_error"))
            k = (c1["seat"], int(float(c1["force_N_per_mm"])), c1["formulation"], int(c1["degree"]))
            print(f"{label(k):30s} level {c1['contact']}: a rel. diff {da:.1e}, p0 rel. diff {dp:.1e} "
                  f"(printed resolution {res:.0e}), "
                  f"iterations {c1['iterations']}/{c2['iterations']}, active {c1['n_active']}/{c2['n_active']}")
    print(f"\nforce balance: max |error| {max(abs(r['force_balance_error']) for r in rows):.1e}"
          + (f"; {len(bad)} rows above {BALANCE_TOL:g}" if bad else ""))


def main():
    global OUT
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "hertz-study"), help="hertz-study binary")
    ap.add_argument("--global", dest="glob", type=int, default=3, help="global refinements (3)")
    ap.add_argument("--max-seconds", type=float, default=None,
                    help="adaptive: stop when the next level is predicted to take longer than this "
                         "(default: the levels of table FINEST)")
    ap.add_argument("--growth", type=float, default=5,
                    help="predicted time ratio of the next contact level to the last one (5)")
    ap.add_argument("--max-level", type=int, default=9, help="hard cap on the contact level with --max-seconds (9)")
    ap.add_argument("--no-mpi", action="store_true", help="skip the 2-rank checks")
    ap.add_argument("--out", default=OUT, help="output directory (doc/hertz)")
    ap.add_argument("--plot-only", action="store_true", help="re-analyse doc/hertz/*.csv without running")
    args = ap.parse_args()
    OUT = args.out
    os.makedirs(OUT, exist_ok=True)
    p_rows, p_prof, p_mpi = (os.path.join(OUT, n) for n in ["hertz.csv", "profiles.csv", "mpi_check.csv"])
    if not args.plot_only:
        rows, raws, profiles = run_all(args)
        header = list(raws[0].keys())
        write_csv(p_rows, header, [[r[c] for c in header] for r in raws])
        write_csv(p_prof, ["seat", "force_N_per_mm", "formulation", "degree", "contact", "s_mm", "p_MPa",
                           "lambda_N_per_mm", "weight_mm"], profiles)
        if not args.no_mpi:
            checks = mpi_checks(args, rows)
            write_csv(p_mpi, list(checks[0].keys()), [list(c.values()) for c in checks])
        print("written", p_rows, p_prof, p_mpi if not args.no_mpi else "")
    rows = [typed(r) for r in read_csv(p_rows)]
    profiles = read_csv(p_prof)
    checks = read_csv(p_mpi) if os.path.exists(p_mpi) and (args.plot_only or not args.no_mpi) else []
    analyse(rows, profiles, checks)


if __name__ == "__main__":
    main()
