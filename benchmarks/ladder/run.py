#!/usr/bin/python3
"""Scene ladder benchmark (issue #6): the seed case at the rated torque in
every scene, each over a sequence of meshes; the reference stiffness, the
error of every run against it and against its scene's finest mesh, the
error-against-cost chart with its Pareto front, cost against DoFs, 1 vs 2 MPI
ranks, and the seed's parameter study with the cheapest adequate FE scene.

One command (about 45 min on 2 cores shared with another job; --quick about
8 min):

    /usr/bin/python3 benchmarks/ladder/run.py [--part analytic,2d,3d1,3d2,ranks,reduced,seed-study]
        [--quick] [--exe build/cycloid-contact] [--out doc/ladder] [--analyse-only]

Rated torque and normalisation
  The stage torque is T = 1000 N m (the rated torque used throughout doc/).
  The two-disc scenes (analytic 'Number of discs = 2', 3D two discs) carry T
  with both discs at one rotation beta, each disc ~T/2. The one-disc scenes
  (2D rigid pins, 2D elastic pins, 3D one disc, and the analytic one-disc
  check) are therefore run at T/2 = 500 N m, the share of one disc, and
  reported as the stage stiffness 2 K_disc(T/2) (= T / beta of a stage whose
  discs both behave like the modelled one). The largest pin force is per
  (disc, pin) pair in every scene, so it compares directly. The CSV keeps
  the program's raw K (column K_*_raw) next to the stage value.

Parts (every FE run: Run = quasi-static, crank angle 0, unmodified seed profile
(zero clearance), --ranks MPI ranks (default 2), no VTU output):
  analytic    both pair models (seed, line-contact), two discs at T and one
              disc at T/2;
  2d          2D plane strain one disc, rigid pins and elastic pins (Pin
              support = axis), Contact refinements 0..3 (elastic 0..4) and
              cr1 + 2 adaptive cycles; and elastic pins on the in-plane meshes
              of the 3D scenes ("3D-plane c0.5 cr2/cr3": 3D/2D at matched
              meshes);
  3d1         3D one-disc slab (pins on their axes): c1 ax1 cr1, its first
              adaptive cycle, c0.5 ax1 cr2, c0.5 ax1 cr3;
  3d2         3D two discs, elastic pins seated in the housing: c1 ax1 cr1,
              and on the 2D scenes' in-plane mesh ("p25") ax1 cr1, ax2 cr1,
              ax1 cr2, ax1 cr2 loaded (refined at the loaded pins only;
              about 16 min). The reference is Richardson over p25 ax1
              cr1/cr2/cr3; cr3 (2.5 M DoFs, 18 GB, 24 min) and cr3 loaded
              (1.5 M DoFs, 11 GB, 14 min) run only with --cases
              "p25 ax1 cr3,p25 ax1 cr3 loaded" --timeout 3600; their rows
              are kept otherwise. The adaptive cycles run only with --cases. Plus
              the runs of doc/contact-speed-3d.csv (marked
              source=contact-speed, not rerun);
  reduced     Run = reduced (doc/reduced-model.md): 2D one disc (elastic pins on
              their axes) at its defaults and with cr0 w = 1 mm; 3D two discs
              (pins in the housing) at its defaults, with one axial slice, and
              on a coarser in-plane mesh (c0.5 p1.5 f2); dofs = the coarse
              model's;
  ranks       2D elastic cr1, cr3 and cr1+ad2, and 3D one disc c0.5 ax1 cr2,
              on 1 and 2 ranks back to back
              (rows with source = ranks, kept out of the error chart);
  seed-study  the pin-radius and eccentricity sweeps of the seed's Table 3
              with 2D elastic pins, cr1 + 2 adaptive cycles (the cheapest
              mesh within 0.1 % of the finest, doc/contact-speed.md), against
              both analytic models (one disc at T/2, same crank angle).

Every FE run is the whole `mpirun -np R cycloid-contact case.prm`, timed from
outside (meshing, set-up, solve included). Re-running a part replaces its rows
in doc/ladder/ladder.csv and keeps the others; --analyse-only rebuilds the
figures and the summary from the CSVs.

Outputs in --out (doc/ladder): ladder.csv, ranks.csv, seed-study-fe.csv,
error-vs-time.png, cost-vs-dofs.png, seed-study-fe.png, summary.txt. Read,
not written: ladder-before-14.csv, the ladder before issue #14's solver work;
cost-vs-dofs.png draws its fit beside the fit of every scene re-timed since.
"""
import argparse
import csv
import math
import os
import re
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import fit_power, read_csv, richardson, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# The ladder as it stood before issue #14's solver work (3D timed
# 2026-11-27): the cost chart draws its fits beside those of re-timed scenes.
BEFORE = os.path.join(ROOT, "doc", "ladder", "ladder-before-14.csv")
T_STAGE = 1000.0
RP_SEED = 2.2 * 40 / 0.675  # 130.370 mm, the pin circle held fixed in the e sweep

SCENES = ["analytic seed", "analytic line-contact", "2D rigid pins", "2D elastic pins",
          "3D one disc", "3D two discs", "reduced 2D elastic pins", "reduced 3D two discs"]
COLOURS = dict(zip(SCENES, ["C7", "C8", "C1", "C0", "C2", "C3", "C9", "C4"]))

# The reduced model (issue #13, doc/reduced-model.md): its coarse model's
# mesh is the label; "default" = every Mesh and Reduced entry at its default.
REDUCED_2D = [("default", {}),
              ("cr0 w1", {"Contact refinements": 0, "Load half-width": 1.0})]
REDUCED_3D = [("default", {}),
              ("1 slice", {"Axial slices per disc": 1}),
              ("c0.5 p1.5 f2", {"mesh": {"Contact element size": 0.5, "Pin element size": 1.5,
                                          "Flank element size": 2}})]


def c3(**kw):  # the 3D meshes of doc/contact-speed.md
    d = {"Contact element size": 1, "Flank element size": 1.5, "Pin element size": 1.5,
         "Coarse element size": 10, "Axial layers per disc": 1, "Contact refinements": 0}
    d.update({k.replace("_", " ").capitalize(): v for k, v in kw.items()})
    return d


CR = lambda n, ad=0: {"Contact refinements": n, **({"Adaptive refinement cycles": ad} if ad else {})}
TWO_D_RIGID = [(f"cr{n}", CR(n)) for n in range(0, 4)] + [("cr1+ad2", CR(1, 2))]
TWO_D_ELASTIC = [(f"cr{n}", CR(n)) for n in range(0, 5)] + [("cr1+ad2", CR(1, 2))]
# The in-plane meshes of the 3D scenes (coarser bulk: 10 mm, flank 1.5 mm):
# 3D/2D at matched meshes.
TWO_D_MATCHED = [("3D-plane c0.5 cr2", c3(contact_element_size=0.5, contact_refinements=2)),
                 ("3D-plane c0.5 cr3", c3(contact_element_size=0.5, contact_refinements=3)),
                 ("3D-plane c0.5 cr4", c3(contact_element_size=0.5, contact_refinements=4)),
                 ("3D-plane c0.5 cr5", c3(contact_element_size=0.5, contact_refinements=5))]
TWO_D_QUICK = ["cr0", "cr1", "cr1+ad2"]
THREE_D1 = [("c1 ax1 cr1", c3(contact_refinements=1)),
            ("c1 ax1 cr1+ad1", c3(contact_refinements=1, adaptive_refinement_cycles=1)),
            ("c0.5 ax1 cr2", c3(contact_element_size=0.5, contact_refinements=2)),
            ("c0.5 ax1 cr3", c3(contact_element_size=0.5, contact_refinements=3))]
THREE_D1_QUICK = ["c1 ax1 cr1"]
THREE_D1_ALL = list(THREE_D1)  # before --cases filters THREE_D1
# The richest scene. The a-priori runs c1 ax1 cr0..cr2, c0.5 ax1 cr2, c0.5 ax2
# cr2 and c0.5 ax1 cr3 (1.2 M DoFs, 20 min) are those of doc/contact-speed-3d.csv
# and are read from there, not rerun. The adaptive sequence (each cycle halves
# the cells next to the active contact nodes) would be nested for Richardson,
# but it refines only pins that are already engaged, and an adaptive cycle
# costs 7x the a-priori run in 3D (3D one disc: 56 s -> 402 s, 85 k -> 229 k
# DoFs, engaged pins 10 -> 9): run it with --cases 'c1 ax1 cr1+ad1,...'.
# "p25": the 2D scenes' in-plane sizes (contact 0.25, flank 1, pin 1, coarse 6
# mm, the prm defaults) extruded; in 2D these converge to 0.5 % at cr1.
P25 = lambda ax, n, side="both": {"Axial layers per disc": ax, "Contact refinements": n,
                                  **({"Contact refinement side": side} if side != "both" else {})}
THREE_D2 = [("c1 ax1 cr1", c3(contact_refinements=1)),
            ("p25 ax1 cr1", P25(1, 1)), ("p25 ax1 cr2", P25(1, 2)), ("p25 ax2 cr2", P25(2, 2)),
            ("p25 ax1 cr3", P25(1, 3)), ("p25 ax2 cr1", P25(2, 1)),
            # refined only at the pins that resist the torque (about half)
            ("p25 ax1 cr2 loaded", P25(1, 2, "loaded")), ("p25 ax1 cr3 loaded", P25(1, 3, "loaded")),
            ("c1 ax1 cr1+ad1", c3(contact_refinements=1, adaptive_refinement_cycles=1)),
            ("c1 ax1 cr1+ad2", c3(contact_refinements=1, adaptive_refinement_cycles=2))]
THREE_D2_DEFAULT = ["c1 ax1 cr1", "p25 ax1 cr1", "p25 ax2 cr1", "p25 ax1 cr2", "p25 ax1 cr2 loaded"]
# The reference: Richardson over these three nested meshes. The finest (2.5 M
# DoFs, 13.5 GB, about 30 min on 2 idle cores) is not in the default run:
# --part 3d2 --cases "p25 ax1 cr3" --timeout 3600.
REFERENCE_SEQUENCE = ["p25 ax1 cr1", "p25 ax1 cr2", "p25 ax1 cr3"]
THREE_D2_QUICK = ["c1 ax1 cr1"]
RANKS = ["cr1", "cr3", "cr1+ad2"]
RANKS_3D = ["c0.5 ax1 cr2"]  # 3D one disc, 1.5e5 DoFs: where parallel speed matters
RANKS_QUICK = ["cr1"]
SEED_MESH = ("cr1+ad2", CR(1, 2))
PIN_RADII = [2.5, 2.75, 3.0, 3.25, 3.5]
ECCENTRICITIES = [1.8, 2.0, 2.2, 2.4, 2.6]
PIN_RADII_QUICK = [2.5, 3.0, 3.5]
ECC_QUICK = [1.8, 2.2, 2.6]


# ---------------------------------------------------------------- running
def prm_text(out, run, dim=2, discs=1, pins="elastic", support="axis", torque=T_STAGE, mesh=None,
             geometry=None, model=None):
    L = [f"set Run = {run}", f"set Output directory = {out}"]
    if run != "analytic":
        L.append("set Write solution = false")
    if geometry:
        L += ["subsection Geometry"] + [f"  set {k} = {v}" for k, v in geometry.items()] + ["end"]
    L += ["subsection Scene", f"  set Dimension = {dim}", f"  set Number of discs = {discs}",
          f"  set Pins = {pins}", f"  set Pin support = {support}", "end",
          "subsection Loading", f"  set Torque = {torque:g}", "  set Crank angle = 0", "end"]
    if model:
        L += ["subsection Analytic", f"  set Pair stiffness model = {model}", "end"]
    if mesh is not None:
        # The mesh asked for (Target accuracy = auto would refine 2D).
        L += ["subsection Mesh", "  set Contact refinement radius = 0.3", "  set Target accuracy = 0"]
        L += [f"  set {k} = {v}" for k, v in mesh.items()] + ["end"]
    return "\n".join(L) + "\n"


def run_one(args, work, tag, text, ranks=None, mpi=True):
    """Run one prm; return (row dict from stiffness.csv or None, wall, status, log tail)."""
    tag = re.sub(r"[^A-Za-z0-9.]+", "_", tag)
    out = os.path.join(work, tag)
    prm = out + ".prm"
    with open(prm, "w") as f:
        f.write(text.replace("__OUT__", out))
    load = os.getloadavg()[0]
    p = run_cycloid((ranks or args.ranks) if mpi else None, args.exe, prm, log=out + ".log",
                    timeout=args.timeout)
    status = f"timeout {args.timeout:.0f} s" if p.timed_out else "ok" if p.returncode == 0 else f"exit {p.returncode}"
    path = os.path.join(out, "stiffness.csv")
    row = None
    if status == "ok" and os.path.exists(path):
        rows = read_csv(path)
        row = rows[-1] if rows else None
    if row is None:
        tail = " | ".join(p.stdout.strip().splitlines()[-4:])
        print(f"  !! {tag}: {status}: {tail}", flush=True)
    return row, p.wall_s, status, load


def fe_row(args, work, scene, label, ranks, text, per_disc, extra=None):
    r, wall, status, load = run_one(args, work, f"{scene}_{label}_np{ranks}", text, ranks)
    row = {"scene": scene, "mesh": label, "ranks": ranks, "source": "ladder", "status": status,
           "wall_s": wall, "load_avg_at_start": load, "normalisation": "2 x one disc at T/2" if per_disc else "stage"}
    row.update(extra or {})
    if r:
        f = 2.0 if per_disc else 1.0
        row.update({"torque_Nm": float(r["torque_Nm"]), "dofs": int(r["dofs"]),
                    "K_secant_raw": float(r["K_secant_Nm_per_rad"]),
                    "K_tangent_raw": float(r["K_tangent_Nm_per_rad"]),
                    "K_secant": f * float(r["K_secant_Nm_per_rad"]),
                    "K_tangent": f * float(r["K_tangent_Nm_per_rad"]),
                    "max_pin_force_N": float(r["max_pin_force_N"]),
                    "pins_in_contact": int(r["pins_in_contact"]),
                    "active_set_iterations": int(r["active_set_iterations"]),
                    "linear_iterations": r.get("linear_iterations", ""),
                    "peak_memory_MB": float(r.get("peak_memory_MB") or "nan"),
                    "program_wall_s": float(r["wall_s"])})
        print(f"  {scene:22s} {label:16s} np{ranks} dofs {row['dofs']:8d} K_sec {row['K_secant']:.5e} "
              f"K_tan {row['K_tangent']:.5e} pins {row['pins_in_contact']:2d} it {row['active_set_iterations']:2d} "
              f"Fmax {row['max_pin_force_N']:7.1f} N  wall {wall:7.1f} s  mem {row['peak_memory_MB']:.0f} MB  "
              f"load {load:.1f}", flush=True)
    return row


def pick(lst, quick, args):
    return [c for c in lst if not args.quick or c[0] in quick]


def part_analytic(args, work):
    rows = []
    for model in ("seed", "line-contact"):
        for discs, torque in ((2, T_STAGE), (1, T_STAGE / 2)):
            text = prm_text("__OUT__", "analytic", discs=discs, torque=torque, model=model)
            r, wall, status, load = run_one(args, work, f"analytic_{model}_{discs}", text, mpi=False)
            f = 2.0 if discs == 1 else 1.0
            row = {"scene": f"analytic {model}", "mesh": f"{discs} disc(s)", "ranks": 1, "source": "ladder",
                   "status": status, "wall_s": wall, "load_avg_at_start": load,
                   "normalisation": "2 x one disc at T/2" if discs == 1 else "stage"}
            if r:
                row.update({"torque_Nm": float(r["torque_Nm"]), "dofs": 0,
                            "K_secant_raw": float(r["K_secant_Nm_per_rad"]),
                            "K_tangent_raw": float(r["K_tangent_Nm_per_rad"]),
                            "K_secant": f * float(r["K_secant_Nm_per_rad"]),
                            "K_tangent": f * float(r["K_tangent_Nm_per_rad"]),
                            "max_pin_force_N": float(r["max_pin_force_N"]),
                            "pins_in_contact": int(r["pins_in_contact"]),
                            "active_set_iterations": int(r["active_set_iterations"]),
                            "peak_memory_MB": float(r.get("peak_memory_MB") or "nan"),
                            "program_wall_s": float(r["wall_s"])})
                print(f"  {row['scene']:22s} {row['mesh']:10s} K_sec {row['K_secant']:.5e} K_tan {row['K_tangent']:.5e} "
                      f"pins {row['pins_in_contact']} Fmax {row['max_pin_force_N']:.1f} N wall {wall:.2f} s "
                      f"(solve {row['program_wall_s'] * 1e3:.2f} ms)", flush=True)
            rows.append(row)
    return rows


def part_2d(args, work):
    rows = []
    for pins, lst, scene in (("elastic", TWO_D_ELASTIC, "2D elastic pins"), ("rigid", TWO_D_RIGID, "2D rigid pins"),
                             ("elastic", TWO_D_MATCHED, "2D elastic pins")):
        for label, mesh in pick(lst, TWO_D_QUICK, args):
            text = prm_text("__OUT__", "quasi-static", 2, 1, pins, "axis", T_STAGE / 2, mesh)
            rows.append(fe_row(args, work, scene, label, args.ranks, text, True))
    return rows


def part_3d1(args, work):
    return [fe_row(args, work, "3D one disc", label, args.ranks,
                   prm_text("__OUT__", "quasi-static", 3, 1, "elastic", "axis", T_STAGE / 2, mesh), True)
            for label, mesh in pick(THREE_D1, THREE_D1_QUICK, args)]


def part_3d2(args, work):
    return [fe_row(args, work, "3D two discs", label, args.ranks,
                   prm_text("__OUT__", "quasi-static", 3, 2, "elastic", "housing", T_STAGE, mesh), False)
            for label, mesh in pick(THREE_D2, THREE_D2_QUICK, args)
            if args.cases or label in THREE_D2_DEFAULT]


def reduced_text(dim, discs, support, torque, settings):
    text = prm_text("__OUT__", "reduced", dim, discs, "elastic", support, torque)
    settings = dict(settings)
    mesh = settings.pop("mesh", {})
    if mesh:
        text += "subsection Mesh\n" + "".join(f"  set {k} = {v}\n" for k, v in mesh.items()) + "end\n"
    if settings:
        text += "subsection Reduced\n" + "".join(f"  set {k} = {v}\n" for k, v in settings.items()) + "end\n"
    return text


def part_reduced(args, work):
    """Run = reduced: 2D one disc (T/2, doubled like the 2D FE scenes) and
    3D two discs with the pins in the housing (the stage); dofs are the coarse
    model's."""
    rows = [fe_row(args, work, "reduced 2D elastic pins", label, args.ranks,
                   reduced_text(2, 1, "axis", T_STAGE / 2, s), True) for label, s in REDUCED_2D]
    rows += [fe_row(args, work, "reduced 3D two discs", label, args.ranks,
                    reduced_text(3, 2, "housing", T_STAGE, s), False) for label, s in REDUCED_3D]
    return rows


def part_ranks(args, work):
    """The same 2D elastic meshes on 1 and 2 ranks, back to back (source = ranks:
    timing rows kept out of the error chart, which uses part 2d)."""
    rows = []
    meshes = dict(TWO_D_ELASTIC)
    for label in (RANKS_QUICK if args.quick else RANKS):
        text = prm_text("__OUT__", "quasi-static", 2, 1, "elastic", "axis", T_STAGE / 2, meshes[label])
        for ranks in (1, 2):
            rows.append(dict(fe_row(args, work, "2D elastic pins", label, ranks, text, True), source="ranks"))
    meshes = dict(THREE_D1_ALL)
    for label in ([] if args.quick else RANKS_3D):
        text = prm_text("__OUT__", "quasi-static", 3, 1, "elastic", "axis", T_STAGE / 2, meshes[label])
        for ranks in (1, 2):
            rows.append(dict(fe_row(args, work, "3D one disc", label, ranks, text, True), source="ranks"))
    return rows


def earlier_3d():
    """The 3D two-disc runs of doc/contact-speed-3d.csv (1000 N m, 2 ranks, VTU output on)."""
    rows = []
    for r in read_csv(os.path.join(ROOT, "doc", "contact-speed-3d.csv"), NUMBERS, missing_ok=True):
        if r.get("part") != "3d" or r.get("status") != "ok":
            continue
        rows.append({"scene": "3D two discs", "mesh": r["case"], "ranks": 2, "source": "contact-speed",
                     "status": "ok", "wall_s": r["total_wall_s"], "load_avg_at_start": r["load_avg_at_start"],
                     "normalisation": "stage", "torque_Nm": r["torque_Nm"], "dofs": r["dofs"],
                     "K_secant_raw": r["K_secant_Nm_per_rad"], "K_tangent_raw": r["K_tangent_Nm_per_rad"],
                     "K_secant": r["K_secant_Nm_per_rad"], "K_tangent": r["K_tangent_Nm_per_rad"],
                     "max_pin_force_N": r["max_pin_force_N"], "pins_in_contact": r["pins_in_contact"],
                     "active_set_iterations": r["active_set_iterations"], "peak_memory_MB": "",
                     "program_wall_s": r["state_wall_s"]})
    return rows


def part_seed_study(args, work):
    """FE (2D elastic, cr1+ad2, one disc at T/2) and both analytic models over rrp and e."""
    rows = []
    rr = PIN_RADII_QUICK if args.quick else PIN_RADII
    ee = ECC_QUICK if args.quick else ECCENTRICITIES
    ecc = lambda v: {"Eccentricity": v, "Shortening coefficient": f"{v * 40 / RP_SEED:.9f}"}
    points = [("pin radius", v, {"Pin radius": v}, T_STAGE) for v in rr]
    points += [("eccentricity", v, ecc(v), T_STAGE) for v in ee]
    # seed-study.md's local maximum in e: modification A (clearances 0-2.6 um)
    # at an intermediate stage torque, 300 N m.
    points += [("eccentricity, modification A, 300 N m", v,
                dict(ecc(v), **{"Pin circle radius modification": 0.01, "Pin radius modification": 0.01}), 300.0)
               for v in ee]
    tags = {"pin radius": "rrp", "eccentricity": "e", "eccentricity, modification A, 300 N m": "eA300"}
    points = [p for p in points if args.sweeps is None or tags[p[0]] in args.sweeps.split(",")]
    for sweep, v, geo, torque in points:
        base = {"sweep": sweep, "value": v, "torque_Nm": torque}
        for model in ("seed", "line-contact"):
            text = prm_text("__OUT__", "analytic", discs=1, torque=torque / 2, model=model, geometry=geo)
            r, wall, status, _ = run_one(args, work, f"ss_{sweep}_{v}_{model}", text, mpi=False)
            row = dict(base, model=f"analytic {model}", status=status, wall_s=wall)
            if r:
                row.update({"K_secant": 2 * float(r["K_secant_Nm_per_rad"]),
                            "K_tangent": 2 * float(r["K_tangent_Nm_per_rad"]),
                            "max_pin_force_N": float(r["max_pin_force_N"]),
                            "pins_in_contact": int(r["pins_in_contact"]), "dofs": 0})
            rows.append(row)
        if args.seed_study_fe:
            text = prm_text("__OUT__", "quasi-static", 2, 1, "elastic", "axis", torque / 2, SEED_MESH[1], geometry=geo)
            fr = fe_row(args, work, "2D elastic pins", f"{SEED_MESH[0]} {sweep} {v}", args.ranks, text, True)
            row = dict(base, model=f"FE 2D elastic {SEED_MESH[0]}", status=fr["status"], wall_s=fr["wall_s"])
            for k in ("K_secant", "K_tangent", "max_pin_force_N", "pins_in_contact", "dofs"):
                row[k] = fr.get(k, "")
            rows.append(row)
        for r in rows[-3:]:
            if r.get("K_secant", "") != "":
                print(f"  seed-study {sweep} {v}: {r['model']:28s} K_sec {r['K_secant']:.4e} K_tan {r['K_tangent']:.4e} "
                      f"pins {r['pins_in_contact']} Fmax {r['max_pin_force_N']:.0f}", flush=True)
    return rows


# ---------------------------------------------------------------- CSV helpers
NUMBERS = (int, float)  # the CSV files' numbers as read back: ints, else floats
COLUMNS = ["scene", "mesh", "ranks", "source", "normalisation", "torque_Nm", "dofs", "K_secant", "K_tangent",
           "K_secant_raw", "K_tangent_raw", "max_pin_force_N", "pins_in_contact", "active_set_iterations",
           "linear_iterations", "wall_s", "program_wall_s", "peak_memory_MB", "load_avg_at_start",
           "err_K_secant_pct", "err_K_tangent_pct", "err_Fmax_pct", "own_finest", "own_err_K_secant_pct",
           "own_err_K_tangent_pct", "own_err_Fmax_pct", "pareto", "status"]
SS_COLUMNS = ["sweep", "value", "torque_Nm", "model", "K_secant", "K_tangent", "max_pin_force_N", "pins_in_contact", "dofs",
              "wall_s", "status"]


def fmt(v):
    if isinstance(v, float):
        return "nan" if math.isnan(v) else f"{v:.6g}"
    return v


def write_csv(path, rows, cols):
    with open(path, "w", newline="") as f:
        w = csv.writer(f)
        w.writerow(cols)
        for r in rows:
            w.writerow([fmt(r.get(c, "")) for c in cols])
    print("written", os.path.relpath(path, ROOT))


def has_k(r):
    return isinstance(r.get("K_secant"), float) or isinstance(r.get("K_secant"), int)


# ---------------------------------------------------------------- analysis
def reference(rows, notes):
    """Reference K (secant, tangent) and largest pin force from the richest
    scene; returns (dict, description)."""
    two = [r for r in rows if r["scene"] == "3D two discs" and has_k(r) and r["ranks"] == 2]
    if not two:
        return None
    # The nested a-priori sequence: each contact refinement halves the cells
    # at every contact of the same gmsh mesh (refinement ratio 2).
    seq = [r for r in two if r["source"] == "ladder" and r["mesh"] in REFERENCE_SEQUENCE]
    seq.sort(key=lambda r: r["dofs"])
    finest = max(two, key=lambda r: r["dofs"])
    ref = {"case": f"{finest['mesh']} ({finest['source']})"}
    asym = True
    for key in ("K_secant", "K_tangent", "max_pin_force_N"):
        vals = [r[key] for r in seq]
        ext = p = None
        if len(vals) >= 3:
            ext, p = richardson(*vals[-3:])
        if ext is not None and 0.5 <= p <= 4.0:
            ref[key] = ext
            # Conservative band: the last change of the sequence (the
            # extrapolation's own estimate, |finest - ext|, is smaller).
            ref[key + "_err_pct"] = 100 * abs(vals[-1] - vals[-2]) / abs(ext)
            ref[key + "_how"] = f"Richardson, order {p:.1f}"
            notes.append(f"reference {key}: Richardson from {[r['mesh'] for r in seq[-3:]]} = {ext:.5g} "
                         f"(order {p:.2f}); finest of that sequence {100 * (vals[-1] - ext) / ext:+.2f} % from it; "
                         f"error band {ref[key + '_err_pct']:.2f} % (the last change)")
        else:
            asym = False
            # Not asymptotic: the finest run, its error estimated from the
            # spread of the scene's last meshes (no pretence of an order).
            tail = seq[-3:] if len(seq) >= 2 else sorted(two, key=lambda r: r["dofs"])[-3:]
            spread = max(abs(r[key] - finest[key]) for r in tail[:-1]) if len(tail) > 1 else float("nan")
            ref[key] = finest[key]
            ref[key + "_err_pct"] = 100 * spread / abs(finest[key])
            ref[key + "_how"] = "finest run, not asymptotic"
            why = (f"sequence {[r['mesh'] for r in seq[-3:]]}: {', '.join(f'{v:.4g}' for v in vals[-3:])}"
                   if len(vals) >= 3 else f"only {len(vals)} nested meshes")
            notes.append(f"reference {key}: NOT asymptotic ({why}{'' if ext is None else f', order {p:.2f}'}); "
                         f"using the finest run {ref['case']} = {finest[key]:.5g}, error estimate "
                         f">= {ref[key + '_err_pct']:.1f} % (largest change among the sequence's meshes)")
    ref["asymptotic"] = asym
    if not asym:
        finest["is_reference"] = True
    return ref


def cross_check(rows, notes):
    """Scene ratios at matched in-plane meshes (2D on the 3D in-plane mesh,
    3D one disc, 3D two discs) and the 3D two-disc K they imply once the
    2D sequence on that in-plane mesh is converged in its contact refinement."""
    def get(scene, mesh):
        rr = [r for r in rows if r["scene"] == scene and r["mesh"] == mesh and has_k(r) and r["ranks"] == 2
              and r["source"] != "ranks"]
        return rr[0] if rr else None
    ratio = {}
    for n in (2, 3):
        p2, d1, d2 = (get("2D elastic pins", f"3D-plane c0.5 cr{n}"), get("3D one disc", f"c0.5 ax1 cr{n}"),
                      get("3D two discs", f"c0.5 ax1 cr{n}"))
        for key in ("K_secant", "K_tangent"):
            if p2 and d1:
                notes.append(f"matched mesh c0.5 cr{n} {key}: 3D one disc / 2D = {d1[key] / p2[key]:.4f}")
            if d1 and d2:
                notes.append(f"matched mesh c0.5 cr{n} {key}: 3D two discs / 3D one disc = {d2[key] / d1[key]:.4f}")
            if p2 and d2:
                ratio[(n, key)] = d2[key] / p2[key]
                notes.append(f"matched mesh c0.5 cr{n} {key}: 3D two discs / 2D = {ratio[(n, key)]:.4f}")
    for n in (1, 2, 3):  # the 2D scenes' own in-plane mesh ("p25")
        p2, d2 = get("2D elastic pins", f"cr{n}"), get("3D two discs", f"p25 ax1 cr{n}")
        if p2 and d2:
            notes.append(f"matched mesh p25 cr{n}: 3D two discs / 2D = K_secant {d2['K_secant'] / p2['K_secant']:.4f}, "
                         f"K_tangent {d2['K_tangent'] / p2['K_tangent']:.4f}")
    seq = [get("2D elastic pins", f"3D-plane c0.5 cr{n}") for n in (3, 4, 5)]
    fine = get("2D elastic pins", "cr4")
    for key in ("K_secant", "K_tangent"):
        vals = [r[key] for r in seq if r]
        if len(vals) == 3 and (3, key) in ratio:
            ext, p = richardson(*vals)
            conv = ext if ext is not None else vals[-1]
            est = ratio[(3, key)] * conv
            notes.append(f"2D on the 3D in-plane mesh, {key} cr3..cr5: {', '.join(f'{v:.5g}' for v in vals)}; "
                         + (f"Richardson {ext:.5g} (order {p:.2f})" if ext is not None else "not monotone, finest used")
                         + f" -> implied converged-contact 3D two-disc {key} = {ratio[(3, key)]:.4f} x {conv:.5g} "
                         f"= {est:.5g} (same coarse bulk mesh)"
                         + (f"; bulk: 2D c0.25 cr4 / 2D 3D-plane finest = {fine[key] / vals[-1]:.4f}" if fine else ""))


def family(r):
    """A scene's own mesh family (the 2D runs on the 3D in-plane mesh are their own)."""
    return (r["scene"], str(r["mesh"]).startswith("3D-plane"))


def add_errors(rows, ref):
    by_scene = {}
    for r in rows:
        if r["source"] == "ranks":
            continue
        if has_k(r) and r["ranks"] == 2 or (has_k(r) and r["scene"].startswith("analytic")):
            by_scene.setdefault(family(r), []).append(r)
    finest = {s: max(rr, key=lambda r: (r["dofs"], r["wall_s"])) for s, rr in by_scene.items()}
    for r in rows:
        if not has_k(r):
            continue
        if ref:
            for key, e in (("K_secant", "err_K_secant_pct"), ("K_tangent", "err_K_tangent_pct"),
                           ("max_pin_force_N", "err_Fmax_pct")):
                r[e] = 100 * (r[key] - ref[key]) / ref[key]
        f = finest.get(family(r))
        if f and not r["scene"].startswith("analytic"):
            r["own_finest"] = f["mesh"]
            for key, e in (("K_secant", "own_err_K_secant_pct"), ("K_tangent", "own_err_K_tangent_pct"),
                           ("max_pin_force_N", "own_err_Fmax_pct")):
                r[e] = 100 * (r[key] - f[key]) / f[key]


def chart_points(rows):
    """(scene, mesh, wall, errK, errF, row) per run on 2 ranks (analytic: 1 process)."""
    pts = []
    for r in rows:
        if not has_k(r) or r.get("err_K_secant_pct", "") == "":
            continue
        if r["scene"].startswith("analytic") and r["normalisation"] != "stage":
            continue
        if not r["scene"].startswith("analytic") and r["ranks"] != 2:
            continue
        if r.get("is_reference") or r["source"] == "ranks":
            continue  # zero error by definition; timing duplicates
        ek = max(abs(r["err_K_secant_pct"]), abs(r["err_K_tangent_pct"]))
        pts.append((r["scene"], r["mesh"], float(r["wall_s"]), ek, abs(r["err_Fmax_pct"]), r))
    return pts


def pareto(pts, idx):
    """Indices of the points not dominated in (wall, error[idx])."""
    order = sorted(range(len(pts)), key=lambda i: (pts[i][2], pts[i][idx]))
    front, best = [], float("inf")
    for i in order:
        if pts[i][idx] < best:
            front.append(i)
            best = pts[i][idx]
    return front


def plot_error(path, pts, ref):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    for ax, idx, what in ((axes[0], 3, "K (max of secant, tangent)"), (axes[1], 4, "largest pin force")):
        seen = set()
        for s, m, w, ek, ef, r in pts:
            e = max((ek, ef)[idx - 3], 1e-2)
            mk = "s" if r["source"] == "contact-speed" else ("^" if "+ad" in m else "o")
            ax.loglog(w, e, mk, color=COLOURS.get(s, "k"), mfc="none" if r["source"] == "contact-speed" else None,
                      ms=6, label=s if s not in seen else None)
            seen.add(s)
            ax.annotate(m.replace(" disc(s)", "d"), (w, e), textcoords="offset points", xytext=(3, 2),
                        fontsize=5, color=COLOURS.get(s, "k"))
        front = pareto(pts, idx)
        fx = [pts[i][2] for i in front]
        fy = [max((pts[i][3], pts[i][4])[idx - 3], 1e-2) for i in front]
        ax.step(fx, fy, where="post", color="k", lw=1.0, ls="-", alpha=0.6, label="Pareto front")
        ax.plot(fx, fy, "o", ms=11, mfc="none", mec="k", alpha=0.6)
        band = (max(ref.get("K_secant_err_pct", float("nan")), ref.get("K_tangent_err_pct", float("nan")))
                if idx == 3 else ref.get("max_pin_force_N_err_pct", float("nan")))
        if band == band:
            ax.axhspan(1e-2, band, color="0.85", zorder=0, label=f"reference uncertainty ({band:.1f} %)")
        ax.set_xlabel("wall time [s] (whole command; FE: mpirun -np 2 incl. meshing)", fontsize=8)
        ax.set_ylabel(f"|error| of {what} vs reference [%]")
        ax.grid(True, which="both", lw=0.3)
        ax.legend(fontsize=6, loc="best")
    fig.suptitle(f"Scene ladder, seed case, stage torque {T_STAGE:g} N m (one-disc scenes: 2 x one disc at "
                 f"{T_STAGE / 2:g} N m);\nreference {ref['case']}: "
                 + ", ".join(f"{k.split('_')[0] if k != 'max_pin_force_N' else 'F_max'}"
                             f"{'_' + k.split('_')[1][:3] if k.startswith('K_') else ''} "
                             f"{ref.get(k + '_how', '')} (+-{ref.get(k + '_err_pct', float('nan')):.2f} %)"
                             for k in ('K_secant', 'K_tangent', 'max_pin_force_N'))
                 + ";\n"
                 "filled: this benchmark, open squares: doc/contact-speed-3d.csv; triangles: adaptive; floor 0.01 %",
                 fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print("written", os.path.relpath(path, ROOT))


def fitted_runs(rows, scene):
    """The runs of @p scene that the cost fit uses: this benchmark's own
    (one timing condition; the contact-speed rows were timed under another
    load), a-priori meshes, 2 ranks."""
    return [r for r in rows if r["scene"] == scene and r.get("source") == "ladder" and r["ranks"] == 2
            and "+ad" not in r["mesh"] and "3D-plane" not in r["mesh"] and has_k(r)
            and isinstance(r.get("dofs"), int) and r["dofs"] > 0]


def plot_cost(path, rows, notes):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.5, 4.6))
    fe = [r for r in rows if has_k(r) and not r["scene"].startswith("analytic") and r["ranks"] == 2
          and r["source"] != "ranks"
          and isinstance(r.get("dofs"), int) and r["dofs"] > 0]
    groups = {}
    for r in fe:
        fam = "adaptive" if "+ad" in r["mesh"] else "a-priori"
        groups.setdefault((r["scene"], fam), []).append(r)
        ax.loglog(r["dofs"], r["wall_s"], "^" if fam == "adaptive" else ("s" if r["source"] != "ladder" else "o"),
                  color=COLOURS[r["scene"]], mfc="none" if r["source"] != "ladder" else None, ms=5)
    before = {s: fitted_runs(read_csv(BEFORE, NUMBERS, missing_ok=True), s) for s in SCENES[2:]}
    for s in SCENES[2:]:
        rr = fitted_runs(fe, s)
        if len(rr) >= 2:
            a, b = fit_power([r["dofs"] for r in rr], [r["wall_s"] for r in rr])
            xs = sorted(r["dofs"] for r in rr)
            ax.plot(xs, [a * x ** b for x in xs], "-", color=COLOURS[s], lw=0.8, label=f"{s}: wall ~ DoFs^{b:.2f}")
            notes.append(f"cost fit {s} (a-priori meshes, {len(rr)} runs): wall ~ DoFs^{b:.2f}")
        old = before[s]
        if len(old) >= 2 and {r["wall_s"] for r in old} != {r["wall_s"] for r in rr}:
            # The scene was re-timed: its fit before issue #14 beside it.
            a, b = fit_power([r["dofs"] for r in old], [r["wall_s"] for r in old])
            xs = sorted(r["dofs"] for r in old)
            ax.plot(xs, [a * x ** b for x in xs], ":", color=COLOURS[s], lw=1.2,
                    label=f"{s}, before #14: wall ~ DoFs^{b:.2f}")
            ax.plot([r["dofs"] for r in old], [r["wall_s"] for r in old], "x", color=COLOURS[s], ms=4)
            notes.append(f"cost fit {s} before issue #14 ({os.path.basename(BEFORE)}, {len(old)} runs): "
                         f"wall ~ DoFs^{b:.2f}")
    # Above 1e5 DoFs the fixed costs (gmsh, set-up: a few s) no longer
    # dominate; 2D and 3D runs mixed, a-priori meshes of this benchmark.
    big = [r for r in fe if r["dofs"] >= 1e5 and r["source"] == "ladder" and "+ad" not in r["mesh"]
           and not r["scene"].startswith("reduced")]
    if len(big) >= 2:
        a, b = fit_power([r["dofs"] for r in big], [r["wall_s"] for r in big])
        xs = [min(r["dofs"] for r in big), max(r["dofs"] for r in big)]
        ax.plot(xs, [a * x ** b for x in xs], "k--", lw=1, label=f"all a-priori runs >= 1e5 DoFs: wall ~ DoFs^{b:.2f}")
        notes.append(f"cost fit all a-priori FE runs of this benchmark with >= 1e5 DoFs ({len(big)}): "
                     f"wall ~ DoFs^{b:.2f}")
    ax.set_xlabel("DoFs (final mesh; reduced: its coarse model)")
    ax.set_ylabel("wall time [s] (2 ranks, incl. meshing)")
    ax.set_title("Cost against DoFs (triangles adaptive, open squares doc/contact-speed-3d.csv,\n"
                 "timed under load and not fitted; x and dotted: before issue #14)", fontsize=8)
    ax.grid(True, which="both", lw=0.3)
    ax.legend(fontsize=6)
    fig.tight_layout()
    fig.savefig(path, dpi=100)
    plt.close(fig)
    print("written", os.path.relpath(path, ROOT))


def plot_seed_study(path, rows):
    """Top: stage K (log scale); bottom: K relative to the seed point (rrp = 3, e = 2.2)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    cols = [("pin radius", "pin radius rrp [mm]", 3.0),
            ("eccentricity", "e [mm] (pin circle fixed, rp = 130.37 mm)", 2.2),
            ("eccentricity, modification A, 300 N m", "e [mm]; modification A (+0.01/+0.01 mm), 300 N m", 2.2)]
    cols = [c for c in cols if any(r["sweep"] == c[0] for r in rows)]
    fig, axes = plt.subplots(2, len(cols), figsize=(5 * len(cols), 7), sharex="col", squeeze=False)
    for col, (sweep, xl, seed_x) in enumerate(cols):
        for model, st in (("analytic seed", "C7--"), ("analytic line-contact", "C8-"),
                          (f"FE 2D elastic {SEED_MESH[0]}", "C0o-")):
            rr = sorted((r for r in rows if r["sweep"] == sweep and r["model"] == model and has_k(r)),
                        key=lambda r: r["value"])
            if not rr:
                continue
            x = [r["value"] for r in rr]
            base = [r for r in rr if abs(r["value"] - seed_x) < 1e-9]
            for key, mk, lab in (("K_secant", st, "K_secant"), ("K_tangent", st[:2] + "s:", "K_tangent")):
                if key == "K_tangent" and not model.startswith("FE") and "modification" not in sweep:
                    continue  # the analytic secant and tangent differ only with clearance
                axes[0, col].semilogy(x, [r[key] for r in rr], mk, ms=4, mfc="none" if key == "K_tangent" else None,
                                      label=f"{model}, {lab}")
                if base:
                    axes[1, col].plot(x, [r[key] / base[0][key] for r in rr], mk, ms=4,
                                      mfc="none" if key == "K_tangent" else None, label=f"{model}, {lab}")
        axes[0, col].set_ylabel("stage stiffness [N m/rad]")
        axes[1, col].set_ylabel(f"K / K(seed point, {seed_x:g} mm)")
        axes[1, col].set_xlabel(xl)
        for ax in axes[:, col]:
            ax.grid(True, which="both", lw=0.3)
            ax.legend(fontsize=6)
    fig.suptitle(f"Seed's Table 3 sweeps, stage torque {T_STAGE:g} N m unless noted (2 x one disc at half of it), "
                 "crank angle 0, unmodified profile unless noted; FE: 2D plane strain, elastic pins, cr1 + 2 adaptive "
                 "cycles", fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=90)
    plt.close(fig)
    print("written", os.path.relpath(path, ROOT))


def analyse(args):
    notes = []
    rows = read_csv(os.path.join(args.out, "ladder.csv"), NUMBERS, missing_ok=True)
    rows = [r for r in rows if r.get("source") != "contact-speed"] + earlier_3d()
    derived = [c for c in COLUMNS if c.startswith(("err_", "own_")) or c == "pareto"]
    for r in rows:  # recomputed below
        for c in derived:
            r[c] = ""
    ref = reference(rows, notes)
    add_errors(rows, ref)
    cross_check(rows, notes)
    pts = chart_points(rows) if ref else []
    for idx, what in ((3, "K"), (4, "Fmax")):
        for i in pareto(pts, idx) if pts else []:
            s, m, w, ek, ef, r = pts[i]
            r["pareto"] = (r.get("pareto", "") + f" {what}").strip()
    order = {s: i for i, s in enumerate(SCENES)}
    rows.sort(key=lambda r: (order.get(r["scene"], 9), r["source"] != "ladder", r["ranks"],
                             r["dofs"] if isinstance(r.get("dofs"), int) else 0, r["wall_s"]))
    write_csv(os.path.join(args.out, "ladder.csv"), rows, COLUMNS)
    if ref:
        notes.insert(0, f"reference: K_secant {ref['K_secant']:.5g}, K_tangent {ref['K_tangent']:.5g} N m/rad, "
                        f"Fmax {ref['max_pin_force_N']:.5g} N from {ref['case']}; asymptotic: {ref['asymptotic']}")
        plot_error(os.path.join(args.out, "error-vs-time.png"), pts, ref)
        for s, m, w, ek, ef, r in sorted(pts, key=lambda p: (order.get(p[0], 9), p[2])):
            own = r.get("own_err_K_secant_pct", "")
            notes.append(f"  {s:22s} {m:16s} {r['dofs'] if r['dofs'] else 0:8d} DoFs {w:8.1f} s  K_sec {r['K_secant']:.4e} "
                         f"K_tan {r['K_tangent']:.4e} err K_sec {r['err_K_secant_pct']:+7.2f} % K_tan "
                         f"{r['err_K_tangent_pct']:+7.2f} % Fmax {r['max_pin_force_N']:7.1f} N ({r['err_Fmax_pct']:+6.2f} %)"
                         + (f"  vs own finest {r['own_finest']}: K_sec {own:+.2f} % K_tan {r['own_err_K_tangent_pct']:+.2f} %"
                            if own != "" else "") + ("  [Pareto " + r["pareto"] + "]" if r.get("pareto") else "")
                         + ("  [contact-speed]" if r["source"] != "ladder" else ""))
    if any(has_k(r) and not r["scene"].startswith("analytic") for r in rows):
        plot_cost(os.path.join(args.out, "cost-vs-dofs.png"), rows, notes)
    # 1 vs 2 ranks
    rk = [r for r in rows if r["scene"] in ("2D elastic pins", "3D one disc") and has_k(r)]
    table = []
    for sc, m in sorted({(r["scene"], r["mesh"]) for r in rk if r["ranks"] == 1}):
        # Prefer the back-to-back pair of part ranks; else the 2-rank run of part 2d.
        one = [r for r in rk if (r["scene"], r["mesh"]) == (sc, m) and r["ranks"] == 1]
        two = [r for r in rk if (r["scene"], r["mesh"]) == (sc, m) and r["ranks"] == 2 and r["source"] == "ranks"] or \
              [r for r in rk if (r["scene"], r["mesh"]) == (sc, m) and r["ranks"] == 2]
        if one and two:
            a, b = one[-1], two[0]
            table.append({"scene": sc, "mesh": m, "pair": "back to back" if b["source"] == "ranks" else "separate runs",
                          "dofs_1": a["dofs"], "dofs_2": b["dofs"], "wall_1_s": a["wall_s"],
                          "wall_2_s": b["wall_s"], "speedup": a["wall_s"] / b["wall_s"],
                          "program_wall_1_s": a["program_wall_s"], "program_wall_2_s": b["program_wall_s"],
                          "solve_speedup": a["program_wall_s"] / b["program_wall_s"],
                          "K_secant_1": a["K_secant"], "K_secant_2": b["K_secant"],
                          "dK_secant_rel": (b["K_secant"] - a["K_secant"]) / a["K_secant"],
                          "dK_tangent_rel": (b["K_tangent"] - a["K_tangent"]) / a["K_tangent"],
                          "dFmax_rel": (b["max_pin_force_N"] - a["max_pin_force_N"]) / a["max_pin_force_N"],
                          "pins_1": a["pins_in_contact"], "pins_2": b["pins_in_contact"],
                          "iters_1": a["active_set_iterations"], "iters_2": b["active_set_iterations"],
                          "load_1": a["load_avg_at_start"], "load_2": b["load_avg_at_start"]})
    if table:
        write_csv(os.path.join(args.out, "ranks.csv"), table, list(table[0].keys()))
        for t in table:
            notes.append(f"ranks {t['scene']} {t['mesh']}: DoFs {t['dofs_1']}/{t['dofs_2']}, wall 1 rank {t['wall_1_s']:.1f} s, "
                         f"2 ranks {t['wall_2_s']:.1f} s, speed-up {t['speedup']:.2f} (program's state wall "
                         f"{t['solve_speedup']:.2f}); dK_sec {t['dK_secant_rel']:.1e}, dK_tan {t['dK_tangent_rel']:.1e}, "
                         f"dFmax {t['dFmax_rel']:.1e}, pins {t['pins_1']}/{t['pins_2']}, AS it. {t['iters_1']}/{t['iters_2']}")
    ss = read_csv(os.path.join(args.out, "seed-study-fe.csv"), NUMBERS, missing_ok=True)
    if ss:
        plot_seed_study(os.path.join(args.out, "seed-study-fe.png"), ss)
        for sweep in ("pin radius", "eccentricity"):
            for model in sorted({r["model"] for r in ss}):
                rr = sorted((r for r in ss if r["sweep"] == sweep and r["model"] == model and has_k(r)),
                            key=lambda r: r["value"])
                if rr:
                    notes.append(f"seed study {sweep:12s} {model:24s}: " + ", ".join(
                        f"{r['value']:g}: {r['K_secant']:.4g}/{r['K_tangent']:.4g} ({r['pins_in_contact']}p)" for r in rr))
    with open(os.path.join(args.out, "summary.txt"), "w") as f:
        f.write("\n".join(notes) + "\n")
    print("\n".join(notes))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0],
                                 formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "cycloid-contact"))
    ap.add_argument("--part", default="analytic,2d,3d1,3d2,ranks,reduced,seed-study",
                    help="comma list of analytic, 2d, 3d1, 3d2, ranks, reduced, seed-study")
    ap.add_argument("--quick", action="store_true", help="the coarse meshes of every part only")
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--cases", default=None, help="comma list of mesh labels to run (default: all of the part)")
    ap.add_argument("--no-seed-study-fe", dest="seed_study_fe", action="store_false",
                    help="seed-study: analytic models only")
    ap.add_argument("--sweeps", default=None,
                    help="seed-study: comma list of rrp, e, eA300 (e sweep with modification A at 300 N m); default all")
    ap.add_argument("--timeout", type=float, default=1500.)
    ap.add_argument("--out", default=os.path.join(ROOT, "doc", "ladder"))
    ap.add_argument("--keep", default=None, help="keep prm, logs and outputs here")
    ap.add_argument("--analyse-only", action="store_true")
    args = ap.parse_args()
    args.exe = os.path.abspath(args.exe)
    os.makedirs(args.out, exist_ok=True)
    if args.cases:
        keep = set(args.cases.split(","))
        for lst in (TWO_D_RIGID, TWO_D_ELASTIC, TWO_D_MATCHED, THREE_D1, THREE_D2):
            lst[:] = [c for c in lst if c[0] in keep]
        RANKS[:] = [c for c in RANKS if c in keep]
        RANKS_3D[:] = [c for c in RANKS_3D if c in keep]
    if not args.analyse_only:
        if args.keep:
            os.makedirs(args.keep, exist_ok=True)
            work, tmp = os.path.abspath(args.keep), None
        else:
            tmp = tempfile.TemporaryDirectory()
            work = tmp.name
        print(f"executable {args.exe}, work dir {work}", flush=True)
        funcs = {"analytic": part_analytic, "2d": part_2d, "3d1": part_3d1, "3d2": part_3d2, "ranks": part_ranks,
                 "reduced": part_reduced}
        path = os.path.join(args.out, "ladder.csv")
        for part in args.part.split(","):
            if part == "seed-study":
                new = part_seed_study(args, work)
                sp = os.path.join(args.out, "seed-study-fe.csv")
                old = read_csv(sp, NUMBERS, missing_ok=True)
                fresh = {(r["sweep"], r["value"], r["model"]) for r in new}
                rows = [r for r in old if (r["sweep"], r["value"], r["model"]) not in fresh] + new
                rows.sort(key=lambda r: (r["sweep"], r["model"], r["value"]))
                write_csv(sp, rows, SS_COLUMNS)
                continue
            print(f"part {part}", flush=True)
            new = funcs[part](args, work)
            # Replace the re-run (scene, mesh, ranks) rows, keep the rest; write after every part.
            old = [r for r in read_csv(path, NUMBERS, missing_ok=True) if r.get("source") in ("ladder", "ranks")]
            fresh = {(r["scene"], r["mesh"], r["ranks"], r["source"]) for r in new}
            rows = [r for r in old if (r["scene"], r["mesh"], r["ranks"], r["source"]) not in fresh] + new
            write_csv(path, rows, COLUMNS)
        if tmp:
            tmp.cleanup()
    analyse(args)


if __name__ == "__main__":
    main()
