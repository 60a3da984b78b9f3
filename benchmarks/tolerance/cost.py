#!/usr/bin/python3
"""The cost of a tolerance study's samples (issue #50 item 6), side by side
with the nominal states of the same reduced model.

Usage: benchmarks/tolerance/cost.py [--exe EXE] [--samples N] [--ranks R]

Cases: the seed stage with the modified profile (Delta rp = -10 um, Delta
rrp = 10 um, rest clearance 17-20 um) in 2D (one disc, pins on their axes)
and 3D (both discs, pins in the housing, the seed case's coarse far field),
crank angle 0, 1 and 3 torques, every band on (typical grades: true
position 10 um, pin radius +-2 um, eccentricity +-3 um, disc angle +-0.5
arcmin, profile +-3 um), no sensitivity. For each: `Run = reduced` of the
nominal stage (its states' wall_s after the first: a state's own solve),
then `Run = tolerance` with N samples; the console's "ms per sample and
rank". Writes doc/tolerance/cost.csv. Run it on an idle machine.
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, "..", "..", "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

STAGE = """
subsection Geometry
  set Pin circle radius modification = -0.01
  set Pin radius modification        = 0.01
end
subsection Loading
  set Torque      = %(torques)s
  set Crank angle = 0
end
subsection Tolerance study
  set Number of samples      = %(samples)d
  set Sensitivity            = false
  set Pin position tolerance = 10
  set Pin radius tolerance   = 2
  set Eccentricity tolerance = 3
  set Disc angle tolerance   = 0.5
  set Profile tolerance      = 3
end
subsection Reduced
  set Error estimate = false
end
"""
SCENES = {
    2: """subsection Scene
  set Dimension   = 2
  set Pins        = elastic
  set Pin support = axis
end
""",
    3: """subsection Scene
  set Dimension       = 3
  set Number of discs = 2
  set Pins            = elastic
  set Pin support     = housing
end
subsection Mesh
  set Flank element size = 2
  set Pin element size   = 1.5
end
""",
}
PER_SAMPLE = re.compile(r"in ([0-9.e+-]+) s on (\d+) rank\(s\): ([0-9.e+-]+) ms per sample and rank")


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("--exe", default=os.path.join(HERE, "..", "..", "build", "cycloid-contact"))
    ap.add_argument("--samples", type=int, default=10000)
    ap.add_argument("--ranks", type=int, default=2)
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    work = tempfile.mkdtemp(prefix="tolerance-cost-")
    load = os.popen("cat /proc/loadavg").read().split()[0]
    out_rows = []
    for dim in (2, 3):
        for torques in ("1000", "300, 1000, 3000"):
            n_t = len(torques.split(","))
            text = SCENES[dim] + STAGE % {"torques": torques, "samples": args.samples}
            result = {"dimension": dim, "torques": n_t, "samples": args.samples,
                      "ranks": args.ranks, "load_before": load}
            for mode in ("reduced", "tolerance"):
                name = "d%d-t%d-%s" % (dim, n_t, mode)
                prm = os.path.join(work, name + ".prm")
                with open(prm, "w") as f:
                    f.write("set Run = %s\nset Output directory = %s\n%s" % (mode, name, text))
                r = run_cycloid(args.ranks, exe, prm, cwd=work, log=os.path.join(work, name + ".log"))
                if r.returncode != 0:
                    sys.exit("%s failed:\n%s" % (prm, r.stdout[-2000:]))
                if mode == "reduced":
                    states = read_csv(os.path.join(work, name, "stiffness.csv"))
                    # The first state carries the condensation; a further
                    # torque is a state's own solve (1 torque: the warm
                    # start is then from the analytical model).
                    own = [float(s["wall_s"]) for s in states[1:]] or [float("nan")]
                    result["nominal_state_ms"] = 1e3 * sum(own) / len(own)
                else:
                    m = PER_SAMPLE.search(r.stdout)
                    result["study_s"] = float(m.group(1))
                    result["sample_ms_per_rank"] = float(m.group(3))
                    result["state_ms_per_rank"] = float(m.group(3)) / n_t
            result["beyond_nominal_ms_per_state"] = (result["state_ms_per_rank"]
                                                     - result["nominal_state_ms"]
                                                     if n_t > 1 else float("nan"))
            print(result, flush=True)
            out_rows.append(result)
    path = os.path.join(HERE, "..", "..", "doc", "tolerance", "cost.csv")
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(out_rows[0].keys()))
        w.writeheader()
        w.writerows(out_rows)
    print("written", os.path.relpath(path))


if __name__ == "__main__":
    main()
