#!/usr/bin/python3
"""Speed of the FE contact stiffness (issue #4 item 8): accuracy of K against
the whole program's wall time, for a sequence of meshes.

Parts (all on --ranks MPI ranks, default 2, Run = quasi-static, crank angle 0):
  seed  2D one disc, elastic pins held at their cores (Pin support = axis),
        unmodified profile (zero clearance), T = 1000 N m;
  mod   the same with the modified profile (Delta rp = -0.01 mm,
        Delta rrp = +0.01 mm: clearances 17-20 um), torque list 300, 1000 N m
        in one run (warm-started states);
  3d    3D two discs, elastic pins seated in the housing (Pin support =
        housing), unmodified profile, T = 1000 N m;
  3d1   3D one disc (Pin support = axis) against 2D one disc on the same
        in-plane mesh settings: how much the third dimension changes K.

Every run is the whole command `mpirun -np R cycloid-contact case.prm`, timed
from outside (mesh generation, set-up, solve and VTU output included). The
stiffness, DoFs, engaged pins and active-set iterations come from the run's
stiffness.csv; the program's own timer table gives the mesh and solve times.
The error of K is relative to the finest mesh of the same part (and, where
three nested contact refinements allow it, to a Richardson extrapolation).

Writes <out>/contact-speed-2d.csv, <out>/contact-speed-3d.csv and
<out>/contact-speed.png (out = doc/ by default) and prints a summary.

Usage:
  /usr/bin/python3 benchmarks/contact_speed/run.py [--exe PATH] [--quick]
      [--parts seed,mod,3d,3d1] [--timeout 1200] [--keep DIR]
"""
import argparse
import csv
import math
import os
import re
import resource
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, richardson, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))

# Mesh settings of the coarse 3D scene (also the "in-plane" mesh of the
# 3D-against-2D comparison).
COARSE3D = {"Contact element size": 1, "Flank element size": 1.5, "Pin element size": 1.5,
            "Coarse element size": 10, "Axial layers per disc": 1, "Contact refinements": 0}

# (part, case label, Mesh settings). Contact refinement radius 0.3 mm always.
SEED = [(f"cr{n}", {"Contact refinements": n}) for n in range(0, 6)] + [
    ("cr1+ad1", {"Contact refinements": 1, "Adaptive refinement cycles": 1}),
    ("cr1+ad2", {"Contact refinements": 1, "Adaptive refinement cycles": 2}),
    ("cr1+ad3", {"Contact refinements": 1, "Adaptive refinement cycles": 3}),
    ("cr2+ad1", {"Contact refinements": 2, "Adaptive refinement cycles": 1}),
    ("Q2 cr0", {"Contact refinements": 0, "Polynomial degree": 2}),
    ("Q2 cr1", {"Contact refinements": 1, "Polynomial degree": 2}),
    ("Q2 cr2", {"Contact refinements": 2, "Polynomial degree": 2}),
    ("Q2 cr3", {"Contact refinements": 3, "Polynomial degree": 2}),
    # One global refinement more: the bulk (away from the contacts) error of Q1.
    ("g1 cr3", {"Global refinements": 1, "Contact refinements": 3}),
]
SEED_QUICK = ["cr0", "cr1", "cr2", "cr3", "cr1+ad1", "Q2 cr0"]
MOD = [(f"cr{n}", {"Contact refinements": n}) for n in range(0, 5)] + [
    ("cr2+ad1", {"Contact refinements": 2, "Adaptive refinement cycles": 1}),
    ("Q2 cr1", {"Contact refinements": 1, "Polynomial degree": 2}),
    ("Q2 cr2", {"Contact refinements": 2, "Polynomial degree": 2}),
]
# Second reference of a 2D part: Q2 at the finest contact refinement run, which
# also has the bulk (away from the contacts) discretisation error of the Q1
# sequence removed (that error does not shrink with Contact refinements).
BEST = {"seed": "Q2 cr3", "mod": "Q2 cr2"}
MOD_QUICK = ["cr0", "cr1", "cr2"]


def c3(**kw):
    d = dict(COARSE3D)
    d.update({k.replace("_", " ").capitalize(): v for k, v in kw.items()})
    return d


THREE_D = [
    ("c1 ax1 cr0", c3()),
    ("c1 ax1 cr1", c3(contact_refinements=1)),
    ("c1 ax1 cr2", c3(contact_refinements=2)),
    ("c0.5 ax1 cr2", c3(contact_element_size=0.5, contact_refinements=2)),
    ("c0.5 ax2 cr2", c3(contact_element_size=0.5, axial_layers_per_disc=2, contact_refinements=2)),
    ("c0.5 ax1 cr3", c3(contact_element_size=0.5, contact_refinements=3)),
]
THREE_D_QUICK = ["c1 ax1 cr0", "c1 ax1 cr1"]
# 3D one disc (Pin support = axis) and 2D one disc on the same in-plane mesh
# ("2D <label>" pairs with "3D <label with axN>").
ONE_DISC = [
    ("2D c0.5 cr2", 2, c3(contact_element_size=0.5, contact_refinements=2)),
    ("3D c0.5 ax1 cr2", 3, c3(contact_element_size=0.5, contact_refinements=2)),
    ("3D c0.5 ax2 cr2", 3, c3(contact_element_size=0.5, axial_layers_per_disc=2, contact_refinements=2)),
    ("2D c0.5 cr3", 2, c3(contact_element_size=0.5, contact_refinements=3)),
    ("3D c0.5 ax1 cr3", 3, c3(contact_element_size=0.5, contact_refinements=3)),
]
ONE_DISC_QUICK = ["2D c0.5 cr2", "3D c0.5 ax1 cr2"]


def prm_text(out, dim, discs, support, torque, mesh, modified):
    lines = ["set Run = quasi-static", f"set Output directory = {out}"]
    if modified:
        lines += ["subsection Geometry", "  set Pin circle radius modification = -0.01",
                  "  set Pin radius modification = 0.01", "end"]
    lines += ["subsection Scene", f"  set Dimension = {dim}", f"  set Number of discs = {discs}",
              "  set Pins = elastic", f"  set Pin support = {support}", "end",
              "subsection Loading", f"  set Torque = {torque}", "  set Crank angle = 0", "end",
              "subsection Mesh", "  set Contact refinement radius = 0.3",
              "  set Target accuracy = 0"]  # the mesh asked for
    lines += [f"  set {k} = {v}" for k, v in mesh.items()]
    lines += ["end"]
    return "\n".join(lines) + "\n"


def timer_section(log, name):
    m = re.search(r"\|\s*" + re.escape(name) + r"\s*\|\s*\d+\s*\|\s*([0-9.e+-]+)s", log)
    return float(m.group(1)) if m else float("nan")


def run_case(args, work, part, label, dim, discs, support, torque, mesh, modified):
    """--repeat mpiruns of one case; the rows of the first, with the median
    wall and CPU times of all (and every wall time in wall_runs_s)."""
    runs = [run_once(args, work, part, label, dim, discs, support, torque, mesh, modified)
            for _ in range(max(1, args.repeat))]
    rows = runs[0]
    walls = [r[0]["total_wall_s"] for r in runs]
    cpus = [r[0]["cpu_s"] for r in runs]
    for r in rows:
        r["total_wall_s"] = sorted(walls)[len(walls) // 2]
        r["cpu_s"] = sorted(cpus)[len(cpus) // 2]
        r["wall_runs_s"] = ";".join(f"{w:.1f}" for w in walls)
    if len(runs) > 1:
        print(f"  {part:5s} {label:14s} wall times {r['wall_runs_s']} s: median {r['total_wall_s']:.1f} s", flush=True)
    return rows


def run_once(args, work, part, label, dim, discs, support, torque, mesh, modified):
    """One mpirun of the program; returns a list of rows (one per load state)."""
    tag = re.sub(r"[^A-Za-z0-9.]+", "_", f"{part}_{label}")
    out = os.path.join(work, tag)
    prm = out + ".prm"
    with open(prm, "w") as f:
        f.write(prm_text(out, dim, discs, support, torque, mesh, modified))
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    load = os.getloadavg()[0]
    p = run_cycloid(args.ranks, args.exe, prm, log=out + ".log", timeout=args.timeout)
    status = f"timeout {args.timeout:.0f} s" if p.timed_out else "ok" if p.returncode == 0 else f"exit {p.returncode}"
    wall, log = p.wall_s, p.stdout
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    cells = re.search(r"mesh: .*?(\d+) cells", log)
    base = {"part": part, "case": label, "dim": dim, "discs": discs,
            "contact_element_mm": mesh.get("Contact element size", 0.25),
            "axial_layers": mesh.get("Axial layers per disc", "") if dim == 3 else "",
            "contact_refinements": mesh.get("Contact refinements", 0),
            "adaptive_cycles": mesh.get("Adaptive refinement cycles", 0),
            "degree": mesh.get("Polynomial degree", 1),
            "cells": int(cells.group(1)) if cells else "",
            "grid_s": timer_section(log, "make grid"), "solve_s": timer_section(log, "solve (active set)"),
            "output_s": timer_section(log, "output results"),
            "total_wall_s": wall, "cpu_s": cpu, "load_avg_at_start": load, "status": status,
            "prm": prm, "log": out + ".log"}
    rows = []
    path = os.path.join(out, "stiffness.csv")
    if status == "ok" and os.path.exists(path):
        for r in read_csv(path):
            row = dict(base)
            row.update({"torque_Nm": float(r["torque_Nm"]), "state": int(r["step"]),
                        "dofs": int(r["dofs"]),
                        "K_secant_Nm_per_rad": float(r["K_secant_Nm_per_rad"]),
                        "K_tangent_Nm_per_rad": float(r["K_tangent_Nm_per_rad"]),
                        "K_secant_elastic_Nm_per_rad": float(r["K_secant_elastic_Nm_per_rad"]),
                        "max_pin_force_N": float(r["max_pin_force_N"]),
                        "pins_in_contact": int(r["pins_in_contact"]),
                        "active_set_iterations": int(r["active_set_iterations"]),
                        "state_wall_s": float(r["wall_s"])})
            rows.append(row)
    if not rows:
        row = dict(base)
        row.update({"torque_Nm": torque, "state": "", "dofs": ""})
        rows.append(row)
        tail = "\n    ".join(log.strip().splitlines()[-8:])
        print(f"  !! {part} {label}: {status}; prm {prm}\n    {tail}", flush=True)
    for r in rows:
        if "K_secant_Nm_per_rad" in r:
            print(f"  {part:5s} {label:14s} T {r['torque_Nm']:6.0f}: dofs {r['dofs']:7d}  "
                  f"K_sec {r['K_secant_Nm_per_rad']:.5e}  K_tan {r['K_tangent_Nm_per_rad']:.5e}  "
                  f"pins {r['pins_in_contact']:2d}  it {r['active_set_iterations']:2d}  "
                  f"Fmax {r['max_pin_force_N']:7.1f} N  wall {wall:7.1f} s (grid {base['grid_s']:.1f}, "
                  f"solve {base['solve_s']:.1f})  cpu {cpu:7.1f} s  load {load:.1f}", flush=True)
    return rows


def add_errors(rows, ref_case, key_fn, prefix=""):
    """{prefix}err_* relative to the case ref_case of the same group (key_fn(row))."""
    refs = {key_fn(r): r for r in rows if r["case"] == ref_case and has_k(r)}
    for r in rows:
        ref = refs.get(key_fn(r))
        r[prefix + "reference_case"] = ref_case if ref else ""
        for k, e in (("K_secant_Nm_per_rad", "err_K_secant_pct"), ("K_tangent_Nm_per_rad", "err_K_tangent_pct")):
            r[prefix + e] = 100. * (r[k] - ref[k]) / ref[k] if ref and has_k(r) else ""


def cheapest_within(rows, pct, key="total_wall_s", prefix=""):
    """The cheapest run (all its load states) with K_secant and K_tangent within pct of the reference."""
    cases = {}
    for r in rows:
        cases.setdefault(r["case"], []).append(r)
    ok = []
    for case, rr in cases.items():
        if all(r.get(prefix + "err_K_secant_pct", "") != "" and abs(r[prefix + "err_K_secant_pct"]) <= pct
               and abs(r[prefix + "err_K_tangent_pct"]) <= pct for r in rr) and case != rr[0][prefix + "reference_case"]:
            ok.append(max(rr, key=lambda r: max(abs(r[prefix + "err_K_secant_pct"]), abs(r[prefix + "err_K_tangent_pct"]))))
    return min(ok, key=lambda r: r[key]) if ok else None


COLUMNS = ["part", "case", "dim", "discs", "contact_element_mm", "axial_layers", "contact_refinements",
           "adaptive_cycles", "degree", "torque_Nm", "state", "cells", "dofs", "K_secant_Nm_per_rad",
           "K_tangent_Nm_per_rad", "K_secant_elastic_Nm_per_rad", "max_pin_force_N", "pins_in_contact",
           "active_set_iterations", "state_wall_s", "grid_s", "solve_s", "output_s", "total_wall_s", "wall_runs_s", "cpu_s",
           "load_avg_at_start", "reference_case", "err_K_secant_pct", "err_K_tangent_pct",
           "best_reference_case", "best_err_K_secant_pct", "best_err_K_tangent_pct", "status"]


def fmt(v):
    if isinstance(v, float):
        return "nan" if math.isnan(v) else f"{v:.6g}"
    return v


def write_csv(path, rows):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(COLUMNS)
        for r in rows:
            w.writerow([fmt(r.get(c, "")) for c in COLUMNS])
    print("written", path)


def family_marker(case):
    if case.startswith("Q2"):
        return "s"
    if case.startswith("g1"):
        return "D"
    if "+ad" in case:
        return "^"
    return "o"


def plot(path, groups):
    """K error (worst of secant and tangent, and of the states of a run)
    against the run's wall time, one marker per mesh, labelled."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(7.0, 4.8))
    for (name, rows), colour in zip(groups, ["C0", "C1", "C2", "C3"]):
        worst = {}
        for r in rows:
            if r.get("err_K_secant_pct", "") == "" or r["case"] == r["reference_case"]:
                continue
            err = max(abs(r["err_K_secant_pct"]), abs(r["err_K_tangent_pct"]))
            w = worst.setdefault(r["case"], [r["total_wall_s"], 0.])
            w[1] = max(w[1], err)
        first = True
        for case, (wall, err) in worst.items():
            err = max(err, 1e-2)
            ax.loglog(wall, err, family_marker(case), color=colour, ms=6, mfc="none" if case.startswith("Q2") else colour,
                      label=name if first else None)
            ax.annotate(case, (wall, err), textcoords="offset points", xytext=(4, 3), fontsize=5.5, color=colour)
            first = False
    ax.axhline(1.0, color="k", lw=0.8, ls="--")
    ax.axvline(60, color="C0", lw=0.6, ls=":")
    ax.axvline(900, color="C2", lw=0.6, ls=":")
    ax.text(60, ax.get_ylim()[0] * 1.3, " 60 s", fontsize=6, color="C0")
    ax.text(900, ax.get_ylim()[0] * 1.3, " 15 min", fontsize=6, color="C2")
    ax.set_xlabel("wall time of the whole run on 2 ranks (mesh + solve + output) [s]")
    ax.set_ylabel("max |error| of K_secant, K_tangent vs finest run [%]")
    ax.set_title("FE contact stiffness: error against cost (circles Q1 a-priori, triangles adaptive,\n"
                 "open squares Q2, diamond one global refinement more; floor 0.01 %)", fontsize=8)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=7, loc="lower right")
    fig.tight_layout()
    fig.savefig(path, dpi=110)
    print("written", path)


def summary_richardson(rows, labels, what):
    by = {r["case"]: r for r in rows if has_k(r)}
    notes = []
    if not all(l in by for l in labels):
        return notes
    for k in ("K_secant_Nm_per_rad", "K_tangent_Nm_per_rad"):
        c, m, f = (by[l][k] for l in labels)
        ext, p = richardson(c, m, f)
        if ext is None:
            notes.append(f"Richardson {what} {k} from {labels}: not monotone ({c:.5e}, {m:.5e}, {f:.5e})")
        else:
            notes.append(f"Richardson {what} {k} from {labels}: {ext:.5e} (order {p:.2f}); "
                         f"finest is {100 * (f - ext) / ext:+.2f} % from it")
    return notes


def has_k(r):
    return r.get("K_secant_Nm_per_rad", "") != ""


def finest_cr(rows):
    """The finest a-priori contact refinement (Q1, no global or adaptive refinement) of a part."""
    done = [r for r in rows if re.fullmatch(r"cr\d", r["case"]) and has_k(r)]
    return max(done, key=lambda r: r["contact_refinements"])["case"] if done else None


def analyse(rows2d, rows3d):
    """Errors against the finest run of every part, Richardson estimates, the 3D/2D ratios."""
    notes = []
    for part in ("seed", "mod"):
        rows = [r for r in rows2d if r["part"] == part]
        ref = finest_cr(rows)
        if not ref:
            continue
        add_errors(rows, ref, lambda r: r["torque_Nm"])
        add_errors(rows, BEST[part], lambda r: r["torque_Nm"], "best_")
        n = int(ref[2:])
        for t in sorted({r["torque_Nm"] for r in rows}):
            notes += summary_richardson([r for r in rows if r["torque_Nm"] == t],
                                        [f"cr{n - 2}", f"cr{n - 1}", f"cr{n}"], f"{part} T={t:.0f}")
    three = [r for r in rows3d if r["part"] == "3d" and has_k(r)]
    if three:
        add_errors([r for r in rows3d if r["part"] == "3d"], max(three, key=lambda r: r["dofs"])["case"],
                   lambda r: 0)
    by = {r["case"]: r for r in rows3d if r["part"] == "3d1" and has_k(r)}
    for l3 in by:
        l2 = "2D " + " ".join(w for w in l3.split()[1:] if not w.startswith("ax"))
        if l3.startswith("3D") and l2 in by:
            notes.append(f"{l3} / {l2}: K_secant {by[l3]['K_secant_Nm_per_rad'] / by[l2]['K_secant_Nm_per_rad']:.4f}, "
                         f"K_tangent {by[l3]['K_tangent_Nm_per_rad'] / by[l2]['K_tangent_Nm_per_rad']:.4f}")
    return notes


def merge(old, new, order):
    """Rows of old whose (part, case) was not run again, plus new, in the order of the case lists."""
    fresh = {(r["part"], r["case"]) for r in new}
    rows = [r for r in old if (r["part"], r["case"]) not in fresh] + new
    parts = ["seed", "mod", "3d", "3d1"]
    return sorted(rows, key=lambda r: (parts.index(r["part"]) if r["part"] in parts else 9,
                                       order.get((r["part"], r["case"]), 999), r["torque_Nm"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "cycloid-contact"))
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--quick", action="store_true", help="a small subset of every part (a few minutes)")
    ap.add_argument("--parts", default="seed,mod,3d,3d1", help="comma list of seed, mod, 3d, 3d1")
    ap.add_argument("--cases", default=None, help="comma list of case labels to run (default: all of the parts)")
    ap.add_argument("--fresh", action="store_true",
                    help="start new CSV files instead of replacing the re-run cases in the existing ones")
    ap.add_argument("--repeat", type=int, default=1,
                    help="run every case this many times and report the median wall time (timing noise)")
    ap.add_argument("--timeout", type=float, default=1200., help="stop a run after this many seconds")
    ap.add_argument("--out", default=os.path.join(ROOT, "doc"), help="directory of the CSV and PNG files")
    ap.add_argument("--keep", default=None, help="keep prm, logs and outputs in this directory")
    args = ap.parse_args()
    args.exe = os.path.abspath(args.exe)
    parts = args.parts.split(",")
    cases = set(args.cases.split(",")) if args.cases else None

    def pick(all_cases, quick):
        return [c for c in all_cases if (not args.quick or c[0] in quick) and (cases is None or c[0] in cases)]

    if args.keep:
        os.makedirs(args.keep, exist_ok=True)
        work, tmp = os.path.abspath(args.keep), None
    else:
        tmp = tempfile.TemporaryDirectory()
        work = tmp.name
    print(f"executable {args.exe}, {args.ranks} ranks, work dir {work}", flush=True)

    new2d, new3d = [], []
    if "seed" in parts:
        print("2D one disc, seed geometry (zero clearance), T = 1000 N m", flush=True)
        for label, mesh in pick(SEED, SEED_QUICK):
            new2d += run_case(args, work, "seed", label, 2, 1, "axis", "1000", mesh, False)
    if "mod" in parts:
        print("2D one disc, modified profile (clearances 17-20 um), T = 300, 1000 N m in one run", flush=True)
        for label, mesh in pick(MOD, MOD_QUICK):
            new2d += run_case(args, work, "mod", label, 2, 1, "axis", "300, 1000", mesh, True)
    if "3d" in parts:
        print("3D two discs, pins in the housing, seed geometry, T = 1000 N m", flush=True)
        for label, mesh in pick(THREE_D, THREE_D_QUICK):
            new3d += run_case(args, work, "3d", label, 3, 2, "housing", "1000", mesh, False)
    if "3d1" in parts:
        print("One disc, pins held at their cores: 3D against 2D on the same in-plane mesh, T = 1000 N m", flush=True)
        for label, dim, mesh in pick([(l, d, m) for l, d, m in ONE_DISC], ONE_DISC_QUICK):
            new3d += run_case(args, work, "3d1", label, dim, 1, "axis", "1000", mesh, False)

    os.makedirs(args.out, exist_ok=True)
    path2d = os.path.join(args.out, "contact-speed-2d.csv")
    path3d = os.path.join(args.out, "contact-speed-3d.csv")
    order = {}
    for part, lst in (("seed", SEED), ("mod", MOD), ("3d", THREE_D), ("3d1", ONE_DISC)):
        for i, c in enumerate(lst):
            order[(part, c[0])] = i
    rows2d = merge([] if args.fresh else read_csv(path2d, (int, float), missing_ok=True), new2d, order)
    rows3d = merge([] if args.fresh else read_csv(path3d, (int, float), missing_ok=True), new3d, order)
    notes = analyse(rows2d, rows3d)
    if new2d or (rows2d and args.fresh):
        write_csv(path2d, rows2d)
    if new3d or (rows3d and args.fresh):
        write_csv(path3d, rows3d)

    print("summary (error relative to the finest run of the part; wall = whole mpirun)")
    for n in notes:
        print("  " + n)
    groups = []
    for name, rows in (("2D seed", [r for r in rows2d if r["part"] == "seed"]),
                       ("2D modified, 300 and 1000 N m", [r for r in rows2d if r["part"] == "mod"]),
                       ("3D two discs", [r for r in rows3d if r["part"] == "3d"])):
        if not rows:
            continue
        for prefix in ("", "best_"):
            best = cheapest_within(rows, 1.0, prefix=prefix)
            if best:
                print(f"  {name}: cheapest within 1 % of {best[prefix + 'reference_case']}: {best['case']} "
                      f"(worst state T = {best['torque_Nm']:g} N m, "
                      f"{best['dofs']} DoFs, {best['total_wall_s']:.1f} s wall incl. meshing, "
                      f"err K_sec {best[prefix + 'err_K_secant_pct']:+.2f} %, "
                      f"K_tan {best[prefix + 'err_K_tangent_pct']:+.2f} %)")
            elif prefix == "" or any(r.get("best_reference_case") for r in rows):
                print(f"  {name}: no cheaper mesh within 1 % of the {prefix or 'finest '}reference")
    groups = [(name, rows) for name, rows in (
        ("2D one disc, seed, 1000 N m", [r for r in rows2d if r["part"] == "seed"]),
        ("2D one disc, modified, 300 + 1000 N m", [r for r in rows2d if r["part"] == "mod"]),
        ("3D two discs, housing, 1000 N m", [r for r in rows3d if r["part"] == "3d"])) if rows]
    if groups:
        plot(os.path.join(args.out, "contact-speed.png"), groups)
    if tmp:
        tmp.cleanup()


if __name__ == "__main__":
    main()
