"""parameters.prm: a run leaves every entry with its value in its output
directory, and running on that file repeats the run (the same
stiffness.csv and pin_forces.csv up to the timing and memory columns).

Usage: check_parameters_file.py EXECUTABLE PRM WORKDIR NP"""
import csv
import os
import shutil
import subprocess
import sys

exe, prm, work, np = sys.argv[1], os.path.abspath(sys.argv[2]), sys.argv[3], int(sys.argv[4])
# Columns that measure the machine, not the result.
VOLATILE = {"wall_s", "peak_memory_MB"}


def entries(lines):
    """{(subsection path, name): value} of the `set` lines of a prm text."""
    values, path = {}, []
    for raw in lines:
        line = raw.split("#")[0].strip()
        if line.startswith("subsection "):
            path.append(line.split(None, 1)[1].strip())
        elif line == "end":
            path.pop()
        elif line.startswith("set "):
            key, value = line[4:].split("=", 1)
            values[("/".join(path), key.strip())] = value.strip()
    return values


def run(directory, prm_file):
    """Run on NP ranks in directory; return the output directory."""
    os.makedirs(directory, exist_ok=True)
    command = [exe, prm_file]
    if np > 1:
        flags = ["--allow-run-as-root"] if os.getuid() == 0 else []
        if (os.cpu_count() or 1) < np:
            flags.append("--oversubscribe")
        command = ["mpirun", *flags, "-np", str(np)] + command
    subprocess.run(command, cwd=directory, check=True, stdout=subprocess.DEVNULL)
    out = entries(open(prm_file))[("", "Output directory")]
    return os.path.join(directory, out)


def rows(path):
    """The rows of a CSV file without the volatile columns."""
    with open(path) as f:
        table = list(csv.DictReader(f))
    return [{k: v for k, v in r.items() if k not in VOLATILE} for r in table]


shutil.rmtree(work, ignore_errors=True)
first = run(os.path.join(work, "first"), prm)
written = os.path.join(first, "parameters.prm")
assert os.path.isfile(written), "no parameters.prm in " + first
used = entries(open(written))
declared = entries(subprocess.run([exe, "--print-parameters"], check=True,
                                  capture_output=True, text=True).stdout.splitlines())
missing = set(declared) - set(used)
assert not missing, f"parameters.prm lacks {sorted(missing)}"
for key, value in entries(open(prm)).items():
    assert used[key] == value, f"{key}: {used[key]!r} written, {value!r} read"

# Run again from the written file, in another directory.
again_dir = os.path.join(work, "again")
os.makedirs(again_dir)
shutil.copy(written, again_dir)
again = run(again_dir, os.path.join(again_dir, "parameters.prm"))
for name in ("stiffness.csv", "pin_forces.csv"):
    a, b = rows(os.path.join(first, name)), rows(os.path.join(again, name))
    assert a and a == b, f"{name} differs after the run from parameters.prm"
assert entries(open(os.path.join(again, "parameters.prm"))) == used
print(f"ok: parameters.prm holds all {len(declared)} entries; the run from it "
      f"gives the same {len(rows(os.path.join(first, 'stiffness.csv')))} "
      "stiffness rows and the same pin forces")
