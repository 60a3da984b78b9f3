#!/usr/bin/env python3
"""`--help` lists every run mode of the `Run` selection, and no other.

The run modes are one table in the code (RunParameters::modes()); this
check reads the selection as the parameter handler declares it (from
`--print-parameters=json`) and the modes `--help` prints, so that a mode
added to one but not the other fails here.

Usage: check_help.py EXECUTABLE
"""
import json
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402


def demangle(name):
    """deal.II's JSON names: every character but [a-zA-Z0-9] as _XX (hex)."""
    return re.sub(r"_([0-9a-f]{2})", lambda m: chr(int(m.group(1), 16)), name)


def run_selection(exe):
    """The names the `Run` entry's Selection pattern admits."""
    out = run_cycloid(None, exe, "--print-parameters=json", check=True).stdout
    tree = {demangle(k): v for k, v in json.loads(out).items()}
    pattern = tree["Run"]["pattern_description"]
    match = re.fullmatch(r"\[Selection (.*) \]", pattern.strip())
    assert match, f"Run's pattern is not a Selection: {pattern!r}"
    return set(match.group(1).split("|"))


def help_modes(exe):
    """The modes `--help` lists under "Run modes", first word of each line."""
    out = run_cycloid(None, exe, "--help", check=True).stdout
    lines = out.splitlines()
    start = next(i for i, l in enumerate(lines) if l.startswith("Run modes"))
    modes = set()
    for line in lines[start + 1:]:
        if not line.startswith("  "):
            break
        modes.add(line.split()[0])
    return modes


def main():
    exe = sys.argv[1]
    selection, listed = run_selection(exe), help_modes(exe)
    print("Run selection:", sorted(selection))
    print("--help lists: ", sorted(listed))
    missing, extra = selection - listed, listed - selection
    if missing or extra:
        print(f"FAIL: --help misses {sorted(missing)}, "
              f"lists unknown {sorted(extra)}")
        return 1
    print(f"OK: {len(selection)} run modes, each in --help")
    return 0


if __name__ == "__main__":
    sys.exit(main())
