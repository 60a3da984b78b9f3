#!/usr/bin/python3
"""Phase groups against one group (issue #14 item 4): the wall time of the
same 2D phase sweep on 2 MPI ranks as one group of 2 ranks and as two
groups of 1 rank (Loading/Ranks per phase group = 0 and 1), side by side.

The sweep is prm/phase-sweep-2d.prm (2D one disc, elastic pins, modified
profile, 9 crank angles over one mesh period; no solution files) at 300 and
1000 N m on the mesh it asks for (Target accuracy 0), as it was measured. Every run is the whole command `mpirun -np 2 cycloid-contact
case.prm`, timed from outside (meshing, set-up, solves, output). The cases
run interleaved (one, groups, one, groups, ...) so that a change of the
machine's load hits both alike; the 1-minute load average is recorded
before each run. The grouped run's K_tangent, beta and pins in contact are
compared with the one-group run's.

Writes <out>/phase-groups.csv (out = doc/ by default) and prints a summary.

Usage:
  /usr/bin/python3 benchmarks/phase_sweep_groups/run.py [--exe PATH]
      [--repeats 2] [--phases 9,10] [--serial] [--out DIR] [--keep DIR]
"""
import argparse
import csv
import os
import re
import shutil
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
PRM = os.path.join(ROOT, "prm", "phase-sweep-2d.prm")


def prm_text(out, group, phases):
    text = open(PRM).read()
    text = re.sub(r"set Output directory *=.*", f"set Output directory = {out}", text)
    text = re.sub(r"set Number of phases *= *\d+",
                  f"set Number of phases = {phases}\n  set Ranks per phase group = {group}", text)
    # The measured sweep: two torques on the example's mesh as asked for
    # (the example itself runs one torque under Target accuracy = auto).
    text = re.sub(r"set Torque *=.*", "set Torque = 300, 1000", text)
    return text + "subsection Mesh\n  set Target accuracy = 0\nend\n"


def run(exe, tmp, name, ranks, group, phases):
    out = os.path.join(tmp, name)
    shutil.rmtree(out, ignore_errors=True)
    prm = os.path.join(tmp, name + ".prm")
    with open(prm, "w") as f:
        f.write(prm_text(out, group, phases))
    load = os.getloadavg()[0]
    p = run_cycloid(ranks, exe, prm, check=True)
    log, wall = p.stdout, p.wall_s
    states = read_csv(os.path.join(out, "stiffness.csv"))
    busy = re.search(r"busy time: (.*); the sweep", log)
    return {"wall": wall, "load": load, "states": states, "busy": busy.group(1) if busy else ""}


def largest_difference(a, b, key):
    return max(abs(float(x[key]) - float(y[key])) / abs(float(x[key])) for x, y in zip(a, b))


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(ROOT, "build", "cycloid-contact"))
    ap.add_argument("--repeats", type=int, default=2)
    ap.add_argument("--phases", default="9,10",
                    help="comma-separated numbers of phases (9: blocks of 4 and 5; 10: 5 and 5)")
    ap.add_argument("--serial", action="store_true", help="also the sweep on 1 rank")
    ap.add_argument("--out", default=os.path.join(ROOT, "doc"))
    ap.add_argument("--keep", help="keep the runs' directories here")
    args = ap.parse_args()

    cases = [("one group of 2 ranks", 2, 0), ("two groups of 1 rank", 2, 1)]
    if args.serial:
        cases.append(("1 rank", 1, 0))
    tmp = args.keep or tempfile.mkdtemp(prefix="phase-groups-")
    os.makedirs(tmp, exist_ok=True)
    lines = []
    for phases in [int(p) for p in args.phases.split(",")]:
        lines += study(args, tmp, cases, phases)
    path = os.path.join(args.out, "phase-groups.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(lines[0].keys()))
        w.writeheader()
        w.writerows(lines)
    print("written", path)
    if not args.keep:
        shutil.rmtree(tmp, ignore_errors=True)
    return 0


def study(args, tmp, cases, phases):
    """The cases at @p phases phases, interleaved; one CSV line per case."""
    results = {name: [] for name, _, _ in cases}
    for rep in range(args.repeats):
        for name, ranks, group in cases:
            r = run(args.exe, tmp, f"{name.replace(' ', '-')}-p{phases}-{rep}", ranks, group, phases)
            results[name].append(r)
            print(f"{phases} phases, {name:22s} run {rep + 1}: {r['wall']:7.2f} s (load before {r['load']:.2f})"
                  + (f"; busy {r['busy']}" if r["busy"] else ""), flush=True)

    ref = results[cases[0][0]][0]["states"]
    lines = []
    for name, ranks, group in cases:
        walls = [r["wall"] for r in results[name]]
        states = results[name][0]["states"]
        diff_k = largest_difference(ref, states, "K_tangent_Nm_per_rad")
        diff_b = largest_difference(ref, states, "rotation_rad")
        same_pins = all(x["pins_in_contact"] == y["pins_in_contact"] for x, y in zip(ref, states))
        state_s = sum(float(s["wall_s"]) for s in states)
        lines.append({"case": name, "ranks": ranks, "ranks_per_phase_group": group,
                      "groups": ranks // group if group else 1, "phases": phases,
                      "states": len(states), "runs": len(walls),
                      "wall_s_min": f"{min(walls):.2f}", "wall_s_mean": f"{sum(walls) / len(walls):.2f}",
                      "sum_state_wall_s": f"{state_s:.2f}",
                      "load_before_min": f"{min(r['load'] for r in results[name]):.2f}",
                      "load_before_max": f"{max(r['load'] for r in results[name]):.2f}",
                      "K_tangent_rel_diff": f"{diff_k:.1e}", "rotation_rel_diff": f"{diff_b:.1e}",
                      "same_pins": same_pins})
    base = float(lines[0]["wall_s_min"])
    for line in lines:
        line["speedup_vs_one_group"] = f"{base / float(line['wall_s_min']):.3f}"
        print(f"{phases} phases, {line['case']:22s}: wall {line['wall_s_min']} s (min of {line['runs']}), "
              f"mean {line['wall_s_mean']} s, speed-up {line['speedup_vs_one_group']}; "
              f"sum of states' wall_s {line['sum_state_wall_s']} s; "
              f"K_tangent vs one group {line['K_tangent_rel_diff']}, beta {line['rotation_rel_diff']}, "
              f"same pins {line['same_pins']}; load before {line['load_before_min']}-{line['load_before_max']}")
    return lines


if __name__ == "__main__":
    sys.exit(main())
