"""What the run checkers share: collecting the checks that fail, reading a
CSV file's rows (read_csv of scripts/cycloid_tools.py, as rows), the
verdict with the exit status, and a run on 2 ranks with the debug output."""
import csv
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import read_csv as rows, run_cycloid  # noqa: E402

failures = []


def check(condition, message):
    """Record @p message if @p condition is false; return the condition."""
    if not condition:
        failures.append(message)
    return condition


def verdict(passed="all checks passed", shown=30):
    """Print the failed checks (the first @p shown) or @p passed; the exit
    status: 1 if any check failed, else 0."""
    if failures:
        print(f"{len(failures)} check(s) failed:")
        for f in failures[:shown]:
            print("  ", f)
        return 1
    print(passed)
    return 0


def run_debug(exe, prm, out):
    """Run @p exe on @p prm on 2 ranks with CYCLOID_DEBUG=1, stdout and
    stderr into out.log; exit naming the log if the run fails, else return
    the log's text."""
    r = run_cycloid(2, exe, prm, log=out + ".log", env={"CYCLOID_DEBUG": "1"})
    if r.returncode != 0:
        sys.exit("%s failed (see %s.log):\n%s" % (prm, out, r.stdout[-2000:]))
    return r.stdout


def merge_csv(path, columns, new, key, replaced):
    """Write @p new (dicts) to the CSV file @p path with @p columns, after
    the rows already in it whose @p key is not in @p replaced; return
    @p path. A benchmark that re-runs some of its cases keeps the others."""
    kept = rows(path) if os.path.exists(path) else []
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=columns)
        w.writeheader()
        w.writerows([r for r in kept if r[key] not in replaced] + new)
    return path


def same_state(s0, p0, s1, p1, names, tolerance=1e-8):
    """Check that two runs reached the same contact state: @p s0, @p s1
    are stiffness.csv rows, @p p0, @p p1 pin_forces.csv rows keyed by
    (disc, pin); @p names = (name of run 0, name of run 1) for the
    messages. Rotation, K_secant and K_tangent to @p tolerance, the same
    engaged pins and active nodes per pin, every pin force to @p tolerance
    of the largest. Return the largest pin force difference relative to
    the largest force."""
    for key in ("rotation_rad", "K_secant_Nm_per_rad", "K_tangent_Nm_per_rad"):
        a, b = float(s1[key]), float(s0[key])
        print("%-22s %s %.12g, %s %.12g" % (key, names[1], a, names[0], b))
        check(abs(a - b) <= tolerance * abs(b),
              "%s: %.12g (%s) against %.12g (%s)" % (key, a, names[1], b, names[0]))
    check(s1["pins_in_contact"] == s0["pins_in_contact"], "engaged pins differ")
    fmax = max(float(r["Fn_N"]) for r in p0.values())
    worst = max(abs(float(p1[k]["Fn_N"]) - float(p0[k]["Fn_N"])) for k in p0)
    print("pin forces agree to %.2g of the largest" % (worst / fmax))
    check(worst <= tolerance * fmax, "pin forces differ by %g N (largest %g N)" % (worst, fmax))
    check(all(p1[k]["active_nodes"] == p0[k]["active_nodes"] for k in p0), "active nodes per pin differ")
    return worst / fmax


def alternate(doc, cases, settings, one, csv_name, columns, work):
    """The command line of a benchmark that compares @p settings side by
    side (doc: @p doc): --case (default @p cases), --repeat, --settings
    (default @p settings), --exe, --out.
    Calls one(exe, case, setting, repeat, work) for every case and repeat
    with the settings alternating, so that neighbouring runs compare on a
    shared machine, and merges the rows into --out/@p csv_name."""
    import argparse
    root = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    ap = argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("--case", default=cases)
    ap.add_argument("--repeat", type=int, default=1)
    ap.add_argument("--settings", default=",".join(settings),
                    help="the settings to compare, comma-separated (default: %(default)s)")
    ap.add_argument("--exe", default=os.path.join(root, "build", "cycloid-contact"))
    ap.add_argument("--out", default=os.path.join(root, "doc"))
    a = ap.parse_args()
    chosen = a.case.split(",")
    new = [one(os.path.abspath(a.exe), c, s, r, work)
           for c in chosen for r in range(a.repeat) for s in a.settings.split(",")]
    print("wrote", merge_csv(os.path.join(a.out, csv_name), columns, new, "case", chosen))
