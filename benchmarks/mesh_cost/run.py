#!/usr/bin/python3
"""Cell counts, quality and generation time of each FE scene at default
Mesh settings (seed case, crank angle 0), on 1 and 2 MPI ranks.

Scenes: 2D one disc + 40 pins; 3D one disc + pins; 3D two discs + pins +
housing (Pin support = housing). The time is the program's own "generated
in" (gmsh + deal.II triangulation + ids + manifolds), without writing the
VTU files. Writes doc/mesh-cost.csv.
Usage: benchmarks/mesh_cost/run.py [path/to/cycloid-contact]
"""
import os
import re
import sys
import tempfile
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import run_cycloid  # noqa: E402

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
EXE = sys.argv[1] if len(sys.argv) > 1 else os.path.join(ROOT, "build", "cycloid-contact")
SCENES = {
    "2D, one disc, pins": "set Dimension = 2\n  set Number of discs = 1",
    "3D, one disc, pins": "set Dimension = 3\n  set Number of discs = 1",
    "3D, two discs, pins, housing": "set Dimension = 3\n  set Number of discs = 2\n  set Pin support = housing",
}


def run(scene, ranks, tmp):
    prm = os.path.join(tmp, "mesh.prm")
    with open(prm, "w") as f:
        f.write(f"set Run = mesh\nset Output directory = {tmp}/out\nsubsection Scene\n  {scene}\nend\n")
    out = run_cycloid(ranks, EXE, prm, check=True).stdout
    cells = re.search(r"cells: (\d+) \(discs (\d+), pins (\d+), housing (\d+)\), vertices (\d+)", out)
    quality = re.search(r"min scaled Jacobian ([0-9.e+-]+).*max aspect ratio ([0-9.e+-]+)", out)
    seconds = float(re.search(r"generated in ([0-9.e+-]+) s", out).group(1))
    return [int(x) for x in cells.groups()], [float(x) for x in quality.groups()], seconds


def main():
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for name, scene in SCENES.items():
            for ranks in (1, 2):
                (total, discs, pins, housing, vertices), (jac, aspect), sec = run(scene, ranks, tmp)
                rows.append(f"{name},{ranks},{total},{discs},{pins},{housing},{vertices},{jac:.4f},{aspect:.2f},{sec:.2f}")
                print(f"{name:30s} ranks {ranks}: {total:7d} cells (discs {discs}, pins {pins}, housing {housing}), "
                      f"min scaled Jacobian {jac:.3f}, max aspect {aspect:.1f}, {sec:.2f} s")
    path = os.path.join(ROOT, "doc", "mesh-cost.csv")
    with open(path, "w") as f:
        f.write("scene,ranks,cells,disc_cells,pin_cells,housing_cells,vertices,min_scaled_jacobian,max_aspect_ratio,seconds\n")
        f.write("\n".join(rows) + "\n")
    print("written", path)


if __name__ == "__main__":
    main()
