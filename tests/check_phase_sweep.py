#!/usr/bin/python3
"""Checks of a `Run = phase-sweep` run on 1 and 2 MPI ranks.

Usage: check_phase_sweep.py FILE.prm DIR_1_RANK DIR_2_RANKS EXECUTABLE

* one stiffness.csv row per (phase, torque), zp pin_forces.csv rows per
  state and disc, crank angles spread over one mesh period 360/zp;
* periodicity: the last phase (one period after the first) has the same
  rotation and K (1e-8) and the pin forces shifted by one pin (1e-6 of the
  largest force);
* fluctuation.csv agrees with the rows of stiffness.csv, and its noise
  floor is unknown for this sweep (3 phases, periodic meshes);
* warm-start independence: a quasi-static run at the middle phase (cold
  start from the analytical model) gives the same rotation and K (1e-8);
* the same results on 1 and 2 ranks (1e-6).
"""
import os
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import parameter_getter, parameter_values, run_cycloid  # noqa: E402


def close(a, b, tol):
    return abs(a - b) <= tol * max(abs(a), abs(b))


def main(prm, dir1, dir2, exe):
    get = parameter_getter(parameter_values(prm, exe))
    zp = int(get("Geometry", "Number of pins", 40))
    torques = [float(t) for t in get("Loading", "Torque").split(",")]
    n_phases = int(get("Loading", "Number of phases"))
    s1, s2 = rows(f"{dir1}/stiffness.csv"), rows(f"{dir2}/stiffness.csv")
    p2 = rows(f"{dir2}/pin_forces.csv")
    check(len(s2) == n_phases * len(torques), f"{len(s2)} rows, expected {n_phases * len(torques)}")
    check(len(p2) == len(s2) * zp, f"{len(p2)} pin rows, expected {len(s2) * zp}")
    angles = sorted({float(r["crank_deg"]) for r in s2})
    check(abs(angles[-1] - angles[0] - 360.0 / zp) < 1e-9, f"crank angles {angles} do not span one period")
    for a, b in zip(s1, s2):
        for key in ("rotation_rad", "K_tangent_Nm_per_rad", "K_secant_Nm_per_rad"):
            check(close(float(a[key]), float(b[key]), 1e-6), f"{key} differs on 1 and 2 ranks: {a[key]} vs {b[key]}")

    by_state = {}
    for r in p2:
        by_state.setdefault(r["step"], {})[int(r["pin"])] = r
    nt = len(torques)
    for t in range(nt):
        first, last = s2[t], s2[len(s2) - nt + t]
        for key in ("rotation_rad", "K_tangent_Nm_per_rad", "K_secant_Nm_per_rad"):
            x, y = float(first[key]), float(last[key])
            print(f"T {torques[t]:g}: {key} first phase {x:.10e}, last phase {y:.10e}, {y / x - 1:+.1e}")
            check(close(x, y, 1e-8), f"{key} not periodic at T {torques[t]}: {x} vs {y}")
        pf, pl = by_state[first["step"]], by_state[last["step"]]
        fmax = max(float(r["Fn_N"]) for r in pf.values())
        worst = max(abs(float(pf[j]["Fn_N"]) - float(pl[(j + 1) % zp]["Fn_N"])) for j in range(zp))
        print(f"T {torques[t]:g}: largest difference of pin j (first) and pin j+1 (last) forces {worst:.2e} N of {fmax:.1f} N")
        check(worst <= 1e-6 * fmax, "pin forces not shifted by one pin after one period")
        ks = [float(r["K_tangent_Nm_per_rad"]) for r in s2[t::nt]]
        fl = rows(f"{dir2}/fluctuation.csv")[t]
        mean = sum(ks) / len(ks)
        check(close(float(fl["K_tangent_mean_Nm_per_rad"]), mean, 1e-9), "fluctuation.csv mean")
        check(close(float(fl["K_tangent_fluctuation"]) + 1, (max(ks) - min(ks)) / mean + 1, 1e-9), "fluctuation.csv fluctuation")
        # The first and last mesh are one mesh turned by a pin pitch and
        # there are fewer than 5 phases: the noise floor is unknown, and
        # the fluctuation is not called resolved.
        if len(ks) < 5:
            check(fl["K_tangent_noise_floor"] == "nan" and fl["K_tangent_fluctuation_resolved"] == "0",
                  f"noise floor {fl['K_tangent_noise_floor']} of a 3-phase periodic-mesh sweep")
        print(f"T {torques[t]:g}: K_tangent over the period {', '.join(f'{k:.5e}' for k in ks)}; fluctuation {float(fl['K_tangent_fluctuation']):.3e}")

    # The middle phase again, as a quasi-static run from a cold start.
    middle = angles[len(angles) // 2]
    with tempfile.TemporaryDirectory() as tmp:
        text = open(prm).read().replace("set Run = phase-sweep", "set Run = quasi-static")
        text = text.replace("set Output directory", f"set Output directory = {tmp}/q\n# ")
        text = text.replace("set Crank angle = 0", f"set Crank angle = {middle!r}")
        with open(f"{tmp}/q.prm", "w") as f:
            f.write(text)
        run_cycloid(None, exe, f"{tmp}/q.prm", check=True)
        q = rows(f"{tmp}/q/stiffness.csv")
    mid = [r for r in s2 if abs(float(r["crank_deg"]) - middle) < 1e-9]
    for a, b in zip(q, mid):
        for key in ("rotation_rad", "K_tangent_Nm_per_rad"):
            print(f"crank {middle:g} deg, T {a['torque_Nm']}: {key} quasi-static {a[key]}, phase sweep {b[key]}")
            check(close(float(a[key]), float(b[key]), 1e-8), f"{key} at the middle phase depends on the warm start")
    return verdict("all checks passed")


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
