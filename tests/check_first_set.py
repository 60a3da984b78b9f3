#!/usr/bin/python3
"""The first active set changes the path, not the answer (issue #14).

Usage: check_first_set.py FILE.prm EXECUTABLE WORKDIR

FILE.prm is a torque-controlled state on a contact mesh fine enough that
the analytical rotation overlaps more flank nodes than the FE model's
converged set holds. The script runs it on 2 ranks with CYCLOID_DEBUG=1
twice, with `Contact/First active set = overlap` (every node the
analytical rotation closes) and `= hertz` (only those within the Hertz
half-width of the analytical pin force, the default), and checks
* that the state is the same, as the contact problem's solution is
  unique: rotation, K_secant, K_tangent to 1e-8, the same engaged pins
  and active nodes per pin, every pin force to 1e-8 of the largest;
* that the hertz start is the smaller set and nearer the converged one,
  and that it takes fewer active-set iterations (what it is for).
"""
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, run_debug, same_state, verdict  # noqa: E402


def run(exe, text, work, start):
    out = os.path.join(work, start)
    prm = out + ".prm"
    os.makedirs(work, exist_ok=True)
    text = re.sub(r"set Output directory *=.*", "", text)
    with open(prm, "w") as f:
        f.write(text + "\nset Output directory = %s\nsubsection Contact\n  set First active set = %s\nend\n"
                % (out, start))
    log = run_debug(exe, prm, out)
    first = re.search(r"iteration 0: .*active (\d+) -> (\d+)", log)
    check(first is not None, "%s: no iteration 0 in the debug output" % start)
    state = rows(os.path.join(out, "stiffness.csv"))[0]
    pins = {(r["disc"], r["pin"]): r for r in rows(os.path.join(out, "pin_forces.csv"))}
    return state, pins, int(first.group(1))


def main():
    prm, exe, work = sys.argv[1:4]
    text = open(prm).read()
    s0, p0, n0 = run(exe, text, work, "overlap")
    s1, p1, n1 = run(exe, text, work, "hertz")
    agree = same_state(s0, p0, s1, p1, ("overlap", "hertz"))
    final = sum(int(r["active_nodes"]) for r in p0.values())
    i0, i1 = int(s0["active_set_iterations"]), int(s1["active_set_iterations"])
    print("first set: overlap %d nodes, hertz %d nodes, converged %d; active-set iterations %d against %d;"
          " pin forces agree to %.2g of the largest" % (n0, n1, final, i0, i1, agree))
    check(abs(n1 - final) < abs(n0 - final), "the hertz start is not nearer the converged set")
    check(i1 < i0, "the hertz start does not save an active-set iteration (%d against %d)" % (i1, i0))
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
