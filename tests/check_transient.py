#!/usr/bin/python3
"""Transient runs (Run = transient).

Usage:
  check_transient.py restart FILE.prm EXECUTABLE WORKDIR
      Runs FILE.prm to its end on 2 ranks; runs it again stopped after the
      first checkpoint and resumed from it. The resumed run's energy.csv,
      stiffness.csv, pin_forces.csv and transient.h5 must equal the
      uninterrupted run's (1e-12 relative; wall times and memory excepted). Also: the
      HDF5 series equal the CSV columns, no penetration is left at the end
      of any step, the disc's angular momentum changes by the torque impulse
      minus the pin forces' moment (1e-8 of T dt; measured 1e-11), and solution.pvd lists every output step. (In a dynamic
      state sum F arm differs from T by the disc's inertia torque.)
  check_transient.py motion FILE.prm EXECUTABLE WORKDIR
      Runs FILE.prm once on 2 ranks: the HDF5 series against the CSV, no
      penetration, the angular momentum balance (as restart) and the
      energy balance within 5 % of the largest energy level.
  check_transient.py slow FILE.prm EXECUTABLE WORKDIR
      A slow, damped load ramp with the crank held must end in the
      quasi-static solution of the same scene and mesh: rotation, engaged
      pins and every pin force within 1e-3 (measured 1e-5), the kinetic
      energy gone (1e-6 of the elastic), sum F arm = T (1e-4; measured 6e-6,
      the inertia torque of the decaying motion), and the
      energy balance
      E_kin + E_el + D - W within 1e-3 of W (measured 2e-4).
  check_transient.py cycle FILE.prm EXECUTABLE WORKDIR
      FILE.prm is a run whose active sets cycle (a loose Solver/Relative
      tolerance on a fine contact mesh): it must end, report at least one
      cycle broken by the union of its sets with a tension left of at most
      1e-3 of the largest nodal force, pass the checks of "motion", and
      agree with the same run at a 1000 times tighter tolerance (which
      does not cycle): every pin force within 1e-6 of the largest and the
      rotation within 1e-6 (measured 5e-8 and 4e-9).
  check_transient.py schur FILE.prm EXECUTABLE WORKDIR
      FILE.prm is a Newmark run with Linear solver = direct, which solves
      its active sets through the contact Schur complement on one kept
      factorisation (Contact Schur complement = auto). It is run again
      with the Schur complement off (each active set condensed and
      factorised): energy.csv, stiffness.csv and pin_forces.csv must agree
      to 1e-9 (relative; measured 1e-12; the penetration left, rounding in
      both, excepted), the first run must have
      factorised once in all (preconditioner_setups) and the second once
      per active-set iteration, and the first passes the checks of
      "motion". A third run keeps 20 columns of the inverse (Contact Schur
      complement columns), so that they are dropped and computed again
      over and over: it must report evictions and agree the same way. If
      FILE.prm writes checkpoints, the Schur complement run is also
      stopped after its first checkpoint and resumed, as in "restart",
      and must agree with the uninterrupted one to 1e-9 (measured 1.5e-12:
      the resumed run factorises again and computes its columns in other
      groups, so bit for bit is not expected).
"""
import math
import os
import re
import sys
from pathlib import Path

import h5py
import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import read_csv as rows, run_cycloid  # noqa: E402


def run(exe, prm, cwd, np_=2):
    r = run_cycloid(np_, exe, prm, cwd=cwd, oversubscribe=True)
    if r.returncode != 0:
        print(r.stdout, r.stderr)
        raise SystemExit(f"{prm} failed")
    return r.stdout


def variant(text, out, transient_extra="", run_mode=None, drop_transient=False):
    text = re.sub(r"set Output directory *=.*", f"set Output directory = {out}", text)
    if run_mode:
        text = re.sub(r"set Run *=.*", f"set Run = {run_mode}", text)
    if drop_transient:
        text = re.sub(r"subsection Transient.*?\nend\n?", "", text, flags=re.S)
    elif transient_extra:
        text = text.replace("subsection Transient", "subsection Transient\n" + transient_extra)
    return text


def same(a, b, skip=("wall_s", "peak_memory_MB"), tol=1e-12):
    bad = []
    if len(a) != len(b):
        return [f"{len(a)} rows vs {len(b)}"]
    for k, (ra, rb) in enumerate(zip(a, b)):
        for key in ra:
            if key in skip:
                continue
            x, y = float(ra[key]), float(rb[key])
            if math.isnan(x) and math.isnan(y):
                continue
            if abs(x - y) > tol * max(abs(x), abs(y), 1e-30) and abs(x - y) > 1e-300:
                bad.append(f"row {k} {key}: {x!r} vs {y!r}")
    return bad


def motion_checks(text, out):
    """The checks of a run in motion on its output directory OUT: the
    HDF5 series against the CSV, no penetration, the angular momentum
    balance."""
    failures = []
    energy = rows(f"{out}/energy.csv")
    stiffness = rows(f"{out}/stiffness.csv")
    with h5py.File(f"{out}/transient.h5", "r") as h:
        for key, col in (("time_s", "time_s"), ("kinetic_J", "kinetic_J"), ("elastic_J", "elastic_J"),
                         ("external_work_J", "external_work_J"), ("rotation_rad", "rotation_rad")):
            series = np.array([float(r[col]) for r in energy])
            if not np.allclose(h[key][:], series, rtol=1e-10, atol=0):
                failures.append(f"transient.h5 {key} differs from energy.csv")
        fn = h["pin_forces/Fn_N"][:]
        zp = int(h.attrs["number_of_pins"])
        if fn.shape != (len(energy), zp):
            failures.append(f"pin_forces/Fn_N shape {fn.shape}")
        print(f"transient.h5: {len(h['time_s'])} steps, pin forces {fn.shape}, largest {fn.max():.4g} N")
    pen = max(float(r["max_penetration_um"]) for r in energy)
    print(f"largest penetration at the end of a step: {pen:.3g} um")
    if pen > 1e-6:
        failures.append(f"penetration {pen} um left at the end of a step")
    # Angular momentum of the disc about its centre: L_n - L_{n-1} =
    # dt ((T_{n-1} + T_n)/2 - M_n), M_n = sum F arm of the step-average
    # contact forces (contact-stabilised) or (M_{n-1} + M_n)/2 (newmark).
    # Internal forces have no moment (rigid rotations are K's null space),
    # so this holds to round-off: it checks the inertia, the pin forces in
    # the housing frame and their arms together.
    scheme = re.search(r"set Scheme *= *([\w-]+)", text).group(1)
    dt = float(re.search(r"set Time step *= *([0-9.e+-]+)", text).group(1))
    L0 = T0 = M0 = 0.
    worst = 0.
    for e, r in zip(energy, stiffness):
        L, T, M = float(e["angular_momentum_Nms"]), float(e["torque_Nm"]), float(r["reaction_torque_Nm"])
        m = M if scheme == "contact-stabilised" else 0.5 * (M0 + M)
        worst = max(worst, abs((L - L0) - dt * (0.5 * (T0 + T) - m)) / (dt * max(abs(T), 1e-30)))
        L0, T0, M0 = L, T, M
    print(f"angular momentum balance ({scheme}): worst error {worst:.2e} of the torque impulse")
    if scheme in ("contact-stabilised", "newmark") and worst > 1e-8:
        failures.append(f"angular momentum balance violated by {worst:.2e} of T dt")
    return failures


def stop_and_resume(exe, text, work, full, tol=1e-12, skip=("wall_s", "peak_memory_MB")):
    """Runs TEXT stopped after its first checkpoint (output directory
    "part") and resumed from it, and compares the resumed run's CSVs and
    transient.h5 with the uninterrupted run in WORK/FULL: to TOL relative,
    the columns SKIP excepted; the HDF5 series bit for bit when TOL is
    1e-12, else to TOL."""
    every = int(re.search(r"Checkpoint interval *= *(\d+)", text).group(1))
    open(f"{work}/part.prm", "w").write(variant(text, "part", f"  set Stop after step = {every}"))
    open(f"{work}/resume.prm", "w").write(variant(text, "part", "  set Resume = true"))
    run(exe, "part.prm", work)
    n_part = len(rows(f"{work}/part/energy.csv"))
    out = run(exe, "resume.prm", work)
    failures = []
    if n_part != every:
        failures.append(f"the stopped run wrote {n_part} energy rows, expected {every}")
    if "resumed from the checkpoint at step" not in out:
        failures.append("the resumed run did not report its checkpoint")
    for f in ("energy.csv", "stiffness.csv", "pin_forces.csv"):
        a, b = rows(f"{work}/{full}/{f}"), rows(f"{work}/part/{f}")
        bad = same(a, b, skip=skip, tol=tol)
        print(f"{f}: {len(a)} rows, uninterrupted vs resumed: "
              f"{('identical' if tol <= 1e-12 else f'equal to {tol:g}') if not bad else bad[:3]}")
        failures += [f"{f}: {x}" for x in bad[:5]]
    with h5py.File(f"{work}/{full}/transient.h5", "r") as h, h5py.File(f"{work}/part/transient.h5", "r") as g:
        for key in ("time_s", "kinetic_J", "elastic_J", "external_work_J", "rotation_rad"):
            equal = (np.array_equal(h[key][:], g[key][:]) if tol <= 1e-12 else
                     np.allclose(h[key][:], g[key][:], rtol=tol, atol=0))
            if not equal:
                failures.append(f"transient.h5 {key}: resumed run differs")
    return failures


def restart(prm, exe, work):
    os.makedirs(work, exist_ok=True)
    text = open(prm).read()
    open(f"{work}/full.prm", "w").write(variant(text, "full"))
    run(exe, "full.prm", work)
    failures = stop_and_resume(exe, text, work, "full")
    failures += motion_checks(text, f"{work}/full")
    energy = rows(f"{work}/full/energy.csv")
    pvd = open(f"{work}/part/solution.pvd").read()
    steps = re.findall(r'timestep="([0-9.e+-]+)"', pvd)
    out_every = int(re.search(r"Output interval *= *(\d+)", text).group(1))
    expect = [s for s in range(1, len(energy) + 1) if s % out_every == 0]
    if [int(float(s)) for s in steps] != expect:
        failures.append(f"solution.pvd lists {steps}, expected {expect}")
    return failures


def motion(prm, exe, work):
    """One run in motion: motion_checks() and the energy balance, whose
    error (the moving obstacles' work is a trapezoidal estimate) must stay
    below the program's warning level, 5 % of the largest energy level
    (measured 1.5 % in 3D, 1.0 % in 2D: the moving obstacles' work is a
    trapezoidal estimate, worst at engagement)."""
    os.makedirs(work, exist_ok=True)
    text = open(prm).read()
    open(f"{work}/transient.prm", "w").write(variant(text, "transient"))
    run(exe, "transient.prm", work)
    failures = motion_checks(text, f"{work}/transient")
    energy = rows(f"{work}/transient/energy.csv")
    worst = max(abs(float(r["relative_balance_error"])) for r in energy)
    print(f"energy balance: worst error {worst:.2e} of the largest energy level")
    if worst > 5e-2:
        failures.append(f"energy balance error {worst:.2e} of the largest level")
    return failures


def cycle(prm, exe, work):
    os.makedirs(work, exist_ok=True)
    text = open(prm).read()
    tol = float(re.search(r"set Relative tolerance *= *([0-9.e+-]+)", text).group(1))
    open(f"{work}/cycle.prm", "w").write(variant(text, "cycle"))
    tight = re.sub(r"set Relative tolerance *=.*", f"set Relative tolerance = {tol * 1e-3:g}", text)
    open(f"{work}/tight.prm", "w").write(variant(tight, "tight"))
    out = run(exe, "cycle.prm", work)
    notes = re.findall(r"note: the active set cycled (\d+) time.*?largest tension left ([0-9.e+-]+)", out)
    broken = sum(int(n) for n, _ in notes)
    worst = max((float(t) for _, t in notes), default=0.)
    print(f"cycles broken: {broken} in {len(notes)} steps, largest tension left {worst:.3g}")
    failures = []
    if broken == 0:
        failures.append("no active-set cycle was broken: the case no longer exercises the remedy")
    if worst > 1e-3:
        failures.append(f"a broken cycle left a tension of {worst} of the largest nodal force")
    failures += motion_checks(text, f"{work}/cycle")
    run(exe, "tight.prm", work)
    fa = np.array([float(r["Fn_N"]) for r in rows(f"{work}/cycle/pin_forces.csv")])
    fb = np.array([float(r["Fn_N"]) for r in rows(f"{work}/tight/pin_forces.csv")])
    ra = np.array([float(r["rotation_rad"]) for r in rows(f"{work}/cycle/energy.csv")])
    rb = np.array([float(r["rotation_rad"]) for r in rows(f"{work}/tight/energy.csv")])
    if fa.shape != fb.shape or ra.shape != rb.shape:
        return failures + [f"{fa.shape} pin forces and {ra.shape} steps vs {fb.shape} and {rb.shape}"]
    df = np.abs(fa - fb).max() / fb.max()
    dr = np.abs(ra - rb).max() / np.abs(rb).max()
    print(f"against tolerance {tol * 1e-3:g}: pin forces {df:.2e} of the largest, rotation {dr:.2e}")
    if df > 1e-6 or dr > 1e-6:
        failures.append(f"the cycled run differs from the tight one: pin forces {df:.2e}, rotation {dr:.2e}")
    return failures


def schur(prm, exe, work):
    os.makedirs(work, exist_ok=True)
    text = open(prm).read()
    open(f"{work}/schur.prm", "w").write(variant(text, "schur"))
    condensed = text.replace("subsection Solver",
                             "subsection Solver\n  set Contact Schur complement = false")
    open(f"{work}/condensed.prm", "w").write(variant(condensed, "condensed"))
    # Few columns kept: they are dropped and computed again all the time.
    evicting = text.replace("subsection Solver",
                            "subsection Solver\n  set Contact Schur complement columns = 20")
    open(f"{work}/evicting.prm", "w").write(variant(evicting, "evicting"))
    run(exe, "schur.prm", work)
    run(exe, "condensed.prm", work)
    debug = run_cycloid(2, exe, "evicting.prm", cwd=work, env={"CYCLOID_DEBUG": "1"}, oversubscribe=True)
    failures = []
    if debug.returncode != 0:
        print(debug.stdout, debug.stderr)
        failures.append("evicting.prm failed")
    evictions = [int(n) for n in re.findall(r"(\d+) evictions", debug.stderr)]
    print(f"with 20 columns kept: {max(evictions, default=0)} evictions")
    if max(evictions, default=0) == 0:
        failures.append("the run keeping 20 columns dropped none: eviction is not exercised")
    for name in ("schur", "evicting"):
        for f in ("energy.csv", "stiffness.csv", "pin_forces.csv"):
            a, b = rows(f"{work}/{name}/{f}"), rows(f"{work}/condensed/{f}")
            # The penetration left is rounding in both (1e-16 um;
            # motion_checks bounds it), so it is not compared.
            bad = same(a, b, skip=("wall_s", "peak_memory_MB", "preconditioner_setups",
                                   "max_penetration_um"), tol=1e-9)
            print(f"{f}: {len(a)} rows, {name} vs condensed: {'equal to 1e-9' if not bad else bad[:3]}")
            failures += [f"{name} {f}: {x}" for x in bad[:5]]
    st, sc = rows(f"{work}/schur/stiffness.csv"), rows(f"{work}/condensed/stiffness.csv")
    fs = [int(r["preconditioner_setups"]) for r in st]
    fc = [int(r["preconditioner_setups"]) for r in sc]
    its = [int(r["active_set_iterations"]) for r in sc]
    print(f"factorisations per step: Schur complement {fs}, condensed {fc} (active-set iterations {its})")
    if sum(fs) != 1 or fs[0] != 1:
        failures.append(f"the Schur complement run factorised {fs} times per step, not once in all")
    if fc != its:
        failures.append(f"the condensed run factorised {fc} times per step, not once per set {its}")
    failures += motion_checks(text, f"{work}/schur")
    if re.search(r"Checkpoint interval *= *[1-9]", text):
        # The resumed run factorises again and computes its columns in
        # other groups, so it agrees to rounding, not bit for bit.
        failures += stop_and_resume(exe, text, work, "schur", tol=1e-9,
                                    skip=("wall_s", "peak_memory_MB", "preconditioner_setups",
                                          "max_penetration_um"))
    return failures


def slow(prm, exe, work):
    os.makedirs(work, exist_ok=True)
    text = open(prm).read()
    open(f"{work}/transient.prm", "w").write(variant(text, "transient"))
    # The same mesh as the transient's: no error estimate (it would raise
    # Contact refinements and solve on three levels).
    open(f"{work}/quasi.prm", "w").write(
        variant(text, "quasi", run_mode="quasi-static", drop_transient=True)
        + "subsection Mesh\n  set Error estimate = false\nend\n")
    run(exe, "transient.prm", work)
    run(exe, "quasi.prm", work)
    failures = []
    st, sq = rows(f"{work}/transient/stiffness.csv")[-1], rows(f"{work}/quasi/stiffness.csv")[-1]
    bt, bq = float(st["rotation_rad"]), float(sq["rotation_rad"])
    print(f"rotation: transient end {bt:.8e}, quasi-static {bq:.8e} rad ({bt / bq - 1:+.2e}); "
          f"pins {st['pins_in_contact']} / {sq['pins_in_contact']}")
    if abs(bt / bq - 1) > 1e-3 or st["pins_in_contact"] != sq["pins_in_contact"]:
        failures.append("end state differs from the quasi-static state")
    pt = [r for r in rows(f"{work}/transient/pin_forces.csv") if r["step"] == st["step"]]
    pq = rows(f"{work}/quasi/pin_forces.csv")
    fmax = max(float(r["Fn_N"]) for r in pq)
    worst = max(abs(float(a["Fn_N"]) - float(b["Fn_N"])) for a, b in zip(pt, pq)) / fmax
    print(f"pin forces: largest {fmax:.6g} N, worst difference {worst:.2e} of it")
    if len(pt) != len(pq) or worst > 1e-3:
        failures.append(f"pin forces differ by {worst:.2e} of the largest")
    s_arm = float(st["reaction_torque_Nm"])
    print(f"sum F arm at the end {s_arm:.10g} N m, T {float(st['torque_Nm']):g} N m")
    if abs(s_arm / float(st["torque_Nm"]) - 1) > 1e-4:
        failures.append(f"sum F arm {s_arm} != T at the end")
    e = rows(f"{work}/transient/energy.csv")[-1]
    kin, el, w = float(e["kinetic_J"]), float(e["elastic_J"]), float(e["external_work_J"])
    bal = float(e["balance_error_J"])
    print(f"end: kinetic {kin:.3e} J, elastic {el:.6e} J, work {w:.6e} J, balance error {bal:+.3e} J "
          f"({bal / w:+.2e} of the work)")
    if kin > 1e-6 * el:
        failures.append(f"kinetic energy {kin} J left at the end")
    if abs(bal) > 1e-3 * w:
        failures.append(f"energy balance error {bal} J")
    return failures


if __name__ == "__main__":
    mode, prm, exe, work = sys.argv[1:5]
    failures = {"restart": restart, "slow": slow, "motion": motion, "cycle": cycle,
                "schur": schur}[mode](os.path.abspath(prm), exe, work)
    print("\n".join(failures) if failures else "all checks passed")
    sys.exit(1 if failures else 0)
