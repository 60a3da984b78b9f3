#!/usr/bin/python3
"""An empty active set under torque control (issue #15 item 6).

Usage: check_free_start.py FILE.prm EXECUTABLE WORKDIR

FILE.prm is a state whose first active set is empty (the analytical
model's rotation closes no node of its coarse mesh). The script runs it on
2 ranks with CYCLOID_DEBUG=1 and checks
* that the first set was empty (iteration 0 reports "active 0 -> N"), so
  the case still exercises the path, and that the run did not cycle;
* the torque balance: reaction torque and sum of pin force x arm = T (1e-8);
* that the state is the contact problem's solution, which is unique: the
  same torque reached from another start, the converged set of a higher
  torque (Torque = 300, 100; the 300 N m state starts from a non-empty
  set), gives the same rotation, K_secant, K_tangent (1e-8), engaged pins
  and pin forces (1e-6 of the largest).
Before the fix the first run stopped with "the active set cycles".
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, run_debug, verdict  # noqa: E402


def run(exe, text, work, name):
    out = os.path.join(work, name)
    prm = out + ".prm"
    with open(prm, "w") as f:
        f.write(re.sub(r"set Output directory *=.*", "set Output directory = " + out, text))
    text = run_debug(exe, prm, out)
    return rows(os.path.join(out, "stiffness.csv")), rows(os.path.join(out, "pin_forces.csv")), text


def main():
    prm, exe, work = sys.argv[1:4]
    os.makedirs(work, exist_ok=True)
    text = open(prm).read()

    s, p, log = run(exe, text, work, "free-start")
    first = re.search(r"iteration 0: .*active (\d+) -> (\d+)", log)
    check(first is not None and first.group(1) == "0",
          "the first active set is not empty: the case no longer exercises the free start")
    check("cycles" not in log, "the active set cycled")
    state = s[0]
    t = float(state["torque_Nm"])
    check(abs(float(state["reaction_torque_Nm"]) - t) <= 1e-8 * t,
          "reaction torque %s != %g" % (state["reaction_torque_Nm"], t))
    total = sum(float(r["Fn_N"]) * float(r["arm_mm"]) * 1e-3 for r in p)
    check(abs(total - t) <= 1e-8 * t, "sum F arm = %g != %g" % (total, t))

    s2, p2, _ = run(exe, re.sub(r"set Torque *=.*", "set Torque = 300, 100", text), work, "from-300")
    warm = [r for r in s2 if float(r["torque_Nm"]) == t][0]
    for key in ("rotation_rad", "K_secant_Nm_per_rad", "K_tangent_Nm_per_rad"):
        a, b = float(state[key]), float(warm[key])
        print("%-22s free start %.10g, from 300 N m %.10g" % (key, a, b))
        check(abs(a - b) <= 1e-8 * abs(b), "%s: %g from the free start, %g from 300 N m" % (key, a, b))
    check(state["pins_in_contact"] == warm["pins_in_contact"], "engaged pins differ")
    forces = {(r["disc"], r["pin"]): float(r["Fn_N"]) for r in p}
    warm_forces = {(r["disc"], r["pin"]): float(r["Fn_N"]) for r in p2 if r["step"] == warm["step"]}
    fmax = max(warm_forces.values())
    worst = max(abs(forces[k] - warm_forces[k]) for k in warm_forces)
    check(worst <= 1e-6 * fmax, "pin forces differ by %g N (largest %g N)" % (worst, fmax))
    print("free start: %s active-set iterations, %s pins; pin forces agree to %.2g of the largest"
          % (state["active_set_iterations"], state["pins_in_contact"], worst / fmax))
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
