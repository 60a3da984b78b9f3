#!/usr/bin/python3
"""The seed article's parameter study (its Table 3) at 3D accuracy: the
reduced model of the whole stage (3D, two discs, elastic pins seated in the
housing; doc/reduced-model.md, within 0.3 % of the full 3D FE model in
K_secant) against the analytical line-contact model at the same states.

Sweeps around the seed case as in benchmarks/seed_study/run.py (pin radius
2.5-3.5 mm, eccentricity 1.8-2.6 mm at fixed rp, K1 0.60-0.75 at fixed e),
3 points each (ends and middle), at 3, 300 and 1000 N m, both modification examples (A:
Delta rp = Delta rrp = +0.01 mm; B: Delta rp = -0.01, Delta rrp = +0.01
mm), crank angle 0 (one condensation per point, ~35 s on 2 cores; the
torques are free).

Writes doc/seed-study/seed_study_reduced.csv and seed_study_reduced.png.
Usage: benchmarks/seed_study/reduced.py [path/to/cycloid-contact] [--ranks N]
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
ARGS = [a for a in sys.argv[1:] if not a.startswith("--")]
EXE = ARGS[0] if ARGS else os.path.join(ROOT, "build", "cycloid-contact")
RANKS = int(sys.argv[sys.argv.index("--ranks") + 1]) if "--ranks" in sys.argv else 2
OUT = os.path.join(ROOT, "doc", "seed-study")
ZP, RP_SEED, E_SEED, K1_SEED, RRP_SEED = 40, 2.2 * 40 / 0.675, 2.2, 0.675, 3.0
TORQUES = [3, 300, 1000]
MODIFICATIONS = {"A": (0.01, 0.01), "B": (-0.01, 0.01)}
ARCMIN = 3437.7468


def run_case(run, rrp, e, k1, d_rp, d_rrp):
    with tempfile.TemporaryDirectory() as tmp:
        prm = os.path.join(tmp, "case.prm")
        scene = ("subsection Scene\n  set Dimension = 3\n  set Number of discs = 2\n"
                 "  set Pins = elastic\n  set Pin support = housing\nend\n"
                 if run == "reduced" else
                 "subsection Analytic\n  set Pair stiffness model = line-contact\nend\n")
        with open(prm, "w") as f:
            f.write(f"""set Run = {run}
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
  set Crank angle = 0
end
{scene}""")
        res = run_cycloid(RANKS, EXE, prm)
        if res.returncode != 0:
            return None, (res.stdout + res.stderr).strip().splitlines()[-1]
        rows = read_csv(f"{tmp}/out/stiffness.csv")
    return {float(r["torque_Nm"]): r for r in rows}, ""


def main():
    os.makedirs(OUT, exist_ok=True)
    sweeps = {
        "pin_radius": [(rrp, E_SEED, K1_SEED) for rrp in np.linspace(2.5, 3.5, 3)],
        "eccentricity": [(RRP_SEED, e, e * ZP / RP_SEED) for e in np.linspace(1.8, 2.6, 3)],
        "shortening_coefficient": [(RRP_SEED, E_SEED, k1) for k1 in np.linspace(0.60, 0.75, 3)],
    }
    records = []
    for sweep, points in sweeps.items():
        for rrp, e, k1 in points:
            for mod, (d_rp, d_rrp) in MODIFICATIONS.items():
                res = {run: run_case(run, round(rrp, 6), round(e, 6), round(k1, 6), d_rp, d_rrp)
                       for run in ["reduced", "analytic"]}
                for t in TORQUES:
                    rec = dict(sweep=sweep, pin_radius_mm=rrp, eccentricity_mm=e, K1=k1,
                               pin_circle_radius_mm=e * ZP / k1, modification=mod, torque_Nm=t)
                    for run, (rows, err) in res.items():
                        for col in ["K_secant_Nm_per_rad", "K_tangent_Nm_per_rad",
                                    "K_secant_elastic_Nm_per_rad", "pins_in_contact",
                                    "max_pin_force_N"]:
                            rec[f"{run}_{col}"] = rows[t][col] if rows else "nan"
                        rec[f"{run}_error"] = err
                    records.append(rec)
                print(f"{sweep}: rrp={rrp:.3f} e={e:.3f} K1={k1:.4f} {mod} done", flush=True)
    with open(os.path.join(OUT, "seed_study_reduced.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(records[0].keys()))
        w.writeheader()
        w.writerows(records)
    plot(records)


def plot(records):
    xkey = {"pin_radius": ("pin_radius_mm", "pin radius rrp [mm]"),
            "eccentricity": ("eccentricity_mm", "eccentricity e [mm] (rp fixed)"),
            "shortening_coefficient": ("K1", "shortening coefficient K1 (e fixed)")}
    fig, axes = plt.subplots(2, 3, figsize=(14, 7.5))
    for col, (sweep, (key, label)) in enumerate(xkey.items()):
        for row, mod in enumerate(MODIFICATIONS):
            ax = axes[row][col]
            for run, style in [("reduced", "-"), ("analytic", "--")]:
                for t, color in zip(TORQUES, ["tab:blue", "tab:orange", "tab:green"]):
                    sel = [r for r in records if r["sweep"] == sweep and r["modification"] == mod
                           and float(r["torque_Nm"]) == t]
                    x = [float(r[key]) for r in sel]
                    y = [float(r[f"{run}_K_tangent_Nm_per_rad"]) / ARCMIN for r in sel]
                    ax.plot(x, y, style, color=color, marker="o", ms=3,
                            label=f"{'reduced 3D' if run == 'reduced' else 'analytic'}, {t} N m")
            d_rp, d_rrp = MODIFICATIONS[mod]
            ax.set_title(f"{mod}: Δrp = {d_rp:+} mm, Δrrp = {d_rrp:+} mm", fontsize=9)
            ax.set_xlabel(label)
            ax.set_ylabel("K_tangent [N m/arcmin]")
            ax.set_yscale("log")
            ax.grid(True, which="both", alpha=0.3)
    axes[0][0].legend(fontsize=7)
    fig.suptitle("Seed Table 3 at 3D accuracy: reduced model (solid) against the analytic "
                 "line-contact model (dashed), crank angle 0")
    fig.tight_layout()
    fig.savefig(os.path.join(OUT, "seed_study_reduced.png"), dpi=90)
    plt.close(fig)


if __name__ == "__main__":
    if "--plot-only" in sys.argv:
        plot(read_csv(os.path.join(OUT, "seed_study_reduced.csv")))
    else:
        main()
