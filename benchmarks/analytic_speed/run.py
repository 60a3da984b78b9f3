#!/usr/bin/python3
"""Compute time of the analytical phase sweep of the seed case: 64 phases
over one mesh period, one torque (1000 N m), both pair models, interleaved
repetitions in one run so that the ratio is measured side by side.

The time is the program's own "compute time" (geometry + load distribution
of all states, without MPI start-up and file set-up), printed by
`Run = analytic`. Writes doc/analytic-speed.csv.
Usage: benchmarks/analytic_speed/run.py [path/to/cycloid-contact] [repetitions]
"""
import os
import re
import statistics
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "cycloid-contact")
REPS = int(sys.argv[2]) if len(sys.argv) > 2 else 7
CASES = {
    "line-contact, unmodified": ("line-contact", 0.0, 0.0),
    "seed, unmodified": ("seed", 0.0, 0.0),
    "line-contact, Delta rp=-0.01 Delta rrp=+0.01": ("line-contact", -0.01, 0.01),
}


def run(model, d_rp, d_rrp, tmp):
    prm = os.path.join(tmp, "speed.prm")
    with open(prm, "w") as f:
        f.write(f"""set Run = analytic
set Output directory = {tmp}/out
subsection Geometry
  set Pin circle radius modification = {d_rp}
  set Pin radius modification = {d_rrp}
end
subsection Loading
  set Torque = 1000
  set Number of phases = 64
end
subsection Analytic
  set Pair stiffness model = {model}
end
""")
    out = run_cycloid(None, EXE, prm, check=True).stdout
    return float(re.search(r"compute time ([0-9.eE+-]+) ms", out).group(1))


def main():
    times = {name: [] for name in CASES}
    with tempfile.TemporaryDirectory() as tmp:
        for _ in range(REPS):
            for name, case in CASES.items():
                times[name].append(run(*case, tmp))
    path = os.path.join(ROOT, "doc", "analytic-speed.csv")
    with open(path, "w") as f:
        f.write("case,phases,repetitions,median_ms,min_ms,max_ms\n")
        for name, t in times.items():
            f.write(f"{name},64,{REPS},{statistics.median(t):.3f},{min(t):.3f},{max(t):.3f}\n")
            print(f"{name:48s} median {statistics.median(t):7.2f} ms  (min {min(t):.2f}, max {max(t):.2f})")
    base = statistics.median(times["seed, unmodified"])
    for name, t in times.items():
        print(f"ratio to the seed model: {name:48s} {statistics.median(t) / base:.2f}")
    print(f"written {path}")


if __name__ == "__main__":
    main()
