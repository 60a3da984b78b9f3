#!/usr/bin/python3
"""Check a reduced (or analytic) run against the full FE model at the same
states.

Usage: check_fe.py FILE.prm [--exe EXE] [--ranks N] [--mesh reference|quick]
                   [--rerun]

FILE.prm is a `Run = reduced` or `Run = analytic` parameter file. The
script

1. runs it, unless its output directory holds results of a run of this
   mode newer than the file (`--rerun` runs it anyway);
2. writes `fe-check.prm` into that directory: the same file with
   `Run = quasi-static` (`phase-sweep` for several phases), the output in
   `<output>/fe-check/` and the FE mesh of `--mesh`:
   - `reference` (default): 2D Contact refinements 4 within 0.3 mm (its
     error estimate on); 3D one axial layer per disc, Contact refinements 3
     within 0.3 mm at the loaded pins, a distributed mesh (the FE seed
     case; within 0.5 % of the finest 3D runs in K);
   - `quick`: one contact refinement fewer;
3. runs the FE model and, as soon as it has meshed, prints what the check
   will cost (its cost model's time per state times the states);
4. prints per state the distance of the run from the FE: K_secant,
   K_tangent, the largest pin force and every pin force as a fraction of the
   largest, the engaged pins, next to the run's own error estimate and the
   FE's, and writes them to `<output>/fe_check.csv`.

Exit status: 0 when every state is within the two estimates together
(|difference| <= run's estimate + FE's estimate, where both exist), 3 when
one is not (the table says which), 1 on a failed run or a bad file.
"""
import argparse
import csv
import math
import os
import re
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from cycloid_tools import (mpirun_command, parameter_getter,  # noqa: E402
                           parameter_values, read_csv, run_cycloid)

MESH = {
    ("reference", 2): {"Contact refinements": 4, "Contact refinement radius": 0.3},
    ("quick", 2): {"Contact refinements": 3, "Contact refinement radius": 0.3},
    ("reference", 3): {"Axial layers per disc": 1, "Contact refinements": 3,
                       "Contact refinement radius": 0.3, "Contact refinement side": "loaded",
                       "Triangulation": "distributed"},
    ("quick", 3): {"Axial layers per disc": 1, "Contact refinements": 2,
                   "Contact refinement radius": 0.3, "Contact refinement side": "loaded",
                   "Triangulation": "distributed"},
}
COST = re.compile(r"estimated time ([0-9.e+-]+) s per state")
CYCLES = re.compile(r"at most ([0-9.e+-]+) s if Target accuracy")


def fail(message):
    print("check_fe: error: " + message, file=sys.stderr)
    sys.exit(1)


def fe_prm(source_text, out, run, dim, mesh):
    """The parameter file's text with the FE run's entries set after it
    (a later `set` wins in deal.II's ParameterHandler)."""
    lines = [source_text.rstrip("\n"), "", "# check_fe.py: the full FE model of the same states",
             "set Run = " + run, "set Output directory = " + out,
             "set Write solution = false", "subsection Mesh"]
    lines += ["  set %s = %s" % (k, v) for k, v in MESH[(mesh, dim)].items()]
    return "\n".join(lines + ["end", ""])


def run_streamed(command, log_path, states):
    """Run @p command, its output into @p log_path, and print its cost
    estimate for @p states states as soon as the FE prints it."""
    announced = False
    start = time.monotonic()
    with open(log_path, "w") as log:
        p = subprocess.Popen(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             text=True, errors="replace")
        for line in p.stdout:
            log.write(line)
            m = COST.search(line)
            if m and not announced:
                per_state = float(m.group(1))
                cycles = CYCLES.search(line)
                most = (", at most %.0f s if every state takes all its Target accuracy "
                        "cycles" % (float(cycles.group(1)) * states)) if cycles else ""
                print("  the FE model: %s\n  so the check takes about %.0f s (%d state(s), "
                      "the FE cost model's estimate%s)"
                      % (line.strip(), per_state * states, states, most), flush=True)
                announced = True
            if line.startswith("  state ") or "Error" in line or "WARNING" in line:
                print("  FE " + line.strip(), flush=True)
        p.wait()
    return p.returncode, time.monotonic() - start


def forces(pins, step):
    return {(p["disc"], p["pin"]): float(p["Fn_N"]) for p in pins if p["step"] == step}


def number(row, key):
    text = row.get(key, "")
    return float(text) if text not in ("", None) else math.nan


def compare(run_dir, fe_dir):
    """Rows per state of the run that the FE has (matched by crank angle
    and torque)."""
    run_states = read_csv(os.path.join(run_dir, "stiffness.csv"))
    run_pins = read_csv(os.path.join(run_dir, "pin_forces.csv"))
    fe_states = read_csv(os.path.join(fe_dir, "stiffness.csv"))
    fe_pins = read_csv(os.path.join(fe_dir, "pin_forces.csv"))
    rows = []
    for a in run_states:
        match = [b for b in fe_states
                 if abs(float(b["crank_deg"]) - float(a["crank_deg"])) < 1e-6
                 and abs(float(b["torque_Nm"]) - float(a["torque_Nm"])) < 1e-9]
        if not match:
            continue
        b = match[0]
        fa, fb = forces(run_pins, a["step"]), forces(fe_pins, b["step"])
        fmax = max(fb.values()) if fb else 0
        row = {"crank_deg": a["crank_deg"], "torque_Nm": a["torque_Nm"]}
        for q, key in [("K_secant", "K_secant_Nm_per_rad"), ("K_tangent", "K_tangent_Nm_per_rad")]:
            fe_value = float(b[key])
            row[q] = float(a[key]) / fe_value - 1 if fe_value else math.nan
            row[q + "_estimate"] = number(a, q + "_error")
            row[q + "_fe_estimate"] = number(b, q + "_error")
        row["max_pin_force"] = float(a["max_pin_force_N"]) / fmax - 1 if fmax else math.nan
        row["pin_forces"] = (max(abs(fa.get(k, 0) - fb.get(k, 0)) for k in set(fa) | set(fb))
                             / fmax if fmax else math.nan)
        row["pin_forces_estimate"] = number(a, "max_pin_force_error")
        fe_pin = number(b, "max_pin_force_error")
        row["pin_forces_fe_estimate"] = fe_pin if not math.isnan(fe_pin) else number(
            b, "resolution_error")
        row["engaged"] = sum(v > 0 for v in fa.values())
        row["engaged_fe"] = sum(v > 0 for v in fb.values())
        within = True
        for q in ["K_secant", "K_tangent", "pin_forces"]:
            band = row[q + "_estimate"] + row[q + "_fe_estimate"]
            if not math.isnan(band) and abs(row[q]) > band:
                within = False
        row["within_estimates"] = int(within)
        rows.append(row)
    return rows


def pct(x):
    return "  n/a" if math.isnan(x) else "%5.2f" % (100 * x)


def print_table(rows):
    print("\n  distance from the full FE model [%] (run's own estimate / FE's estimate):")
    print("  crank  torque | K_secant           | K_tangent          | every pin force    "
          "| F_max  | engaged | verdict")
    for r in rows:
        cells = []
        for q in ["K_secant", "K_tangent", "pin_forces"]:
            cells.append("%+6.2f (%s/%s)" % (100 * r[q], pct(r[q + "_estimate"]).strip(),
                                             pct(r[q + "_fe_estimate"]).strip()))
        print("  %5s %7s | %-18s | %-18s | %-18s | %+6.2f | %3d/%-3d | %s" % (
            r["crank_deg"], r["torque_Nm"], cells[0], cells[1], cells[2],
            100 * r["max_pin_force"], r["engaged"], r["engaged_fe"],
            "within the estimates" if r["within_estimates"] else "OUTSIDE the estimates"))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("prm")
    ap.add_argument("--exe", default=os.path.join(os.path.dirname(os.path.abspath(__file__)),
                                                  "..", "build", "cycloid-contact"))
    ap.add_argument("--ranks", type=int, default=2)
    ap.add_argument("--mesh", choices=["reference", "quick"], default="reference")
    ap.add_argument("--rerun", action="store_true")
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    if not os.path.isfile(args.prm):
        fail("parameter file '%s' not found" % args.prm)
    try:
        values = parameter_values(args.prm, exe=exe)
    except subprocess.CalledProcessError as e:
        fail("cannot read %s:\n%s" % (args.prm, (e.stdout or "") + (e.stderr or "")))
    get = parameter_getter(values)
    mode = get("", "Run")
    if mode not in ("reduced", "analytic"):
        fail("%s has Run = %s; the FE check is for a reduced or analytic run" % (args.prm, mode))
    dim = int(get("Scene", "Dimension"))
    out = get("", "Output directory")
    phases = int(get("Loading", "Number of phases"))

    # 1. The run itself, unless its output directory holds results of a
    # run of this mode newer than the file.
    done = os.path.join(out, "stiffness.csv")
    fresh = (os.path.isfile(done) and os.path.getmtime(done) > os.path.getmtime(args.prm)
             and os.path.isfile(os.path.join(out, "parameters.json"))
             and parameter_values(out).get("Run") == mode)
    if args.rerun or not fresh:
        print("check_fe: running %s (Run = %s) first" % (args.prm, mode), flush=True)
        p = run_cycloid(args.ranks, exe, args.prm, log=os.path.join(
            os.path.dirname(os.path.abspath(out)) or ".", os.path.basename(out) + ".log"))
        if p.returncode != 0:
            print(p.stdout)
            fail("the %s run failed" % mode)
    n_states = len(read_csv(os.path.join(out, "stiffness.csv")))

    # 2./3. The FE model of the same states.
    fe_out = os.path.join(out, "fe-check")
    fe_file = os.path.join(out, "fe-check.prm")
    with open(args.prm) as f:
        text = f.read()
    run = "phase-sweep" if phases > 1 else "quasi-static"
    # Deviation files are named relative to the run's file; the FE's file
    # lives elsewhere, so it names them absolutely.
    here = os.path.dirname(os.path.abspath(args.prm))
    files = ["  set %s = %s" % (entry, os.path.join(here, get("Deviations", entry)))
             for entry in ["Pin deviations file", "Disc deviations file"]
             if get("Deviations", entry)]
    if files:
        text += "\n" + "\n".join(["subsection Deviations"] + files + ["end", ""])
    with open(fe_file, "w") as f:
        f.write(fe_prm(text, fe_out, run, dim, args.mesh))
    print("check_fe: the full FE model (%s, %dD, %s mesh) of the %d state(s) of %s; "
          "its file: %s" % (run, dim, args.mesh, n_states, out, fe_file), flush=True)
    command = mpirun_command(args.ranks, exe, fe_file)
    code, wall = run_streamed(command, fe_out + ".log", n_states)
    if code != 0:
        fail("the FE run failed (exit %d); its log: %s.log" % (code, fe_out))
    print("check_fe: the FE took %.0f s" % wall)

    # 4. The distances.
    rows = compare(out, fe_out)
    if not rows:
        fail("no state of %s has an FE state at the same crank angle and torque" % out)
    print_table(rows)
    path = os.path.join(out, "fe_check.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, list(rows[0]))
        w.writeheader()
        for r in rows:
            w.writerow({k: ("%.6g" % v) if isinstance(v, float) else v for k, v in r.items()})
    print("  written: %s" % path)
    sys.exit(0 if all(r["within_estimates"] for r in rows) else 3)


if __name__ == "__main__":
    main()
