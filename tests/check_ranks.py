#!/usr/bin/python3
"""The same quasi-static run on more ranks against a reference run.

Usage: check_ranks.py [--distributed] FILE.prm EXECUTABLE REFERENCE_DIR NP [NP ...]

Runs FILE.prm on each NP ranks (oversubscribed where NP exceeds the cores)
and compares its outputs with REFERENCE_DIR (the same prm's output on other
ranks, e.g. the 1-rank run of run_ranks.sh):

* the same states, engaged pins and active-set iterations;
* the same active set: every pin has the same number of active contact
  nodes (`active_nodes` of pin_forces.csv);
* the rotation, K_secant and K_tangent within 1e-8 (relative) and every pin
  force within 1e-8 of the state's largest (issue #14 item 3).

With --distributed the runs hold the mesh on p4est (`Mesh/Triangulation =
distributed`: each refined cell on one rank, contact nodes, master faces
and ties gathered), against a reference on the shared mesh: the same
answer, whatever holds the cells.

The partition changes the AMG hierarchy and the order of the sums, so the
answers differ at the level of CG's tolerance (1e-10), not by zero; the
largest differences are printed. benchmarks/ranks/run.py uses compare()
for its table (doc/ranks.md).
"""
import os
import sys
from pathlib import Path

from checker import check, rows, verdict

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402

TOL = 1e-8


def read(directory):
    """stiffness.csv's states and pin_forces.csv's rows by step."""
    pins = {}
    for r in rows(os.path.join(directory, "pin_forces.csv")):
        pins.setdefault(r["step"], []).append(r)
    return rows(os.path.join(directory, "stiffness.csv")), pins


def compare(ref, other):
    """Largest differences of @p other from @p ref (both from read()):
    relative in beta and K, pin forces relative to the state's largest;
    same_active_set is whether the states, pins, active nodes and
    active-set iterations are the same."""
    (s0, p0), (s1, p1) = ref, other
    d = {"beta": 0., "K_secant": 0., "K_tangent": 0., "pin_forces": 0.,
         "same_active_set": len(s0) == len(s1)}
    for a, b in zip(s0, s1):
        for key, col in (("beta", "rotation_rad"),
                         ("K_secant", "K_secant_Nm_per_rad"),
                         ("K_tangent", "K_tangent_Nm_per_rad")):
            x, y = float(a[col]), float(b[col])
            d[key] = max(d[key], abs(x - y) / abs(x))
        pa, pb = p0.get(a["step"], []), p1.get(b["step"], [])
        d["same_active_set"] &= len(pa) == len(pb) and all(
            a[k] == b[k] for k in ("pins_in_contact", "active_set_iterations"))
        largest = max([float(r["Fn_N"]) for r in pa] + [1e-300])
        for ra, rb in zip(pa, pb):
            d["pin_forces"] = max(
                d["pin_forces"], abs(float(ra["Fn_N"]) - float(rb["Fn_N"])) / largest)
            d["same_active_set"] &= ra["active_nodes"] == rb["active_nodes"]
    return d


def prm_into(prm, work, distributed=False):
    """A copy of @p prm that writes its CSV files, and no solution files,
    into @p work (on a distributed mesh if @p distributed); returns its
    path."""
    path = work + ".prm"
    with open(path, "w") as f:
        f.write(open(prm).read())
        f.write("\nset Output directory = %s\nset Write solution = false\n" % work)
        # Always written: the prm may name a triangulation of its own.
        f.write("subsection Mesh\n  set Triangulation = %s\nend\n"
                % ("distributed" if distributed else "shared"))
    return path


def run(prm, exe, ranks, work, distributed=False):
    """Run @p prm on @p ranks ranks (oversubscribed where the ranks exceed
    the cores) with its output in @p work."""
    p = run_cycloid(ranks, exe, prm_into(prm, work, distributed))
    return p.returncode, p.stdout[-2000:] + p.stderr[-2000:]


def main():
    args = sys.argv[1:]
    distributed = "--distributed" in args
    if distributed:
        args.remove("--distributed")
    prm, exe, reference = args[:3]
    ref = read(reference)
    for ranks in [int(n) for n in args[3:]]:
        work = os.path.abspath(("distributed-np%d" if distributed else "np%d") % ranks)
        rc, tail = run(prm, exe, ranks, work, distributed)
        if not check(rc == 0, f"{ranks} ranks: exit {rc}\n{tail}"):
            continue
        d = compare(ref, read(work))
        mesh = "distributed mesh, " if distributed else ""
        print(f"{mesh}{ranks} ranks against {reference}: beta {d['beta']:.1e}, "
              f"K_secant {d['K_secant']:.1e}, K_tangent {d['K_tangent']:.1e}, "
              f"pin forces {d['pin_forces']:.1e} of the largest, "
              f"same active set {bool(d['same_active_set'])}")
        check(d["same_active_set"], f"{ranks} ranks: the active set differs")
        for key in ("beta", "K_secant", "K_tangent", "pin_forces"):
            check(d[key] <= TOL, f"{ranks} ranks: {key} differs by {d[key]:.2e} > {TOL}")
    return verdict()


if __name__ == "__main__":
    sys.exit(main())
