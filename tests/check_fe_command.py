#!/usr/bin/python3
"""scripts/check_fe.py, the cross-check of a reduced run against the full FE
model (issue #51 item 3), on a 2D case of one state.

Usage: check_fe_command.py EXECUTABLE WORKDIR

Checks: the reduced run is run first; the FE's cost ("so the check takes
about ... s") is printed before the FE's first state; the FE state is
within the two models' estimates (exit 0) and fe_check.csv has the state
with its distances; a second call reuses the reduced run's results; a
`Run = quasi-static` file is refused with one error line and exit 1.
"""
import os
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from checker import check, rows, verdict  # noqa: E402
from cycloid_tools import run_cycloid  # noqa: E402

SCRIPT = str(Path(__file__).resolve().parents[1] / "scripts" / "check_fe.py")
CASE = """set Run              = reduced
set Output directory = own
subsection Geometry
  set Number of pins    = 30
  set Pin radius        = 4
  set Eccentricity      = 1.5
  set Pin circle radius = 75
  set Tooth width       = 12
end
subsection Scene
  set Dimension = 2
end
subsection Loading
  set Torque = 300
end
"""


def main():
    exe, work = os.path.abspath(sys.argv[1]), sys.argv[2]
    os.makedirs(work, exist_ok=True)
    prm = os.path.join(work, "own.prm")
    with open(prm, "w") as f:
        f.write(CASE)
    command = [SCRIPT, "own.prm", "--exe", exe, "--mesh", "quick"]
    first = run_cycloid(None, "/usr/bin/python3", *command, cwd=work)
    out = first.stdout + first.stderr
    print(out)
    check(first.returncode == 0, "exit %d, not 0" % first.returncode)
    check("running own.prm (Run = reduced) first" in out, "the reduced run was not run first")
    cost, state = out.find("so the check takes about"), out.find("FE state 1/1")
    check(0 <= cost < state, "no cost line before the FE's first state")
    table = rows(os.path.join(work, "own", "fe_check.csv"))
    check(len(table) == 1, "fe_check.csv has %d rows, not 1" % len(table))
    if table:
        r = table[0]
        check(r["within_estimates"] == "1", "the state is outside the estimates: %s" % r)
        check(abs(float(r["K_secant"])) < 0.01, "K_secant differs by %s" % r["K_secant"])
        check(float(r["K_secant_estimate"]) > 0, "no K_secant estimate: %s" % r)
    second = run_cycloid(None, "/usr/bin/python3", *command, cwd=work)
    check(second.returncode == 0 and "running own.prm" not in second.stdout,
          "the second call ran the reduced model again:\n" + second.stdout[:500])
    with open(os.path.join(work, "fe.prm"), "w") as f:
        f.write(CASE.replace("Run              = reduced", "Run = quasi-static"))
    bad = run_cycloid(None, "/usr/bin/python3", SCRIPT, "fe.prm", "--exe", exe, cwd=work)
    lines = [l for l in bad.stderr.splitlines() if l.strip()]
    check(bad.returncode == 1 and len(lines) == 1 and lines[0].startswith("check_fe: error:")
          and "reduced or analytic" in lines[0],
          "a quasi-static file: exit %d, stderr %r" % (bad.returncode, bad.stderr))
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
