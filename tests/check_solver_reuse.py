#!/usr/bin/python3
"""Preconditioner reuse changes the cost, not the answer (issue #14 item 1).

Usage: check_solver_reuse.py EXECUTABLE WORKDIR FILE.prm [FILE.prm ...]

Each FILE.prm runs twice on 2 ranks, with Solver/Preconditioner reuse =
true (one sparsity pattern for every contact candidate, the AMG hierarchy
kept over active sets, states and time steps) and = false (the default: a
new pattern and hierarchy for every active set). CG's answer does not depend on its
preconditioner, so the two agree to TOLERANCE in K_secant, K_tangent, the
reaction torque, every pin force and (transient runs) every energy, with the
same number of pins in contact in every state. The reuse must also build
fewer preconditioners: a reuse that did nothing would fail here. (A pattern
without room for an active set's entries throws in the assembly, so a
superset that is too small fails here too.)

The Error estimate is turned off so that both runs solve the same meshes.

Usage: check_solver_reuse.py --hierarchy EXECUTABLE WORKDIR FILE.prm [...]

The same comparison for Solver/AMG hierarchy: each FILE.prm (3D) runs with
the default (auto, plain aggregation and a W-cycle in 3D) and with
smoothed-V. The answers agree to TOLERANCE; the CG iterations must differ
in every state, or the setting did not reach ML.
"""
import math
import os
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402

TOLERANCE = 1e-7


def run(exe, prm, work, reuse=None, hierarchy=None):
    if hierarchy is None:
        suffix = "-reuse" if reuse else "-rebuild"
        solver = "set Preconditioner reuse = %s" % ("true" if reuse else "false")
    else:
        suffix, solver = "-" + hierarchy, "set AMG hierarchy = %s" % hierarchy
    name = os.path.splitext(os.path.basename(prm))[0] + suffix
    out = os.path.join(work, name)
    text = open(prm).read()
    with open(out + ".prm", "w") as f:
        f.write(text)
        f.write("set Output directory = %s\n" % out)
        f.write("subsection Mesh\n  set Error estimate = false\nend\n")
        f.write("subsection Solver\n  %s\nend\n" % solver)
    if run_cycloid(2, exe, out + ".prm", log=out + ".log").returncode != 0:
        sys.exit("%s failed, see %s.log" % (name, out))
    return out


def close(a, b, scale):
    a, b = float(a), float(b)
    if math.isnan(a) or math.isnan(b):
        return math.isnan(a) and math.isnan(b)
    return abs(a - b) <= TOLERANCE * scale


def compare(name, kept, rebuilt, hierarchy=False):
    # How the two runs are named in the messages.
    one, two = ("with auto", "with smoothed-V") if hierarchy else ("with reuse", "without")
    s1, s0 = rows(os.path.join(kept, "stiffness.csv")), rows(os.path.join(rebuilt, "stiffness.csv"))
    check(len(s1) == len(s0) > 0, "%s: %d states %s, %d %s" % (name, len(s1), one, len(s0), two))
    for a, b in zip(s1, s0):
        for col in ("K_secant_Nm_per_rad", "K_tangent_Nm_per_rad", "reaction_torque_Nm", "max_pin_force_N"):
            scale = max(abs(float(b[col])), 1e-30) if not math.isnan(float(b[col])) else 1
            if col == "reaction_torque_Nm":
                scale = max(abs(float(x[col])) for x in s0)
            check(close(a[col], b[col], scale),
                  "%s step %s: %s %s %s, %s %s" % (name, a["step"], col, a[col], one, b[col], two))
        check(a["pins_in_contact"] == b["pins_in_contact"],
              "%s step %s: %s pins in contact %s, %s %s"
              % (name, a["step"], a["pins_in_contact"], one, b["pins_in_contact"], two))
    p1, p0 = rows(os.path.join(kept, "pin_forces.csv")), rows(os.path.join(rebuilt, "pin_forces.csv"))
    fmax = max(float(p["Fn_N"]) for p in p0)
    check(len(p1) == len(p0), "%s: %d pin rows %s, %d %s" % (name, len(p1), one, len(p0), two))
    worst = max(abs(float(a["Fn_N"]) - float(b["Fn_N"])) for a, b in zip(p1, p0)) / fmax
    check(worst <= TOLERANCE, "%s: pin forces differ by %.2e of the largest" % (name, worst))
    energy = os.path.join(rebuilt, "energy.csv")
    if os.path.exists(energy):
        e1, e0 = rows(os.path.join(kept, "energy.csv")), rows(energy)
        top = max(float(e["elastic_J"]) + float(e["kinetic_J"]) for e in e0)
        for a, b in zip(e1, e0):
            for col in ("kinetic_J", "elastic_J", "external_work_J"):
                check(close(a[col], b[col], top),
                      "%s step %s: %s %s %s, %s %s" % (name, a["step"], col, a[col], one, b[col], two))
    if hierarchy:
        for a, b in zip(s1, s0):
            check(a["linear_iterations"] != b["linear_iterations"],
                  "%s step %s: %s CG iterations with auto, the same with smoothed-V: "
                  "the hierarchy setting did not reach ML" % (name, a["step"], a["linear_iterations"]))
        print("%s: %d states agree (pin forces to %.1e of the largest); CG iterations %s with auto, %s with smoothed-V"
              % (name, len(s1), worst, [int(a["linear_iterations"]) for a in s1],
                 [int(b["linear_iterations"]) for b in s0]))
        return
    builds1 = sum(int(s["preconditioner_setups"]) for s in s1)
    builds0 = sum(int(s["preconditioner_setups"]) for s in s0)
    check(builds1 < builds0, "%s: %d preconditioner builds with reuse, %d without" % (name, builds1, builds0))
    print("%s: %d states agree (pin forces to %.1e of the largest); preconditioner builds %d with reuse, %d without"
          % (name, len(s1), worst, builds1, builds0))


def main():
    hierarchy = sys.argv[1] == "--hierarchy"
    args = sys.argv[2:] if hierarchy else sys.argv[1:]
    exe, work, prms = args[0], args[1], args[2:]
    os.makedirs(work, exist_ok=True)
    for prm in prms:
        name = os.path.basename(prm)
        if hierarchy:
            compare(name, run(exe, prm, work, hierarchy="auto"),
                    run(exe, prm, work, hierarchy="smoothed-V"), hierarchy=True)
        else:
            compare(name, run(exe, prm, work, True), run(exe, prm, work, False))
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
