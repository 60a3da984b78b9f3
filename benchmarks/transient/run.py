#!/usr/bin/python3
"""Stability study of the transient schemes (issue #5 item 5).

Where does each time scheme fail, and how does the program notice?
Parts (run all but long-example, or some with --part a,b):

  bar         build/bar-impact (elastic bar against a rigid wall, 1D closed
              form: force rho c h v0, contact time 2L/c, rebound -v0):
              newmark, contact-stabilised, generalized-alpha with
              rho_inf = 0.5, 0.8, 1.0 at CFL 0.25 ... 4 (40 cells) and at
              20/40/80 cells (CFL 1): energy error, energy gain, contact-force
              oscillation, contact-time and rebound errors, penetration.
  cycloid     tests/runs/transient.prm (2D seed, elastic pins, crank at
              9000 deg/s, 300 N m ramped over 8e-5 s) with the three schemes
              at dt 4e-5, 2e-5, 1e-5 to 2.4e-4 s: relative energy balance
              error, its convergence with dt, oscillation of the largest pin
              force, active-set and CG iterations, wall time. Controls:
              contact-stabilised and generalized-alpha with the crank held
              (dt 4e-5), and an impact (modified profile, 1000 N m at once,
              to 3.6e-4 s) with newmark and contact-stabilised.
  slow        prm/phase-sweep-2d.prm scene at 1000 N m (Contact refinements
              1 by default, --slow-refinements 2 for the prm's own): Run =
              phase-sweep over one mesh period (21 phases) against a slow
              damped contact-stabilised transient (100 steps of 1e-4 s per
              mesh period, Rayleigh mass damping 2e4 1/s, ramp 5 steps; half a
              period by default, --slow-full for the whole one after a
              10-step ramp): K_secant(crank angle).
  active-set  tests/runs/quasi-static-elastic.prm scene (torques 100, 1000:
              cold start from the analytical model, then warm start) at
              Contact refinements 0..3, modified and seed profile, and one
              node-to-surface case: active-set iterations (and the active-set
              sizes per iteration, from CYCLOID_DEBUG).
  solver      the same scene, Solver/Linear solver = cg-amg against
              cg-amg-translations at Contact refinements 0..3: CG iterations
              per solve (2 solves per active-set iteration).

  long        prm/transient-2d.prm on a coarser contact mesh (Contact
              refinements 1, 85 k DoFs): Newmark through 10 mesh periods
              (1000 steps of 1e-5 s at 1500 rpm) against contact-stabilised
              through 3 (its drift shows by then): the relative energy balance
              error per period, its drift, active-set iterations and time per
              step (issue #15 item 6).
  long-example the example as shipped (Contact refinements 3; along a
              10-period sweep 417 k DoFs), Newmark through 10 mesh periods:
              the same figures (long-example.csv, -series.csv,
              -balance.png); about 2 h on 2 cores condensing every set
              (5 s a step), 3.1-3.7 s a step with the Schur complement,
              the default (--timeout 7200).
  example     prm/transient-2d.prm as shipped, cut to 30 steps (10 after
              the ramp): contact-stabilised with CG+AMG (the earlier
              setting), Newmark with CG+AMG, Newmark with the direct
              solver condensing and factorising every active set, and
              Newmark with the direct solver through the contact Schur
              complement on one factorisation (shipped): time per step
              after the ramp, active-set and CG iterations, and the
              figures that must not change.
Writes CSVs and PNGs into doc/transient/ (or --out) and prints a summary
with markdown tables. FE runs go to --work (default /tmp/cycloid-stability),
one directory per case; a case whose prm is unchanged is not run again
unless --rerun (so the figures can be redone without computing).
--quick runs fewer cases (bar at CFL 1, cycloid at dt 2e-5, a short slow
run, Contact refinements 0 and 1) and writes to <work>/quick-out.

Usage:
  /usr/bin/python3 benchmarks/transient/run.py [--part bar,cycloid,...]
      [--quick] [--ranks 2] [--work DIR] [--out DIR] [--rerun]
      [--slow-full] [--timeout 1800]
"""
import argparse
import csv
import json
import math
import os
import re
import sys
import time
from pathlib import Path

import numpy as np

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import mpirun_command, read_csv, run_cycloid, walk_prm  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PARTS = ["bar", "cycloid", "slow", "active-set", "solver", "long", "long-example", "example"]
SCHEMES = ["newmark", "contact-stabilised", "generalized-alpha"]
COLOURS = {"newmark": "tab:red", "contact-stabilised": "tab:blue",
           "generalized-alpha": "tab:green", "ga0.5": "tab:olive",
           "ga0.8": "tab:green", "ga1.0": "tab:purple"}


# ---------------------------------------------------------------- helpers
def log(*a):
    print(*a, flush=True)


def run_command(ranks, exe, *args, env=None, timeout=1800):
    """Run exe with args on ranks MPI ranks (None: without mpirun); if the
    executable is missing or busy (being relinked), wait 30 s and retry (up
    to 10 times). Returns (rc, stdout, stderr, wall); rc 124 at the timeout."""
    for attempt in range(10):
        if not os.access(exe, os.X_OK):
            log(f"    {exe} not there (relinking?), waiting 30 s")
            time.sleep(30)
            continue
        p = run_cycloid(ranks, exe, *args, env=env, timeout=timeout)
        if p.timed_out:
            return 124, p.stdout or "", (p.stderr or "") + "\ntimeout", p.wall_s
        busy = re.search(r"Text file busy|No such file or directory.*cycloid|execvp|not found", p.stderr or "")
        if p.returncode in (126, 127) or (p.returncode != 0 and busy and not p.stdout.strip()):
            log(f"    executable busy or missing (rc {p.returncode}), waiting 30 s")
            time.sleep(30)
            continue
        return p.returncode, p.stdout, p.stderr, p.wall_s
    raise RuntimeError("executable unavailable: " + " ".join(mpirun_command(ranks, exe, *args)))


def error_message(text):
    """The program's error message (the ExcMessage text) from its output."""
    lines = [l.strip() for l in text.splitlines()]
    for i, l in enumerate(lines):
        if l.startswith("Additional information:"):
            msg = []
            for m in lines[i + 1:]:
                if not m or m.startswith("Stacktrace") or m.startswith("---"):
                    break
                msg.append(m)
            return " ".join(msg)
    for l in lines:
        if re.search(r"error|Exception|what\(\)", l, re.I) and "mpirun" not in l.lower():
            return l
    return lines[-1] if lines else ""


def edit_prm(base, overrides=None, deletes=()):
    """Text of the prm file `base` with `set` entries replaced/added
    (overrides: {(section, key): value}, section "" = top level) and removed
    (deletes: [(section, key)])."""
    overrides = dict(overrides or {})
    used, out = set(), []
    for raw, section, key, _ in walk_prm(open(base)):
        if key is not None:
            sk = (section[-1] if section else "", key)
            if sk in deletes:
                continue
            if sk in overrides:
                indent = raw[:len(raw) - len(raw.lstrip())]
                out.append(f"{indent}set {key} = {overrides[sk]}\n")
                used.add(sk)
                continue
        out.append(raw)
    rest = {sk: v for sk, v in overrides.items() if sk not in used}
    top = [f"set {k} = {v}\n" for (s, k), v in rest.items() if s == ""]
    text = "".join(top) + "".join(out)
    for s in dict.fromkeys(s for (s, k) in rest if s):
        text += f"subsection {s}\n" + "".join(
            f"  set {k} = {v}\n" for (ss, k), v in rest.items() if ss == s) + "end\n"
    return text


class FE:
    """One cycloid-contact run per case directory, cached by prm text."""

    def __init__(self, args):
        self.args = args
        self.exe = args.exe

    def run(self, name, base, overrides=None, deletes=(), debug=False):
        d = os.path.join(self.args.work, name)
        os.makedirs(d, exist_ok=True)
        ov = dict(overrides or {})
        ov[("", "Output directory")] = os.path.join(d, "out")
        text = edit_prm(base, ov, deletes)
        prm = os.path.join(d, "case.prm")
        meta_file = os.path.join(d, "meta.json")
        if not self.args.rerun and os.path.exists(meta_file) and os.path.exists(prm) \
                and open(prm).read() == text:
            meta = json.load(open(meta_file))
            if meta.get("debug", False) == debug:
                log(f"  {name}: cached (rc {meta['rc']}, {meta['wall_s']:.1f} s)")
                meta["dir"] = os.path.join(d, "out")
                return meta
        open(prm, "w").write(text)
        env = {"CYCLOID_DEBUG": "1"} if debug else None
        log(f"  {name}: running ...")
        ranks = self.args.ranks if self.args.ranks > 1 else None  # 1 rank: without mpirun
        rc, out, err, wall = run_command(ranks, self.exe, prm, env=env, timeout=self.args.timeout)
        open(os.path.join(d, "stdout.log"), "w").write(out)
        open(os.path.join(d, "stderr.log"), "w").write(err)
        meta = {"rc": rc, "wall_s": wall, "debug": debug,
                "error": error_message(out + "\n" + err) if rc != 0 else "",
                "warnings": [l.strip() for l in (out + err).splitlines() if "warning" in l.lower()],
                "exe_mtime": os.path.getmtime(self.exe),
                "command": " ".join(mpirun_command(ranks, self.exe, prm))}
        json.dump(meta, open(meta_file, "w"), indent=1)
        log(f"  {name}: rc {rc}, {wall:.1f} s" + (f" -- {meta['error']}" if rc else ""))
        meta["dir"] = os.path.join(d, "out")
        return meta


def write_csv(path, rows, keys=None):
    if not rows:
        return
    keys = keys or list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys, extrasaction="ignore")
        w.writeheader()
        for r in rows:
            w.writerow({k: fmt(r.get(k, "")) for k in keys})
    log(f"  wrote {os.path.relpath(path, ROOT)}")


def fmt(v, digits=4):
    if isinstance(v, float):
        if math.isnan(v):
            return "nan"
        if v == 0:
            return "0"
        if abs(v) >= 1e5 or abs(v) < 1e-3:
            return f"{v:.{digits - 1}e}"
        return f"{v:.{digits}g}"
    return str(v)


def md_table(rows, cols, heads=None):
    heads = heads or cols
    s = "| " + " | ".join(heads) + " |\n|" + "---|" * len(cols) + "\n"
    for r in rows:
        s += "| " + " | ".join(fmt(r.get(c, "")) for c in cols) + " |\n"
    return s


# ---------------------------------------------------------------- part 1: bar
def bar_run(args, scheme, cells, cfl, rho=None):
    cmd = [scheme, str(cells), str(cfl)] + ([str(rho)] if rho is not None else [])
    key = f"bar-{scheme}-{cells}-{cfl}" + (f"-{rho}" if rho is not None else "")
    cache = os.path.join(args.work, "bar", key + ".csv")
    os.makedirs(os.path.dirname(cache), exist_ok=True)
    if not args.rerun and os.path.exists(cache):
        out, wall = open(cache).read(), float("nan")
    else:
        rc, out, err, wall = run_command(None, args.bar, *cmd, timeout=args.timeout)
        if rc != 0:
            raise RuntimeError(f"{' '.join([args.bar] + cmd)} failed: {err}")
        open(cache, "w").write(out)
    lines = out.splitlines()
    head = lines[0]
    num = lambda pat: float(re.search(pat + r" ([-0-9.e+]+)", head).group(1))  # noqa: E731
    meta = {"dt": num(r"dt"), "tc": num(r"2L/c"), "f": num(r"v0"), "E0": num(r"E0"), "c": num(r", c")}
    rows = read_csv(lines[1:])
    data = {k: np.array([float(r[k]) for r in rows]) for k in rows[0]}
    return meta, data, wall


def bar_metrics(meta, d):
    dt, tc, f1, e0 = meta["dt"], meta["tc"], meta["f"], meta["E0"]
    t, F, act = d["time_s"], d["contact_force_N_per_mm"], d["n_active"] > 0
    during = (t <= tc - dt * (1 - 1e-6))  # steps wholly inside the contact period
    Fd = F[during]
    switches = int(np.sum(act[during][1:] != act[during][:-1]))
    t_last = t[act].max() if act.any() else 0.
    bal = d["balance_error_Nmm"] / e0
    return {
        "dt_s": dt, "steps": len(t),
        "final_energy_error": bal[-1],
        "max_balance_error": bal.max(),
        "min_energy_error": bal.min(),
        "mean_force_error": Fd.mean() / f1 - 1,
        "force_std_over_mean": Fd.std() / Fd.mean() if Fd.mean() != 0 else float("nan"),
        "switches_in_contact": switches,
        "contact_time_error": (t_last - tc) / tc,
        "contact_time_error_steps": (t_last - tc) / dt,
        "rebound_error": d["velocity_mm_per_s"][-1] / -1000. - 1,
        "max_penetration_mm": d["max_penetration_mm"].max(),
        "mean_active_set_iterations": d["iterations"].mean(),
        "max_active_set_iterations": d["iterations"].max(),
    }


BAR_VARIANTS = [("newmark", "newmark", None), ("contact-stabilised", "contact-stabilised", None),
                ("ga0.5", "generalized-alpha", 0.5), ("ga0.8", "generalized-alpha", 0.8),
                ("ga1.0", "generalized-alpha", 1.0)]


def part_bar(args):
    log("== bar: elastic bar against a rigid wall (build/bar-impact, 1 rank)")
    cfls = [1] if args.quick else [0.25, 0.5, 1, 2, 4]
    cells_list = [20, 40] if args.quick else [20, 40, 80]
    rows, series = [], {}
    cases = [(v, 40, c) for v in BAR_VARIANTS for c in cfls] + \
            [(v, n, 1) for v in BAR_VARIANTS for n in cells_list if n != 40]
    for (label, scheme, rho), cells, cfl in cases:
        meta, d, wall = bar_run(args, scheme, cells, cfl, rho)
        m = bar_metrics(meta, d)
        rows.append({"variant": label, "scheme": scheme, "rho_inf": rho if rho is not None else "",
                     "cells": cells, "cfl": cfl, **m, "wall_s": wall})
        if cells == 40 and cfl == 1:
            series[label] = (meta, d)
    write_csv(os.path.join(args.out, "bar.csv"), rows)
    # Force series at CFL 1 (40 cells) for the figure.
    meta = series["contact-stabilised"][0]
    srows = []
    for i in range(len(series["contact-stabilised"][1]["time_s"])):
        r = {"time_s": series["contact-stabilised"][1]["time_s"][i]}
        for label in series:
            r[f"force_{label}"] = series[label][1]["contact_force_N_per_mm"][i]
        srows.append(r)
    write_csv(os.path.join(args.out, "bar-force-cfl1.csv"), srows)

    # Figure: contact force at CFL 1.
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    tc, f1 = meta["tc"], meta["f"]
    ax.plot([0, 0, tc * 1e6, tc * 1e6, 2.5 * tc * 1e6], [0, f1, f1, 0, 0], "k-", lw=2.5, alpha=.35,
            label="1D closed form")
    for label, name in [("newmark", "newmark"), ("contact-stabilised", "contact-stabilised"),
                        ("ga0.8", "generalized-alpha (rho 0.8)")]:
        mt, d = series[label]
        ax.plot(d["time_s"] * 1e6, d["contact_force_N_per_mm"], ".-", ms=3, lw=.8, color=COLOURS[label],
                label=name)
    ax.set_xlabel("time [us]")
    ax.set_ylabel("contact force [N/mm]")
    ax.set_title(f"bar impact, 40 cells, CFL 1 (dt = {meta['dt'] * 1e9:.1f} ns)", fontsize=9)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "bar-force.png"), dpi=110)
    plt.close(fig)

    # Figure: energy error against CFL.
    fig, axs = plt.subplots(1, 2, figsize=(8.4, 3.4))
    for label, scheme, rho in BAR_VARIANTS:
        sel = sorted([r for r in rows if r["variant"] == label and r["cells"] == 40], key=lambda r: r["cfl"])
        x = [r["cfl"] for r in sel]
        name = label if not label.startswith("ga") else f"gen-alpha rho {rho}"
        axs[0].plot(x, [r["final_energy_error"] for r in sel], "o-", color=COLOURS[label], label=name)
        axs[1].plot(x, [r["max_balance_error"] for r in sel], "o-", color=COLOURS[label], label=name)
    for ax, title in zip(axs, ["balance error at the end / E0", "largest balance error / E0 (gain > 0)"]):
        ax.set_xscale("log")
        ax.set_yscale("symlog", linthresh=1e-4)
        ax.axhline(0, color="k", lw=.5)
        ax.set_xlabel("CFL = c dt / h")
        ax.set_title(title, fontsize=9)
        ax.grid(alpha=.3)
    axs[0].legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "bar-energy-cfl.png"), dpi=110)
    plt.close(fig)

    cols = ["variant", "cells", "cfl", "final_energy_error", "max_balance_error", "mean_force_error",
            "force_std_over_mean", "switches_in_contact", "contact_time_error_steps", "rebound_error",
            "max_penetration_mm", "mean_active_set_iterations"]
    log(md_table(rows, cols))
    return rows


# ---------------------------------------------------------------- part 2: cycloid
def balance_summary(e):
    """Final and extreme energy-balance figures of one run's energy.csv rows."""
    return {"final_relative_balance_error": e[-1]["relative_balance_error"],
            "max_abs_relative_balance_error": max(abs(x["relative_balance_error"]) for x in e),
            "max_relative_balance_error": max(x["relative_balance_error"] for x in e),
            "final_balance_error_J": e[-1]["balance_error_J"],
            "final_external_work_J": e[-1]["external_work_J"],
            "final_contact_work_J": e[-1]["contact_work_J"]}


def transient_series(out_dir):
    e = read_csv(os.path.join(out_dir, "energy.csv"), numbers=(float,), missing_ok=True)
    s = read_csv(os.path.join(out_dir, "stiffness.csv"), numbers=(float,), missing_ok=True)
    return e, s


def part_cycloid(args, fe):
    log("== cycloid: tests/runs/transient.prm, three schemes, three time steps")
    base = os.path.join(ROOT, "tests/runs/transient.prm")
    dts = [2e-5] if args.quick else [4e-5, 2e-5, 1e-5]
    end, ramp = 2.4e-4, 8e-5
    rows, curves = [], {}
    for scheme in SCHEMES:
        for dt in dts:
            name = f"cycloid-{scheme}-dt{dt:g}"
            ov = {("Transient", "Scheme"): scheme, ("Transient", "Time step"): f"{dt:g}",
                  ("Transient", "End time"): f"{end:g}", ("Transient", "Checkpoint interval"): 0,
                  ("Transient", "Output interval"): 0}
            m = fe.run(name, base, ov)
            e, s = transient_series(m["dir"])
            r = {"scheme": scheme, "dt_s": dt, "rc": m["rc"], "steps_done": len(e),
                 "steps_planned": int(round(end / dt)), "command_wall_s": m["wall_s"],
                 "error": m["error"], "warning": "; ".join(m["warnings"])}
            if e:
                t = np.array([x["time_s"] for x in e])
                rel = np.array([x["relative_balance_error"] for x in e])
                bal = np.array([x["balance_error_J"] for x in e])
                W = np.array([x["external_work_J"] for x in e])
                Wc = np.array([x["contact_work_J"] for x in e])
                its = np.array([x["active_set_iterations"] for x in e])
                F = np.array([x["max_pin_force_N"] for x in s])
                lin = np.array([x["linear_iterations"] for x in s])
                d2 = F[2:] - 2 * F[1:-1] + F[:-2] if len(F) > 2 else np.array([np.nan])
                after = t[1:-1] >= ramp - 1e-12 if len(F) > 2 else np.array([True])
                Fa = F[t >= ramp - 1e-12]
                r.update({
                    "t_end_s": t[-1],
                    "final_relative_balance_error": rel[-1],
                    "max_abs_relative_balance_error": np.abs(rel).max(),
                    "max_relative_balance_error": rel.max(),
                    "final_balance_error_J": bal[-1], "final_external_work_J": W[-1],
                    "final_contact_work_J": Wc[-1],
                    "final_kinetic_J": e[-1]["kinetic_J"], "final_elastic_J": e[-1]["elastic_J"],
                    "max_penetration_um": max(x["max_penetration_um"] for x in e),
                    "mean_largest_pin_force_after_ramp_N": Fa.mean() if len(Fa) else float("nan"),
                    "max_second_difference_over_mean": (np.abs(d2[after]).max() / Fa.mean()
                                                        if len(Fa) and after.any() else float("nan")),
                    "mean_active_set_iterations": its.mean(), "max_active_set_iterations": its.max(),
                    "cg_per_solve": lin.sum() / (2 * its.sum()),
                    "step_wall_s": sum(x["wall_s"] for x in e) / len(e),
                })
                curves[(scheme, dt)] = (t, rel, F, bal, W)
            rows.append(r)
    # Control: contact-stabilised with the crank held (fixed obstacles: no
    # obstacle work; the scheme must not gain).
    held = []
    for scheme in ([] if args.quick else ["contact-stabilised", "generalized-alpha"]):
        dt = 4e-5
        ov = {("Transient", "Scheme"): scheme, ("Transient", "Time step"): f"{dt:g}",
              ("Transient", "End time"): f"{end:g}", ("Transient", "Checkpoint interval"): 0,
              ("Transient", "Output interval"): 0, ("Transient", "Crank speed"): 0}
        m = fe.run(f"cycloid-{scheme}-dt{dt:g}-crank-held", base, ov)
        e, s = transient_series(m["dir"])
        if e:
            held.append({"scheme": f"{scheme} (crank held)", "dt_s": dt, "rc": m["rc"], "steps_done": len(e),
                    **balance_summary(e),
                    "mean_active_set_iterations": np.mean([x["active_set_iterations"] for x in e]),
                    "command_wall_s": m["wall_s"], "error": m["error"], "warning": "; ".join(m["warnings"])})
    # Impact: the modified profile (clearances 17-20 um) with 1000 N m
    # applied at once: the disc swings through the clearance (takeup 2e-4 rad,
    # reached after about 1.5e-4 s) and hits the pins.
    impact = []
    end_impact = 3.6e-4
    for scheme in ([] if args.quick else ["newmark", "contact-stabilised"]):
        dt = 2e-5
        ov = {("Transient", "Scheme"): scheme, ("Transient", "Time step"): f"{dt:g}",
              ("Transient", "End time"): f"{end_impact:g}", ("Transient", "Checkpoint interval"): 0,
              ("Transient", "Output interval"): 0, ("Transient", "Ramp time"): 0, ("Loading", "Torque"): 1000,
              ("Geometry", "Pin circle radius modification"): -0.01, ("Geometry", "Pin radius modification"): 0.01}
        m = fe.run(f"cycloid-impact-{scheme}-dt{dt:g}", base, ov)
        e, s = transient_series(m["dir"])
        if e:
            F = np.array([x["max_pin_force_N"] for x in s])
            pins = np.array([x["pins_in_contact"] for x in s])
            impact.append({"scheme": f"{scheme} (impact: modified profile, 1000 N m at once)", "dt_s": dt,
                           "rc": m["rc"], "steps_done": len(e), "steps_planned": int(round(end_impact / dt)),
                           **balance_summary(e),
                           "largest_pin_force_series_N": " ".join(f"{f:.0f}" for f in F),
                           "pins_in_contact_series": " ".join(str(int(p)) for p in pins),
                           "mean_active_set_iterations": np.mean([x["active_set_iterations"] for x in e]),
                           "max_active_set_iterations": max(x["active_set_iterations"] for x in e),
                           "command_wall_s": m["wall_s"], "error": m["error"], "warning": "; ".join(m["warnings"])})
    held += impact
    # Convergence of the balance error with dt (same end time).
    for scheme in SCHEMES:
        sel = [r for r in rows if r["scheme"] == scheme and r.get("t_end_s", 0) >= end - 1e-12]
        sel.sort(key=lambda r: -r["dt_s"])
        for a, b in zip(sel, sel[1:]):
            ea, eb = abs(a["final_balance_error_J"]), abs(b["final_balance_error_J"])
            b["observed_order_vs_previous_dt"] = math.log(ea / eb) / math.log(a["dt_s"] / b["dt_s"]) \
                if ea > 0 and eb > 0 else float("nan")
    write_csv(os.path.join(args.out, "cycloid.csv"), rows + held)
    srows = []
    for (scheme, dt), (t, rel, F, bal, W) in curves.items():
        for i in range(len(t)):
            srows.append({"scheme": scheme, "dt_s": dt, "time_s": t[i], "relative_balance_error": rel[i],
                          "balance_error_J": bal[i], "external_work_J": W[i], "largest_pin_force_N": F[i]})
    write_csv(os.path.join(args.out, "cycloid-series.csv"), srows)

    # Figures.
    fig, axs = plt.subplots(1, 2, figsize=(9, 3.6))
    for scheme in SCHEMES:
        if (scheme, 2e-5) in curves:
            t, rel, F, bal, W = curves[(scheme, 2e-5)]
            axs[0].plot(t * 1e6, rel * 100, "o-", ms=3, color=COLOURS[scheme], label=scheme)
        sel = [r for r in rows if r["scheme"] == scheme and r.get("t_end_s", 0) >= end - 1e-12]
        if sel:
            axs[1].loglog([r["dt_s"] for r in sel], [abs(r["final_balance_error_J"]) for r in sel], "o-",
                          color=COLOURS[scheme], label=scheme)
    axs[0].axvline(ramp * 1e6, color="k", ls=":", lw=.8)
    axs[0].set_xlabel("time [us]")
    axs[0].set_ylabel("balance error / work [%]")
    axs[0].set_title("relative energy balance error, dt = 2e-5 s", fontsize=9)
    axs[0].legend(fontsize=7)
    axs[0].grid(alpha=.3)
    axs[1].set_xlabel("time step [s]")
    axs[1].set_ylabel("|balance error| at t = 2.4e-4 s [J]")
    axs[1].set_title("convergence of the balance error with dt", fontsize=9)
    axs[1].grid(alpha=.3, which="both")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "cycloid-balance.png"), dpi=110)
    plt.close(fig)

    fig, ax = plt.subplots(figsize=(6.4, 3.8))
    styles = {4e-5: ":", 2e-5: "-", 1e-5: "--"}
    for (scheme, dt), (t, rel, F, bal, W) in sorted(curves.items()):
        ax.plot(t * 1e6, F, styles.get(dt, "-"), marker="o", ms=2.5, lw=1, color=COLOURS[scheme],
                label=f"{scheme}, dt {dt:g}")
    ax.axvline(ramp * 1e6, color="k", ls=":", lw=.8)
    ax.set_xlabel("time [us]")
    ax.set_ylabel("largest pin force [N]")
    ax.set_title("largest pin force (300 N m ramped over 80 us, 9000 deg/s)", fontsize=9)
    ax.legend(fontsize=6, ncol=2)
    ax.grid(alpha=.3)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "cycloid-pin-force.png"), dpi=110)
    plt.close(fig)

    cols = ["scheme", "dt_s", "rc", "steps_done", "final_relative_balance_error", "max_abs_relative_balance_error",
            "final_balance_error_J", "final_external_work_J", "observed_order_vs_previous_dt",
            "max_second_difference_over_mean", "mean_active_set_iterations", "max_active_set_iterations",
            "cg_per_solve", "step_wall_s", "command_wall_s"]
    log(md_table(rows + held, cols))
    for r in rows + held:
        if r["error"] or r["warning"]:
            log(f"  {r['scheme']} dt {r['dt_s']:g}: {r['warning']} {r['error']}")
    return rows


# ---------------------------------------------------------------- part 3: slow
def part_slow(args, fe):
    log("== slow: slow damped transient against the quasi-static phase sweep")
    base = os.path.join(ROOT, "prm/phase-sweep-2d.prm")
    torque, period, dt = 1000, 9.0, 1e-4
    steps_per_period = 100
    speed = period / (steps_per_period * dt)  # 900 deg/s
    if args.slow_full:
        ramp_steps, cover = 10, 1.0
    elif args.quick:
        ramp_steps, cover = 3, 0.15
    else:
        ramp_steps, cover = 5, 0.5
    n_steps = ramp_steps + int(round(cover * steps_per_period))
    phases = 5 if args.quick else 21
    cr = args.slow_refinements
    sweep = fe.run(f"slow-sweep-cr{cr}-{phases}", base, {
        ("", "Write solution"): "false", ("Loading", "Torque"): torque, ("Loading", "Number of phases"): phases,
        ("Mesh", "Contact refinements"): cr, ("Mesh", "Target accuracy"): 0})
    tr = fe.run(f"slow-transient-cr{cr}-{n_steps}", base, {
        ("", "Run"): "transient", ("", "Write solution"): "false", ("Loading", "Torque"): torque,
        ("Mesh", "Contact refinements"): cr,
        ("Loading", "Number of phases"): 1,
        ("Transient", "Scheme"): "contact-stabilised", ("Transient", "Time step"): f"{dt:g}",
        ("Transient", "End time"): f"{n_steps * dt:g}", ("Transient", "Ramp time"): f"{ramp_steps * dt:g}",
        ("Transient", "Crank speed"): f"{speed:g}", ("Transient", "Rayleigh mass damping"): "2e4",
        ("Transient", "Checkpoint interval"): 0, ("Transient", "Output interval"): 0})
    qs = read_csv(os.path.join(sweep["dir"], "stiffness.csv"), numbers=(float,), missing_ok=True)
    e, s = transient_series(tr["dir"])
    psi_q = np.array([r["crank_deg"] for r in qs])
    k_q = np.array([r["K_secant_Nm_per_rad"] for r in qs])
    ramp_t = ramp_steps * dt
    after = [(r, x) for r, x in zip(s, e) if x["time_s"] > ramp_t + 1e-12]
    psi_t = np.array([r["crank_deg"] for r, x in after])
    k_t = np.array([r["K_secant_Nm_per_rad"] for r, x in after])
    kin = np.array([x["kinetic_J"] for r, x in after])
    el = np.array([x["elastic_J"] for r, x in after])
    # Sweep at the transient's angles (periodic, linear interpolation) and
    # exactly at the coinciding angles.
    order = np.argsort(psi_q)
    k_interp = np.interp(np.mod(psi_t, period), psi_q[order], k_q[order], period=period)
    coincide = []
    for p, k in zip(psi_t, k_t):
        j = np.argmin(np.abs(psi_q - np.mod(p, period)))
        if abs(psi_q[j] - np.mod(p, period)) < 1e-6:
            coincide.append((p, k, k_q[j]))
    lo, hi = psi_t.min(), psi_t.max()
    in_range = [(p, k) for p, k in zip(psi_q, k_q) if lo - 1e-9 <= p <= hi + 1e-9]
    kq_range = np.array([k for p, k in in_range] + list(np.interp([lo, hi], psi_q[order], k_q[order])))
    settled = np.array([x["time_s"] > 2 * ramp_t + 1e-12 for r, x in after])
    if settled.any():
        a, b = psi_t[settled].min(), psi_t[settled].max()
        ks_range = np.array([k for p, k in zip(psi_q, k_q) if a - 1e-9 <= p <= b + 1e-9] +
                            list(np.interp([a, b], psi_q[order], k_q[order])))
    summary = {
        "torque_Nm": torque, "contact_refinements": cr, "time_step_s": dt, "crank_speed_deg_per_s": speed, "ramp_time_s": ramp_t,
        "steps": len(e), "transient_rc": tr["rc"], "transient_error": tr["error"],
        "transient_warnings": "; ".join(tr["warnings"]), "sweep_rc": sweep["rc"],
        "sweep_phases": phases, "angles_after_ramp_deg": f"{lo:.3f}-{hi:.3f}",
        "sweep_mean_K": k_q[:-1].mean() if len(k_q) > 1 else float("nan"),
        "sweep_fluctuation_full_period": (k_q.max() - k_q.min()) / k_q[:-1].mean(),
        "sweep_fluctuation_same_range": (kq_range.max() - kq_range.min()) / kq_range.mean(),
        "transient_mean_K_after_ramp": k_t.mean(),
        "transient_fluctuation_after_ramp": (k_t.max() - k_t.min()) / k_t.mean(),
        "max_rel_diff_vs_sweep_interp": np.abs(k_t / k_interp - 1).max(),
        "mean_rel_diff_vs_sweep_interp": (k_t / k_interp - 1).mean(),
        "max_rel_diff_at_coinciding_angles": max(abs(k / kq - 1) for p, k, kq in coincide) if coincide else float("nan"),
        "mean_rel_diff_at_coinciding_angles": float(np.mean([k / kq - 1 for p, k, kq in coincide])) if coincide else float("nan"),
        "n_coinciding": len(coincide),
        # After the ramp's own transient has decayed (t > 2 ramp times).
        "settled_from_deg": psi_t[settled].min() if settled.any() else float("nan"),
        "transient_fluctuation_settled": (k_t[settled].max() - k_t[settled].min()) / k_t[settled].mean()
        if settled.any() else float("nan"),
        "sweep_fluctuation_settled_range": (ks_range.max() - ks_range.min()) / ks_range.mean()
        if settled.any() else float("nan"),
        "max_rel_diff_settled_vs_sweep_interp": np.abs(k_t[settled] / k_interp[settled] - 1).max()
        if settled.any() else float("nan"),
        "max_kinetic_over_elastic_settled": (kin[settled] / el[settled]).max() if settled.any() else float("nan"),
        "max_kinetic_over_elastic_after_ramp": (kin / el).max(),
        "final_relative_balance_error": e[-1]["relative_balance_error"] if e else float("nan"),
        "dissipated_over_work": e[-1]["dissipated_J"] / e[-1]["external_work_J"] if e else float("nan"),
        "transient_wall_s": tr["wall_s"], "sweep_wall_s": sweep["wall_s"],
        "transient_step_wall_s": float(np.mean([x["wall_s"] for x in e])) if e else float("nan"),
        "sweep_dofs": qs[0]["dofs"] if qs else "", "transient_dofs": s[0]["dofs"] if s else "",
        "mean_active_set_iterations_after_ramp": float(np.mean([x["active_set_iterations"] for r, x in after])),
    }
    write_csv(os.path.join(args.out, "slow.csv"), [summary])
    rows = [{"source": "phase-sweep", "crank_deg": p, "K_secant_Nm_per_rad": k} for p, k in zip(psi_q, k_q)] + \
           [{"source": "transient", "crank_deg": r["crank_deg"], "time_s": x["time_s"],
             "K_secant_Nm_per_rad": r["K_secant_Nm_per_rad"], "torque_Nm": r["torque_Nm"],
             "kinetic_J": x["kinetic_J"], "elastic_J": x["elastic_J"],
             "pins_in_contact": r["pins_in_contact"]} for r, x in zip(s, e)]
    write_csv(os.path.join(args.out, "slow-series.csv"), rows)

    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    ax.plot(psi_q, k_q / 1e6, "ks-", ms=4, label=f"phase sweep ({phases} phases)")
    psi_all = np.array([r["crank_deg"] for r in s])
    k_all = np.array([r["K_secant_Nm_per_rad"] for r in s])
    ramp_mask = np.array([x["time_s"] <= ramp_t + 1e-12 for x in e])
    ax.plot(psi_all[~ramp_mask], k_all[~ramp_mask] / 1e6, "o-", ms=2.5, lw=.8, color=COLOURS["contact-stabilised"],
            label=f"transient, {speed:g} deg/s, dt {dt:g} s, after the ramp")
    lim = ax.get_ylim()
    ax.plot(psi_all[ramp_mask], k_all[ramp_mask] / 1e6, "x", color="0.6", label="transient, during the ramp")
    ax.set_ylim(lim)
    ax.set_xlabel("crank angle [deg]")
    ax.set_ylabel("K_secant [MN m/rad]")
    ax.set_title(f"2D modified profile, {torque} N m, Contact refinements {cr}: slow transient vs phase sweep",
                 fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=.3)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "slow-ksecant.png"), dpi=110)
    plt.close(fig)
    for k, v in summary.items():
        log(f"  {k}: {fmt(v) if isinstance(v, float) else v}")
    return summary


# ---------------------------------------------------------------- parts 4, 5: quasi-static
QS_BASE = "tests/runs/quasi-static-elastic.prm"
MODS = [("Geometry", "Pin circle radius modification"), ("Geometry", "Pin radius modification")]


def debug_sets(stderr):
    """Active-set sizes per iteration, one list per state, from CYCLOID_DEBUG."""
    states, cur, last_label = [], None, None
    for l in stderr.splitlines():
        m = re.search(r"\[active set\] (.*), iteration (\d+): .* active (\d+) -> (\d+)", l)
        if not m:
            continue
        label, it = m.group(1), int(m.group(2))
        if it == 0 or label != last_label:
            cur = [int(m.group(3))]
            states.append(cur)
        cur.append(int(m.group(4)))
        last_label = label
    return states


def qs_case(fe, cr, profile="modified", solver="cg-amg", formulation="mortar"):
    name = f"qs-{profile}-cr{cr}-{solver}-{formulation}"
    ov = {("", "Write solution"): "false", ("Mesh", "Contact refinements"): cr}
    if solver != "cg-amg":
        ov[("Solver", "Linear solver")] = solver
    if formulation != "mortar":
        ov[("Contact", "Formulation")] = formulation
    m = fe.run(name, os.path.join(ROOT, QS_BASE), ov, MODS if profile == "seed" else (), debug=True)
    rows = read_csv(os.path.join(m["dir"], "stiffness.csv"), numbers=(float,), missing_ok=True)
    err = open(os.path.join(fe.args.work, name, "stderr.log")).read()
    sets = debug_sets(err)
    out = []
    for i, r in enumerate(rows):
        its = int(r["active_set_iterations"])
        out.append({"profile": profile, "contact_refinements": cr, "formulation": formulation, "solver": solver,
                    "torque_Nm": r["torque_Nm"], "start": "cold (analytical model)" if i == 0 else "warm (previous torque)",
                    "active_set_iterations": its, "active_set_sizes": " > ".join(map(str, sets[i])) if i < len(sets) else "",
                    "pins_in_contact": int(r["pins_in_contact"]), "dofs": int(r["dofs"]),
                    "K_secant_Nm_per_rad": r["K_secant_Nm_per_rad"],
                    "cg_iterations": int(r["linear_iterations"]),
                    "cg_per_solve": r["linear_iterations"] / (2 * its), "state_wall_s": r["wall_s"],
                    "rc": m["rc"], "error": m["error"], "command_wall_s": m["wall_s"]})
    if not rows:
        out.append({"profile": profile, "contact_refinements": cr, "formulation": formulation, "solver": solver,
                    "rc": m["rc"], "error": m["error"], "command_wall_s": m["wall_s"]})
    return out


def part_active_set(args, fe):
    log("== active-set: quasi-static 2D, cold and warm starts")
    crs = [0, 1] if args.quick else [0, 1, 2, 3]
    rows = []
    for profile in ["modified", "seed"]:
        for cr in crs:
            rows += qs_case(fe, cr, profile)
    rows += qs_case(fe, crs[-1], "modified", formulation="node-to-surface")
    write_csv(os.path.join(args.out, "active-set.csv"), rows)
    cols = ["profile", "formulation", "contact_refinements", "dofs", "torque_Nm", "start", "active_set_iterations",
            "active_set_sizes", "pins_in_contact", "K_secant_Nm_per_rad", "state_wall_s", "rc"]
    log(md_table(rows, cols))
    return rows


def part_solver(args, fe):
    log("== solver: CG iterations, cg-amg vs cg-amg-translations")
    crs = [0, 1] if args.quick else [0, 1, 2, 3]
    rows = []
    for solver in ["cg-amg", "cg-amg-translations"]:
        for cr in crs:
            rows += qs_case(fe, cr, "modified", solver)
    write_csv(os.path.join(args.out, "solver.csv"), rows)
    fig, ax = plt.subplots(figsize=(5.6, 3.4))
    for solver, mk in [("cg-amg", "o-"), ("cg-amg-translations", "s--")]:
        for torque in [100, 1000]:
            sel = [r for r in rows if r["solver"] == solver and r.get("torque_Nm") == torque]
            if sel:
                ax.plot([r["dofs"] for r in sel], [r["cg_per_solve"] for r in sel], mk,
                        label=f"{solver}, {torque} N m")
    ax.set_xscale("log")
    ax.set_xlabel("DoFs (Contact refinements 0..3)")
    ax.set_ylabel("CG iterations per solve")
    ax.set_title("CG + ML AMG, relative tolerance 1e-10", fontsize=9)
    ax.legend(fontsize=7)
    ax.grid(alpha=.3, which="both")
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, "solver-cg.png"), dpi=110)
    plt.close(fig)
    cols = ["solver", "contact_refinements", "dofs", "torque_Nm", "active_set_iterations", "cg_iterations",
            "cg_per_solve", "state_wall_s", "command_wall_s", "rc", "error"]
    log(md_table(rows, cols))
    return rows


# ---------------------------------------------------------------- parts 6, 7: the 2D example
EXAMPLE = os.path.join(ROOT, "prm/transient-2d.prm")
PERIOD = 1e-3  # one mesh period at 9000 deg/s [s]
RAMP = 2e-4  # the example's Ramp time [s]


def per_period(e, s, ramp):
    """Per mesh period: the balance at its end, its largest |balance|, and
    the mean active-set iterations and wall time per step (after the ramp)."""
    t = np.array([x["time_s"] for x in e])
    rel = np.array([x["relative_balance_error"] for x in e])
    its = np.array([x["active_set_iterations"] for x in e])
    wall = np.array([x["wall_s"] for x in s])
    rows = []
    for k in range(int(round(t[-1] / PERIOD))):
        m = (t > k * PERIOD + 1e-12) & (t <= (k + 1) * PERIOD + 1e-12)
        a = m & (t >= ramp - 1e-12)
        rows.append({"period": k + 1, "relative_balance_error_at_end": rel[m][-1],
                     "max_abs_relative_balance_error": np.abs(rel[m]).max(),
                     "active_set_iterations_per_step": its[a].mean(),
                     "wall_s_per_step": wall[a].mean()})
    return rows


def part_long(args, fe):
    log("== long: prm/transient-2d.prm at Contact refinements 1, energy over many periods")
    # (scheme, periods swept by the mesh, time step, steps run or 0: all,
    # linear solver). The last case halves the step on the second one's
    # mesh for one period: the order of contact-stabilised's drift.
    cases = [("newmark", 10, 1e-5, 0, "direct"), ("contact-stabilised", 3, 1e-5, 0, "cg-amg"),
             ("contact-stabilised", 3, 5e-6, 200, "cg-amg")]
    return long_runs(args, fe, cases, 1, "long", "2D example, Contact refinements 1, 1500 rpm, 1000 N m")


def part_long_example(args, fe):
    log("== long-example: prm/transient-2d.prm as shipped (Contact refinements 3), Newmark over 10 periods")
    return long_runs(args, fe, [("newmark", 10, 1e-5, 0, "direct")], None, "long-example",
                     "2D example as shipped (Contact refinements 3), 1500 rpm, 1000 N m",
                     checkpoints=100)


def long_runs(args, fe, cases, refinements, prefix, title, checkpoints=0):
    """The cases over many mesh periods on the example: per period the
    balance error, iterations and time per step (<prefix>.csv), the series
    (<prefix>-series.csv) and the balance chart (<prefix>-balance.png).
    refinements None keeps the example's Contact refinements."""
    rows, series = [], {}
    for scheme, periods, dt, stop, solver in cases:
        ov = {("Transient", "Scheme"): scheme,
              ("Transient", "End time"): f"{periods * PERIOD:g}", ("Transient", "Output interval"): 0,
              ("Transient", "Checkpoint interval"): checkpoints, ("Solver", "Linear solver"): solver}
        if refinements is not None:
            ov[("Mesh", "Contact refinements")] = refinements
        if dt != 1e-5:
            ov[("Transient", "Time step")] = f"{dt:g}"
        if stop:
            ov[("Transient", "Stop after step")] = stop
        label = f"{scheme} dt {dt:g}"
        m = fe.run(f"{prefix}-{scheme}-{periods}" + (f"-dt{dt:g}" if dt != 1e-5 else ""), EXAMPLE, ov)
        e, s = transient_series(m["dir"])
        if not e:
            log(f"  {label}: no rows ({m['error']})")
            continue
        for r in per_period(e, s, RAMP):
            rows.append({"scheme": scheme, "dt_s": dt, "linear_solver": solver, **r})
        rows[-1]["drift_per_period"] = drift_per_period(e, RAMP)
        series[label] = e
    write_csv(os.path.join(args.out, f"{prefix}.csv"), rows)
    keys = ["scheme", "step", "time_s", "relative_balance_error", "balance_error_J", "kinetic_J",
            "elastic_J", "external_work_J", "contact_work_J"]
    write_csv(os.path.join(args.out, f"{prefix}-series.csv"),
              [{"scheme": sc, **x} for sc, e in series.items() for x in e], keys)
    styles = {"newmark dt 1e-05": ("tab:red", "-"), "contact-stabilised dt 1e-05": ("tab:blue", "-"),
              "contact-stabilised dt 5e-06": ("tab:blue", ":")}
    fig, ax = plt.subplots(figsize=(6.4, 3.6))
    for sc, e in series.items():
        colour, ls = styles.get(sc, ("k", "-"))
        ax.plot([x["time_s"] * 1e3 for x in e], [100 * x["relative_balance_error"] for x in e],
                ls, lw=.8, color=colour, label=sc + " s")
    for y in (-0.5, 0.5):
        ax.axhline(y, color="k", ls=":", lw=.8)
    ax.set_xlabel("time [ms] (one mesh period = 1 ms)")
    ax.set_ylabel("balance error / largest energy level [%]")
    ax.set_title(title, fontsize=9)
    ax.legend(fontsize=8)
    ax.grid(alpha=.3)
    fig.tight_layout()
    fig.savefig(os.path.join(args.out, f"{prefix}-balance.png"), dpi=110)
    plt.close(fig)
    log(md_table(rows, ["scheme", "dt_s", "period", "relative_balance_error_at_end",
                        "max_abs_relative_balance_error", "active_set_iterations_per_step", "wall_s_per_step",
                        "drift_per_period"]))
    return rows


def drift_per_period(e, ramp):
    """Slope of the relative balance error after the ramp, per mesh period
    (least squares)."""
    t = np.array([x["time_s"] for x in e])
    rel = np.array([x["relative_balance_error"] for x in e])
    a = t >= ramp - 1e-12
    if a.sum() < 2:
        return float("nan")
    return float(np.polyfit(t[a] / PERIOD, rel[a], 1)[0])


def part_example(args, fe):
    log("== example: prm/transient-2d.prm, 30 steps, schemes and linear solvers")
    # Stop after step, not End time: the contact refinement follows the
    # sweep to End time, so the mesh stays the example's.
    rows = []
    # With the direct solver, each active set condensed and factorised
    # (Contact Schur complement = false) or one factorisation for the run
    # (true, the default for Newmark).
    for scheme, solver, schur in [("contact-stabilised", "cg-amg", "false"), ("newmark", "cg-amg", "false"),
                                  ("newmark", "direct", "false"), ("newmark", "direct", "true")]:
        ov = {("Transient", "Scheme"): scheme, ("Transient", "Stop after step"): 30,
              ("Transient", "Output interval"): 0, ("Transient", "Checkpoint interval"): 0,
              ("Solver", "Linear solver"): solver, ("Solver", "Contact Schur complement"): schur}
        m = fe.run(f"example-{scheme}-{solver}" + ("-schur" if schur == "true" else ""), EXAMPLE, ov)
        e, s = transient_series(m["dir"])
        if not e:
            log(f"  {scheme}/{solver}: no rows ({m['error']})")
            continue
        a = [x["time_s"] >= RAMP + 1e-12 for x in e]
        mean = lambda rows_, key: float(np.mean([x[key] for x, y in zip(rows_, a) if y]))
        rows.append({"scheme": scheme, "linear_solver": solver, "schur_complement": schur,
                     "command_wall_s": m["wall_s"],
                     "wall_s_per_step_after_ramp": mean(s, "wall_s"),
                     "active_set_iterations_per_step": mean(e, "active_set_iterations"),
                     "cg_iterations_per_step": mean(s, "linear_iterations"),
                     "rotation_end_rad": s[-1]["rotation_rad"], "max_pin_force_end_N": s[-1]["max_pin_force_N"],
                     "relative_balance_error_end": e[-1]["relative_balance_error"]})
    write_csv(os.path.join(args.out, "example-solvers.csv"), rows)
    log(md_table(rows, list(rows[0].keys()) if rows else []))
    return rows


# ---------------------------------------------------------------- main
def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--part", default=",".join(p for p in PARTS if p != "long-example"),
                    help="comma-separated: " + ",".join(PARTS) + " (default: all but long-example)")
    ap.add_argument("--quick", action="store_true", help="fewer cases (a smoke test of every part)")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build/cycloid-contact"))
    ap.add_argument("--bar", default=os.path.join(ROOT, "build/bar-impact"))
    ap.add_argument("--work", default="/tmp/cycloid-stability")
    ap.add_argument("--out", default=os.path.join(ROOT, "doc/transient"))
    ap.add_argument("--rerun", action="store_true", help="ignore cached runs")
    ap.add_argument("--slow-full", action="store_true", help="slow part over a whole mesh period")
    ap.add_argument("--slow-refinements", type=int, default=1,
                    help="Mesh/Contact refinements of the slow part (the prm has 2; 1 halves the cost)")
    ap.add_argument("--timeout", type=float, default=1800)
    args = ap.parse_args()
    parts = [p.strip() for p in args.part.split(",") if p.strip()]
    for p in parts:
        if p not in PARTS:
            ap.error(f"unknown part {p} ({', '.join(PARTS)})")
    if args.quick and args.out == os.path.join(ROOT, "doc/transient"):
        # Fewer cases: keep doc/transient for the full study (the runs share
        # the work directory's cache).
        args.out = os.path.join(args.work, "quick-out")
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    fe = FE(args)
    start = time.time()
    results = {}
    for p in parts:
        t0 = time.time()
        results[p] = {"bar": lambda: part_bar(args), "cycloid": lambda: part_cycloid(args, fe),
                      "slow": lambda: part_slow(args, fe), "active-set": lambda: part_active_set(args, fe),
                      "solver": lambda: part_solver(args, fe), "long": lambda: part_long(args, fe),
                      "long-example": lambda: part_long_example(args, fe), "example": lambda: part_example(args, fe)}[p]()
        log(f"== {p} done in {time.time() - t0:.0f} s")
    log(f"total {time.time() - start:.0f} s; outputs in {args.out}, runs in {args.work}")


if __name__ == "__main__":
    main()
