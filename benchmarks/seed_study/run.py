#!/usr/bin/python3
"""The seed article's parameter study (its Table 3) with the analytical
models of cycloid-contact.

Sweeps, each around the seed case (zp = 40, rrp = 3 mm, e = 2.2 mm,
K1 = 0.675, rp = 130.370 mm, b = 16 mm):
  * pin radius rrp 2.5 ... 3.5 mm (rp and e fixed);
  * eccentricity e 1.8 ... 2.6 mm at fixed pin circle rp = 130.370 mm
    (K1 = e zp / rp follows: 0.55 ... 0.80), the design question "which e
    for a given housing";
  * shortening coefficient K1 0.60 ... 0.75 at fixed e = 2.2 mm (rp follows);
at three torques (3, 300, 1000 N m), for both modification examples of
doc/design-basis.md section 2.2 (A: Delta rp = Delta rrp = +0.01 mm,
clearance 0-2.6 um; B: Delta rp = -0.01, Delta rrp = +0.01 mm, clearance
17.4-20 um) and both
pair models (seed, line-contact). Each point is a phase sweep over one mesh
period (9 phases); the mean over the period of K_tangent and K_secant is
recorded.

Writes doc/seed-study/seed_study.csv and one PNG per sweep.
Usage: benchmarks/seed_study/run.py [path/to/cycloid-contact]
"""
import csv
import os
import sys
import tempfile
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "cycloid-contact")
OUT = os.path.join(ROOT, "doc", "seed-study")
ZP, RP_SEED, E_SEED, K1_SEED, RRP_SEED = 40, 2.2 * 40 / 0.675, 2.2, 0.675, 3.0
TORQUES = [3, 300, 1000]
MODIFICATIONS = {"A": (0.01, 0.01), "B": (-0.01, 0.01)}
MODELS = ["seed", "line-contact"]
N_PHASES = 9


def run_case(rrp, e, k1, d_rp, d_rrp, model):
    with tempfile.TemporaryDirectory() as tmp:
        prm = os.path.join(tmp, "case.prm")
        with open(prm, "w") as f:
            f.write(f"""set Run = analytic
set Output directory = {tmp}/out
subsection Geometry
  set Pin radius = {rrp}
  set Eccentricity = {e}
  set Shortening coefficient = {k1}
  set Pin circle radius modification = {d_rp}
  set Pin radius modification = {d_rrp}
end
subsection Loading
  set Torque = {", ".join(str(t) for t in TORQUES)}
  set Number of phases = {N_PHASES}
end
subsection Analytic
  set Pair stiffness model = {model}
end
""")
        res = run_cycloid(None, EXE, prm)
        if res.returncode != 0:
            return None, res.stderr.strip().splitlines()[-1] if res.stderr else "failed"
        rows = read_csv(f"{tmp}/out/stiffness.csv")
    out = {}
    for t in TORQUES:
        sel = [r for r in rows if float(r["torque_Nm"]) == t]
        out[t] = {
            "K_tangent": np.mean([float(r["K_tangent_Nm_per_rad"]) for r in sel]),
            "K_secant": np.mean([float(r["K_secant_Nm_per_rad"]) for r in sel]),
            "K_secant_elastic": np.mean([float(r["K_secant_elastic_Nm_per_rad"]) for r in sel]),
            "pins": np.mean([float(r["pins_in_contact"]) for r in sel]),
            "max_force": np.max([float(r["max_pin_force_N"]) for r in sel]),
        }
    return out, ""


def main():
    os.makedirs(OUT, exist_ok=True)
    sweeps = {
        "pin_radius": [(rrp, E_SEED, K1_SEED) for rrp in np.linspace(2.5, 3.5, 9)],
        "eccentricity": [(RRP_SEED, e, e * ZP / RP_SEED) for e in np.linspace(1.8, 2.6, 9)],
        "shortening_coefficient": [(RRP_SEED, E_SEED, k1) for k1 in np.linspace(0.60, 0.75, 7)],
    }
    records = []
    for sweep, points in sweeps.items():
        for rrp, e, k1 in points:
            for mod, (d_rp, d_rrp) in MODIFICATIONS.items():
                for model in MODELS:
                    res, err = run_case(round(rrp, 6), round(e, 6), round(k1, 6), d_rp, d_rrp, model)
                    for t in TORQUES:
                        rec = dict(sweep=sweep, pin_radius_mm=rrp, eccentricity_mm=e, K1=k1,
                                   pin_circle_radius_mm=e * ZP / k1, modification=mod, model=model,
                                   torque_Nm=t)
                        if res is None:
                            rec.update(K_tangent_Nm_per_rad="nan", K_secant_Nm_per_rad="nan",
                                       K_secant_elastic_Nm_per_rad="nan", mean_pins_in_contact="nan",
                                       max_pin_force_N="nan", error=err)
                        else:
                            r = res[t]
                            rec.update(K_tangent_Nm_per_rad=f"{r['K_tangent']:.6e}",
                                       K_secant_Nm_per_rad=f"{r['K_secant']:.6e}",
                                       K_secant_elastic_Nm_per_rad=f"{r['K_secant_elastic']:.6e}",
                                       mean_pins_in_contact=f"{r['pins']:.3f}",
                                       max_pin_force_N=f"{r['max_force']:.4f}", error="")
                        records.append(rec)
            print(f"{sweep}: rrp={rrp:.3f} e={e:.3f} K1={k1:.4f} done", flush=True)
    with open(os.path.join(OUT, "seed_study.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(records[0].keys()))
        w.writeheader()
        w.writerows(records)
    plot(records)


def plot(records):
    xkey = {"pin_radius": ("pin_radius_mm", "pin radius rrp [mm]"),
            "eccentricity": ("eccentricity_mm", "eccentricity e [mm] (rp fixed, K1 = e zp/rp)"),
            "shortening_coefficient": ("K1", "shortening coefficient K1 (e fixed, rp = e zp/K1)")}
    for sweep, (key, label) in xkey.items():
        fig, axes = plt.subplots(1, 2, figsize=(11, 4.2), sharey=False)
        for ax, mod in zip(axes, MODIFICATIONS):
            for model, style in zip(MODELS, ["--", "-"]):
                for t, color in zip(TORQUES, ["tab:blue", "tab:orange", "tab:green"]):
                    sel = [r for r in records if r["sweep"] == sweep and r["modification"] == mod
                           and r["model"] == model and r["torque_Nm"] == t]
                    x = [float(r[key]) for r in sel]
                    y = [float(r["K_tangent_Nm_per_rad"]) / 3437.7468 for r in sel]
                    ax.plot(x, y, style, color=color, marker="o", ms=3, label=f"{model}, T = {t} N m")
            d_rp, d_rrp = MODIFICATIONS[mod]
            ax.set_title(f"modification {mod}: Δrp = {d_rp:+} mm, Δrrp = {d_rrp:+} mm", fontsize=10)
            ax.set_xlabel(label)
            ax.set_ylabel("K_tangent, mean over the period [N m/arcmin]")
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
        axes[0].legend(fontsize=7)
        fig.tight_layout()
        fig.savefig(os.path.join(OUT, f"{sweep}.png"), dpi=90)
        plt.close(fig)


if __name__ == "__main__":
    main()
