#!/usr/bin/python3
"""Independent check of `Run = mesh` output with VTK's own reader.

Usage: check_mesh_output.py FILE.prm DIR_1_RANK DIR_2_RANKS [EXECUTABLE]

* the per-body statistics (mesh.csv) are identical on 1 and 2 ranks;
* both PVTU files read, and hold the same global mesh (cells, per-body
  sorted centroids) on 1 and 2 ranks; the 2-rank mesh is split over both;
* body ids complete: the discs, every pin, the housing when modelled;
* boundary ids complete: every boundary face identified, every kind the
  scene has is present;
* disc cross-section area (shoelace over the cells) within 1e-3 of the
  exact area of the profile minus bore and crank holes (computed here from
  the x/y profile formula of doc/design-basis.md).
"""
import math
import sys
from pathlib import Path

import numpy as np
import vtk
from vtk.util.numpy_support import vtk_to_numpy

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import parameter_getter, parameter_values  # noqa: E402

failures = []


def check(cond, msg):
    if not cond:
        failures.append(msg)


def read(path):
    r = vtk.vtkXMLPUnstructuredGridReader()
    r.SetFileName(path)
    r.Update()
    g = r.GetOutput()
    pts = vtk_to_numpy(g.GetPoints().GetData())
    offsets = vtk_to_numpy(g.GetCells().GetOffsetsArray())
    conn = vtk_to_numpy(g.GetCells().GetConnectivityArray())
    n = offsets[1] - offsets[0]
    cells = conn.reshape(-1, n)
    data = {g.GetCellData().GetArrayName(i): vtk_to_numpy(g.GetCellData().GetArray(i))
            for i in range(g.GetCellData().GetNumberOfArrays())}
    return pts, cells, data


def exact_disc_area():
    zp, zc, rrp, e, k1 = 40, 39, 3.0, 2.2, 0.675
    rp = e * zp / k1
    ih = zp / zc
    phi = np.linspace(0, 2 * math.pi * zc, 400000, endpoint=False)
    s = 1 + k1 * k1 - 2 * k1 * np.cos(phi)
    w = 1 / np.sqrt(s)
    x = (rp - rrp * w) * np.cos((1 - ih) * phi) - (e - k1 * rrp * w) * np.cos(ih * phi)
    y = (rp - rrp * w) * np.sin((1 - ih) * phi) + (e - k1 * rrp * w) * np.sin(ih * phi)
    area = 0.5 * abs(np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y))
    return area - math.pi * 25**2 - 3 * math.pi * 15**2


def main(prm, dir1, dir2, exe=None):
    get = parameter_getter(parameter_values(dir1))
    dim = int(get("Scene", "Dimension", "2"))
    discs = get("Scene", "Number of discs", "auto")
    n_discs = (1 if dim == 2 else 2) if discs == "auto" else int(discs)
    housing = get("Scene", "Pin support", "axis") == "housing"
    check(open(f"{dir1}/mesh.csv").read() == open(f"{dir2}/mesh.csv").read(),
          "mesh.csv differs between 1 and 2 ranks")
    meshes = []
    for d in (dir1, dir2):
        pts, cells, data = read(f"{d}/mesh.pvtu")
        bpts, bcells, bdata = read(f"{d}/mesh_boundary.pvtu")
        meshes.append((pts, cells, data, bpts, bcells, bdata))

    # Same global mesh on 1 and 2 ranks.
    keys = []
    for pts, cells, data, *_ in meshes:
        centroids = pts[cells].mean(axis=1)
        order = np.lexsort((centroids[:, 2], centroids[:, 1], centroids[:, 0], data["body_id"]))
        keys.append((data["body_id"][order], np.round(centroids[order], 9)))
    check(len(keys[0][0]) == len(keys[1][0]), f"cell counts differ: {len(keys[0][0])} vs {len(keys[1][0])}")
    if len(keys[0][0]) == len(keys[1][0]):
        check(np.array_equal(keys[0][0], keys[1][0]), "body ids differ between 1 and 2 ranks")
        check(np.allclose(keys[0][1], keys[1][1], atol=1e-9), "cell centroids differ between 1 and 2 ranks")
    check(set(meshes[0][2]["mpi_rank"]) == {0}, "1-rank run: ranks other than 0")
    ranks, counts = np.unique(meshes[1][2]["mpi_rank"], return_counts=True)
    check(list(ranks) == [0, 1], "2-rank run: cells not on both ranks")
    print("cells per rank (2 ranks):", dict(zip(ranks.tolist(), counts.tolist())))

    pts, cells, data, bpts, bcells, bdata = meshes[1]
    bodies = set(data["body_id"].tolist())
    expected = set(range(n_discs)) | {100 + j for j in range(40)} | ({9} if housing else set())
    check(bodies == expected, f"body ids {sorted(bodies)} != expected {sorted(expected)}")
    kinds = set(bdata["boundary_id"].tolist())
    expected_kinds = {1, 2, 3, 4} | ({5, 6, 7} if housing else set())
    if dim == 3:
        expected_kinds |= {8, 9} | ({10} if housing else set())
    check(0 not in kinds, "boundary faces without id")
    check(kinds == expected_kinds, f"boundary ids {sorted(kinds)} != expected {sorted(expected_kinds)}")
    for j in range(40):
        check(np.any((bdata["boundary_id"] == 4) & (bdata["body_id"] == 100 + j)), f"pin {j} has no pin-surface faces")

    if dim == 2:
        p = pts[cells][:, :, :2]
        areas = 0.5 * np.abs(np.sum(p[:, :, 0] * np.roll(p[:, :, 1], -1, axis=1)
                                    - np.roll(p[:, :, 0], -1, axis=1) * p[:, :, 1], axis=1))
        exact = exact_disc_area()
        a = areas[data["body_id"] == 0].sum()
        print(f"disc area {a:.6f} mm^2, exact {exact:.6f}, relative error {abs(a - exact) / exact:.2e}")
        check(abs(a - exact) / exact < 1e-3, "disc area differs by more than 1e-3")

    if failures:
        print(f"{len(failures)} check(s) failed:")
        for f in failures:
            print("  ", f)
        return 1
    print(f"all checks passed ({len(keys[0][0])} cells, bodies {len(bodies)}, boundary kinds {sorted(kinds)})")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:5]))
