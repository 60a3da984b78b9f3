#!/usr/bin/python3
"""Checks of scripts/plot.sh on a run's output directory.

Usage:
  check_plots.py PLOT_SH DIR [--copy-of SOURCE_DIR]
      Runs PLOT_SH DIR (after copying SOURCE_DIR's files to DIR, for a
      fixture kept in the source tree) and checks that
      * it exits 0 and prints the path of every PNG it wrote;
      * every PNG is a valid PNG of sensible size (400-3000 px a side,
        10 kB - 1 MB);
      * plots/index.json lists exactly the figures this directory has data
        for (decided here from the CSV files, independently of plot.py);
      * the curves match the data: one curve per disc with zp points in the
        polar plot, for the state with the largest torque at the first crank
        angle (a transient: the last step); one curve per torque with one
        point per crank angle against the crank angle, one curve per crank
        angle against the torque; the transmission-error peak-to-peak in the
        legend; the energy terms and the balance error on the right axis;
        the torsion curve per crank angle with rigidity.csv's values in the
        legend; pressure per pin and disc;
      * every panel has a title and axis labels with units (the pin number
        excepted), the figure's title names zp.
  check_plots.py PLOT_SH --bad WORKDIR
      plot.sh must fail with a message for a missing directory and for a
      directory that holds no output file.
"""
import json
import math
import os
import re
import shutil
import struct
import subprocess
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import read_csv  # noqa: E402

failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)
    return cond


def columns(path):
    """Columns of a CSV file as lists of floats; None if the file is absent."""
    if not os.path.isfile(path):
        return None
    rows = read_csv(path)
    return {k: [float(r[k]) for r in rows] for k in rows[0]}


def key(v):
    return float(f"{v:.9g}")


def close(a, b, tol):
    return abs(a - b) <= tol * max(abs(a), abs(b), 1e-30)


def check_png(path):
    with open(path, "rb") as f:
        head = f.read(24)
    if not check(head[:8] == b"\x89PNG\r\n\x1a\n" and head[12:16] == b"IHDR",
                 f"{path}: not a PNG"):
        return
    width, height = struct.unpack(">II", head[16:24])
    size = os.path.getsize(path)
    check(400 <= width <= 3000 and 300 <= height <= 3000, f"{path}: {width}x{height} px")
    check(10e3 <= size <= 1e6, f"{path}: {size} bytes")


class Data:
    """What the directory holds, read independently of plot.py."""

    def __init__(self, d):
        self.s = columns(os.path.join(d, "stiffness.csv"))
        self.p = columns(os.path.join(d, "pin_forces.csv"))
        self.e = columns(os.path.join(d, "energy.csv"))
        self.f = columns(os.path.join(d, "fluctuation.csv"))
        self.tc = columns(os.path.join(d, "torsion_curve.csv"))
        self.bd = columns(os.path.join(d, "compliance_breakdown.csv"))
        self.rig = columns(os.path.join(d, "rigidity.csv"))
        self.transient = self.e is not None
        rotation = self.f is not None and "rotation_rad" in self.f
        if self.s and self.tc:
            # A torque cycle: each non-zero torque once per crank angle.
            first = {}
            for i, (c, t) in enumerate(zip(self.s["crank_deg"], self.s["torque_Nm"])):
                if t != 0:
                    first.setdefault((c, t), i)
            rows = sorted(first.values())
            self.s = {k: [v[i] for i in rows] for k, v in self.s.items()}
        if self.s:
            self.load = self.s["rotation_rad" if rotation else "torque_Nm"]
            self.loads = sorted({key(v) for v in self.load})
            self.cranks = sorted({key(v) for v in self.s["crank_deg"]})

    def expected(self):
        want = set()
        if self.p:
            want.add("pin_forces_polar.png")
            if "max_contact_pressure_MPa" in self.p or "hertz_pressure_MPa" in self.p:
                want.add("contact_pressure.png")
        if self.s and not self.transient:
            if len(self.cranks) >= 2:
                want |= {"stiffness_vs_crank.png", "transmission_error.png"}
            if len(self.loads) >= 2:
                want.add("stiffness_vs_torque.png")
        if self.transient and len(self.e["step"]) >= 2:
            want |= {"energy.png", "transmission_error.png"}
        if self.tc:
            want.add("torsion_curve.png")
        if self.bd and self.loaded_breakdown():
            want.add("compliance_breakdown.png")
        return want

    def loaded_breakdown(self):
        """Rows of compliance_breakdown.csv with a torque and a finite
        total."""
        return [i for i, (t, b) in enumerate(zip(self.bd["torque_Nm"], self.bd["total_rad"]))
                if t != 0 and math.isfinite(b)]

    def representative_step(self):
        s = self.s
        if self.transient:
            return int(s["step"][-1])
        first = [i for i, c in enumerate(s["crank_deg"]) if key(c) == key(s["crank_deg"][0])]
        return int(s["step"][max(first, key=lambda i: abs(self.load[i]))])

    def te(self):
        if "transmission_error_arcsec" in self.s:
            return self.s["transmission_error_arcsec"]
        return [r * 180 * 3600 / math.pi for r in self.s["rotation_rad"]]


def number_after(label, word):
    m = re.search(re.escape(word) + r" ([-0-9.e+]+)", label)
    return float(m.group(1)) if m else None


def check_polar(fig, data):
    p, step = data.p, data.representative_step() if data.s else None
    discs = sorted(set(p["disc"]))
    zp = len(set(p["pin"]))
    polar = [q for q in fig["panels"] if q["polar"]]
    if not check(len(polar) == 1, "pin_forces_polar: no polar panel"):
        return
    curves = polar[0]["curves"]
    check(len(curves) == len(discs), f"polar: {len(curves)} curves for {len(discs)} discs")
    check(all(c["points"] == zp for c in curves), f"polar: not {zp} points per disc: {curves}")
    if step is not None:
        check(fig.get("step") == step, f"polar: state {fig.get('step')}, expected {step}")
        for c, d in zip(curves, discs):
            fmax = max(f for f, s_, di in zip(p["Fn_N"], p["step"], p["disc"])
                       if s_ == step and di == d)
            shown = number_after(c["label"], "max")
            check(shown is not None and close(shown, fmax, 1e-3),
                  f"polar: disc {d} label {c['label']!r}, max Fn {fmax}")


def check_stiffness(fig, data, along):
    """along = 'crank': a curve per load, a point per crank angle; 'torque':
    a curve per crank angle (mean and band beyond 6), a point per load."""
    n_curves, n_points = (len(data.loads), len(data.cranks)) if along == "crank" else \
        (len(data.cranks), len(data.loads))
    check(len(fig["panels"]) == 2, f"stiffness vs {along}: {len(fig['panels'])} panels")
    for panel in fig["panels"]:
        curves = panel["curves"]
        if along == "torque" and n_curves > 6:
            check([c["kind"] for c in curves] == ["line", "band"] or
                  sorted(c["kind"] for c in curves) == ["band", "line"],
                  f"stiffness vs torque: expected mean and band, got {curves}")
            continue
        check(len(curves) == n_curves, f"stiffness vs {along}: {len(curves)} curves, "
              f"expected {n_curves} ({panel['title']})")
        check(all(c["points"] == n_points for c in curves),
              f"stiffness vs {along}: points {[c['points'] for c in curves]}, expected {n_points}")
        check("N·m/arcmin" in panel["ylabel"], f"stiffness: ylabel {panel['ylabel']!r}")


def check_transmission_error(fig, data):
    te = data.te()
    if data.transient:
        curves = [c for c in fig["panels"][0]["curves"] if c["axis"] == "left"]
        check(len(curves) == 1 and curves[0]["points"] == len(te), f"TE in time: {curves}")
        pp = number_after(curves[0]["label"], "p-p")
        check(pp is not None and close(pp, max(te) - min(te), 5e-3), f"TE p-p {curves[0]}")
        return
    curves = fig["panels"][0]["curves"]
    check(len(curves) == len(data.loads), f"TE: {len(curves)} curves for {len(data.loads)} loads")
    for c, load in zip(curves, data.loads):
        values = [t for t, v in zip(te, data.load) if key(v) == load]
        check(c["points"] == len(data.cranks),
              f"TE: {c['points']} points, {len(data.cranks)} angles")
        pp = number_after(c["label"], "p-p")
        check(pp is not None and close(pp, max(values) - min(values), 5e-3),
              f"TE: label {c['label']!r}, p-p {max(values) - min(values)}")


def check_energy(fig, data):
    curves = fig["panels"][0]["curves"]
    left = {c["label"] for c in curves if c["axis"] == "left"}
    right = [c for c in curves if c["axis"] == "right"]
    for term in ("kinetic", "elastic", "external work", "dissipated"):
        check(any(lab.startswith(term) for lab in left), f"energy: no {term} curve in {left}")
    check(len(right) == 1 and "balance error" in right[0]["label"], f"energy: right axis {right}")
    check(all(c["points"] == len(data.e["step"]) for c in curves), "energy: points != rows")
    check("[" in fig["panels"][0].get("ylabel_right", ""), "energy: no unit on the right axis")


def check_torsion(fig, data):
    tc, rig = data.tc, data.rig
    cranks = sorted({key(c) for c in tc["crank_deg"]}) if "crank_deg" in tc else [None]
    curves = fig["panels"][0]["curves"]
    tors = [c for c in curves if c["label"].startswith("torsion curve")]
    check(len(tors) == len(cranks), f"torsion: {len(tors)} curves for {len(cranks)} crank angles")
    for c, crank in zip(tors, cranks):
        n = len(tc["torque_Nm"]) if crank is None else sum(key(v) == crank for v in tc["crank_deg"])
        check(c["points"] == n, f"torsion: {c['points']} points, {n} rows")
    labels = " | ".join(c["label"] for c in curves)
    for word, column in (("rigidity", "torsional_rigidity_Nm_per_arcmin"),
                         ("lost motion", "lost_motion_arcmin"), ("backlash", "backlash_arcmin")):
        shown = number_after(labels, word)
        check(shown is not None and (rig is None or close(shown, rig[column][0], 5e-3)),
              f"torsion: {word} {shown} in {labels!r}, rigidity.csv {rig and rig[column][0]}")
    check(any("3 %" in c["label"] and c["points"] == 2 for c in curves), "torsion: no ±3 % points")


def check_pressure(fig, data):
    p = data.p
    zp, discs = len(set(p["pin"])), len(set(p["disc"]))
    n_cols = sum(c in p for c in ("max_contact_pressure_MPa", "hertz_pressure_MPa"))
    curves = fig["panels"][0]["curves"]
    check(len(curves) == discs * n_cols,
          f"pressure: {len(curves)} curves, expected {discs * n_cols}")
    check(all(c["points"] == zp for c in curves), "pressure: not zp points per curve")
    check(fig["panels"][0]["ylabel"].endswith("[MPa]"), "pressure: ylabel")
    check(len(fig["panels"]) == (2 if "max_shear_stress_MPa" in p else 1), "pressure: shear panel")


def check_breakdown(fig, data):
    """Three stacked parts and the total, a bar or point per loaded state;
    the bearings' share in its label as the file gives it."""
    n = len(data.loaded_breakdown())
    curves = fig["panels"][0]["curves"]
    kinds = sorted(c["kind"] for c in curves)
    check(kinds == ["bars", "bars", "bars", "line"], f"breakdown: curves {kinds}")
    check(all(c["points"] == n for c in curves),
          f"breakdown: points {[c['points'] for c in curves]}, expected {n}")
    rows = data.loaded_breakdown()
    shares = [abs(data.bd["bearings_rad"][i] / data.bd["total_rad"][i]) for i in rows]
    label = [c["label"] for c in curves if c["label"].startswith("crank bearings")]
    check(label and number_after(label[0], "bearings:") is not None and
          abs(number_after(label[0], "bearings:") - 100 * min(shares)) <= 0.05 + 1e-3 * 100 * min(shares),
          f"breakdown: bearings label {label} against the smallest share {100 * min(shares):.3g} %")


def check_directory(plot_sh, d):
    shutil.rmtree(os.path.join(d, "plots"), ignore_errors=True)
    r = subprocess.run([plot_sh, d], capture_output=True, text=True)
    if not check(r.returncode == 0, f"plot.sh failed ({r.returncode}): {r.stdout}{r.stderr}"):
        return
    printed = {os.path.basename(line) for line in r.stdout.split()}
    index = json.load(open(os.path.join(d, "plots", "index.json")))
    figures = {f["file"]: f for f in index["figures"]}
    data = Data(d)
    want = data.expected()
    check(set(figures) == want, f"figures {sorted(figures)}, expected {sorted(want)}")
    check(printed == set(figures), f"printed {sorted(printed)}, index {sorted(figures)}")
    zp = len(set(data.p["pin"])) if data.p else None
    for name, fig in figures.items():
        check_png(os.path.join(d, "plots", name))
        check(zp is None or f"zp = {zp}" in fig["title"], f"{name}: zp not in {fig['title']!r}")
        for panel in fig["panels"]:
            check(panel["title"], f"{name}: a panel without a title")
            if not panel["polar"]:
                # Units on both axes; the pin number is the one count.
                check(("[" in panel["xlabel"] or panel["xlabel"].startswith("pin j"))
                      and "[" in panel["ylabel"],
                      f"{name}: labels without units: {panel['xlabel']!r}, {panel['ylabel']!r}")
    checks = {"pin_forces_polar.png": check_polar,
              "stiffness_vs_crank.png": lambda f, x: check_stiffness(f, x, "crank"),
              "stiffness_vs_torque.png": lambda f, x: check_stiffness(f, x, "torque"),
              "transmission_error.png": check_transmission_error,
              "energy.png": check_energy, "torsion_curve.png": check_torsion,
              "contact_pressure.png": check_pressure,
              "compliance_breakdown.png": check_breakdown}
    for name, fig in figures.items():
        checks[name](fig, data)
    print(f"{d}: {', '.join(sorted(figures))}")


def check_bad(plot_sh, work):
    missing = os.path.join(work, "no-such-directory")
    empty = os.path.join(work, "empty")
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(empty)
    for d, message in ((missing, "does not exist"), (empty, "holds none of the files")):
        r = subprocess.run([plot_sh, d], capture_output=True, text=True)
        check(r.returncode != 0, f"plot.sh {d}: exit status 0")
        check(message in r.stderr, f"plot.sh {d}: stderr {r.stderr!r} lacks {message!r}")
        check("Traceback" not in r.stderr, f"plot.sh {d}: a Python traceback")
        check(not os.path.exists(os.path.join(d, "plots")), f"plot.sh {d}: wrote plots/")


def main(argv):
    plot_sh = argv[1]
    if argv[2] == "--bad":
        check_bad(plot_sh, argv[3])
    else:
        d = argv[2]
        if len(argv) > 3 and argv[3] == "--copy-of":
            shutil.rmtree(d, ignore_errors=True)
            shutil.copytree(argv[4], d)
        check_directory(plot_sh, d)
    for f in failures:
        print("FAIL:", f)
    print("ok" if not failures else f"{len(failures)} failure(s)")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
