"""parameters.prm: a run leaves every entry with its value in its output
directory, and running on that file repeats the run (the same
stiffness.csv and pin_forces.csv up to the timing and memory columns).

Usage: check_parameters_file.py EXECUTABLE PRM WORKDIR NP"""
import os
import shutil
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import parameter_values, read_csv, read_prm, run_cycloid  # noqa: E402

exe, prm, work, np = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3], int(sys.argv[4])
# Columns that measure the machine, not the result.
VOLATILE = {"wall_s", "peak_memory_MB"}


def run(directory, prm_file):
    """Run on NP ranks in directory; return the output directory."""
    os.makedirs(directory, exist_ok=True)
    run_cycloid(np if np > 1 else None, exe, prm_file, cwd=directory, check=True)
    return os.path.join(directory, parameter_values(prm_file, exe)["Output directory"])


def rows(path):
    """The rows of a CSV file without the volatile columns."""
    return [{k: v for k, v in r.items() if k not in VOLATILE} for r in read_csv(path)]


shutil.rmtree(work, ignore_errors=True)
first = run(os.path.join(work, "first"), prm)
written = os.path.join(first, "parameters.prm")
assert os.path.isfile(written), "no parameters.prm in " + first
used = read_prm(written)
declared = read_prm(run_cycloid(None, exe, "--print-parameters", check=True).stdout.splitlines())
missing = set(declared) - set(used)
assert not missing, f"parameters.prm lacks {sorted(missing)}"
for key, value in read_prm(prm).items():
    assert used[key] == value, f"{key}: {used[key]!r} written, {value!r} read"

# Run again from the written file, in another directory.
again_dir = os.path.join(work, "again")
os.makedirs(again_dir)
shutil.copy(written, again_dir)
again = run(again_dir, os.path.join(again_dir, "parameters.prm"))
for name in ("stiffness.csv", "pin_forces.csv"):
    a, b = rows(os.path.join(first, name)), rows(os.path.join(again, name))
    assert a and a == b, f"{name} differs after the run from parameters.prm"
assert read_prm(os.path.join(again, "parameters.prm")) == used
print(f"ok: parameters.prm holds all {len(declared)} entries; the run from it "
      f"gives the same {len(rows(os.path.join(first, 'stiffness.csv')))} "
      "stiffness rows and the same pin forces")
