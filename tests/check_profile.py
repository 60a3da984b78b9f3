"""Check the output of `Run = profile` against an independent implementation
of the modified cycloid profile (doc/design-basis.md section 2.1), reading
profile.csv directly, profile.dxf with ezdxf and profile.step with the gmsh
(OpenCASCADE) Python API.

Usage: check_profile.py PRM NP1_DIR NP2_DIR EXECUTABLE [--coarse TOL]

With --coarse TOL the executable is run once more on PRM with
`Profile/Chord tolerance = TOL`; that output must pass the same checks, its
largest chord deviation must lie in [TOL/10, TOL] (the sampler uses the
tolerance rather than some fixed fine spacing) and it must have fewer
vertices.
"""
import argparse
import math
import os
import re
import sys
from pathlib import Path

import numpy as np

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import parameter_getter, parameter_values, run_cycloid  # noqa: E402

VERTEX_TOL = 1e-9  # mm: vertices are exact profile points
HOLE_TOL = 1e-8  # mm: holes as written (STEP keeps 13 digits)
FAILURES = []


def check(ok, message):
    """Record and print one check."""
    print(("ok:   " if ok else "FAIL: ") + message)
    if not ok:
        FAILURES.append(message)


class Profile:
    """The exact modified profile in the disc frame, from the textbook
    equations: x = (R - r/sqrt S) cos((1-iH)phi) - (e - K r/sqrt S) cos(iH phi),
    y = (R - r/sqrt S) sin((1-iH)phi) + (e - K r/sqrt S) sin(iH phi), with
    R = rp + Delta rp, r = rrp + Delta rrp, K = e zp / R,
    S = 1 + K^2 - 2 K cos phi, rp = e zp / K1, iH = zp/zc, the whole curve
    turned clockwise by the rotation modification delta."""

    def __init__(self, get):
        g = lambda key, default: float(get("Geometry", key, default))
        self.zp = int(get("Geometry", "Number of pins", "40"))
        self.zc = int(get("Geometry", "Number of cycloid teeth", "39"))
        self.e = g("Eccentricity", "2.2")
        k1 = g("Shortening coefficient", "0.675")
        self.rp = self.e * self.zp / k1
        self.big_r = self.rp + g("Pin circle radius modification", "0")
        self.r = g("Pin radius", "3") + g("Pin radius modification", "0")
        self.k = self.e * self.zp / self.big_r
        self.ih = self.zp / self.zc
        self.delta = math.radians(g("Rotation modification", "0"))
        self.period = 2 * math.pi * self.zc
        self.bore = g("Bore radius", "25")
        self.n_holes = int(get("Geometry", "Number of crank holes", "3"))
        self.hole_r = g("Crank hole radius", "15")
        self.hole_circle = g("Crank hole circle radius", "65")

    def __call__(self, phi):
        """Points (N, 2) at the parameters phi."""
        phi = np.asarray(phi, dtype=float)
        s = 1.0 / np.sqrt(1 + self.k ** 2 - 2 * self.k * np.cos(phi))
        a, g = (1 - self.ih) * phi, self.ih * phi
        x = (self.big_r - self.r * s) * np.cos(a) - (self.e - self.k * self.r * s) * np.cos(g)
        y = (self.big_r - self.r * s) * np.sin(a) + (self.e - self.k * self.r * s) * np.sin(g)
        c, d = math.cos(self.delta), math.sin(self.delta)
        return np.stack([c * x + d * y, -d * x + c * y], axis=-1)

    def closest(self, q):
        """Parameter and distance of the closest profile point to each of
        the points q (N, 2): sampling of a window of one and a half teeth around the
        polar angle of q, then golden-section refinement."""
        q = np.atleast_2d(q)
        phis, dists = [], []
        for chunk in np.array_split(q, max(1, len(q) // 2000)):
            phis_c, dists_c = self._closest_chunk(chunk)
            phis.append(phis_c)
            dists.append(dists_c)
        return np.concatenate(phis), np.concatenate(dists)

    def _closest_chunk(self, q):
        # The polar angle of P(phi) is near -phi/zc - delta.
        phi0 = -(np.arctan2(q[:, 1], q[:, 0]) + self.delta) * self.zc
        n, half = 97, 1.5 * math.pi
        offsets = np.linspace(-half, half, n)
        h = offsets[1] - offsets[0]
        cand = phi0[:, None] + offsets[None, :]
        d2 = np.sum((self(cand) - q[:, None, :]) ** 2, axis=-1)
        best = cand[np.arange(len(q)), np.argmin(d2, axis=1)]
        lo, hi = best - h, best + h
        f = lambda p: np.sum((self(p) - q) ** 2, axis=-1)
        ratio = (math.sqrt(5) - 1) / 2
        x1, x2 = hi - ratio * (hi - lo), lo + ratio * (hi - lo)
        f1, f2 = f(x1), f(x2)
        for _ in range(60):
            # Keep the side of the smaller value; one new evaluation each.
            left = f1 < f2
            hi, lo = np.where(left, x2, hi), np.where(left, lo, x1)
            x_new = np.where(left, hi - ratio * (hi - lo), lo + ratio * (hi - lo))
            f_new = f(x_new)
            x1, x2 = np.where(left, x_new, x2), np.where(left, x1, x_new)
            f1, f2 = np.where(left, f_new, f2), np.where(left, f1, f_new)
        phi = 0.5 * (lo + hi)
        return phi, np.sqrt(f(phi))

    def holes(self):
        """Expected holes (cx, cy, r): the bore, then crank hole k at angle
        2 pi k / n on the crank-hole circle (disc frame)."""
        out = [(0.0, 0.0, self.bore)]
        for k in range(self.n_holes):
            a = 2 * math.pi * k / self.n_holes
            out.append((self.hole_circle * math.cos(a), self.hole_circle * math.sin(a), self.hole_r))
        return out


def segment_distance(q, a, b):
    """Distance of the points q from the segments a-b (all (N, 2))."""
    ab = b - a
    t = np.clip(np.sum((q - a) * ab, axis=1) / np.sum(ab * ab, axis=1), 0, 1)
    return np.linalg.norm(q - (a + t[:, None] * ab), axis=1)


def signed_area(v):
    """Shoelace area of the closed polygon v (positive counter-clockwise)."""
    x, y = v[:, 0], v[:, 1]
    return 0.5 * np.sum(x * np.roll(y, -1) - np.roll(x, -1) * y)


def check_polyline(name, v, prof, tol):
    """Vertices on the curve, closed and counter-clockwise around it once,
    each chord within tol both ways; returns the largest chord deviation."""
    phi, dist = prof.closest(v)
    check(dist.max() <= VERTEX_TOL, f"{name}: {len(v)} vertices on the exact curve (max {dist.max():.2e} mm)")
    step = np.diff(np.append(phi, phi[0]))
    step = (step + prof.period / 2) % prof.period - prof.period / 2
    check(np.all(step < 0) and abs(step.sum() + prof.period) < 1e-6,
          f"{name}: one counter-clockwise turn of decreasing phi (sum {step.sum():.9f}, 2 pi zc = {prof.period:.9f})")
    check(signed_area(v) > 0, f"{name}: counter-clockwise (area {signed_area(v):.3f} mm^2)")
    a, b = v, np.roll(v, -1, axis=0)
    # Curve -> polyline: 32 exact points of each arc between two vertices
    # (the arcs cover the curve, see above) from its chord.
    s = np.linspace(0, 1, 34)[1:-1]
    arc = phi[:, None] + s[None, :] * step[:, None]
    pts = prof(arc)
    dev = segment_distance(pts.reshape(-1, 2), np.repeat(a, len(s), axis=0),
                           np.repeat(b, len(s), axis=0)).reshape(len(v), len(s)).max(axis=1)
    check(dev.max() <= tol, f"{name}: every exact arc within tol of its chord (max {dev.max():.4e} <= {tol:g} mm)")
    # Polyline -> curve: chord midpoints and quarter points.
    q = np.concatenate([a + w * (b - a) for w in (0.25, 0.5, 0.75)])
    _, dq = prof.closest(q)
    check(dq.max() <= tol, f"{name}: chord points within tol of the curve (max {dq.max():.4e} mm)")
    return dev.max()


def match_holes(name, found, prof):
    """The holes found (cx, cy, r) are the expected ones."""
    expected = prof.holes()
    ok = len(found) == len(expected)
    for c in expected:
        ok = ok and min(max(abs(c[0] - f[0]), abs(c[1] - f[1]), abs(c[2] - f[2])) for f in found) < HOLE_TOL
    check(ok, f"{name}: bore and {prof.n_holes} crank holes, radii and centres (found {len(found)})")


def check_csv(directory, prof, tol):
    """profile.csv: header, closed by repeating the first row."""
    path = os.path.join(directory, "profile.csv")
    header = open(path).readline().strip()
    check(header == "x_mm,y_mm", f"csv header '{header}'")
    v = np.loadtxt(path, delimiter=",", skiprows=1)
    check(np.array_equal(v[0], v[-1]), "csv: closed (last row repeats the first)")
    return v[:-1], check_polyline("csv", v[:-1], prof, tol)


def check_dxf(directory, prof, tol, csv_vertices):
    """profile.dxf through ezdxf: units, layers, closed polyline, circles."""
    import ezdxf

    doc = ezdxf.readfile(os.path.join(directory, "profile.dxf"))
    auditor = doc.audit()
    check(len(auditor.errors) == 0, f"dxf: ezdxf audit finds no error ({doc.dxfversion})")
    check(doc.header.get("$INSUNITS") == 4, "dxf: $INSUNITS = 4 (mm)")
    msp = doc.modelspace()
    polys = [e for e in msp if e.dxftype() in ("POLYLINE", "LWPOLYLINE")]
    check(len(polys) == 1 and polys[0].dxf.layer == "PROFILE" and polys[0].is_closed,
          "dxf: one closed polyline on layer PROFILE")
    p = polys[0]
    pts = [vx.dxf.location for vx in p.vertices] if p.dxftype() == "POLYLINE" else list(p.vertices())
    v = np.array([[q[0], q[1]] for q in pts])
    check(not np.array_equal(v[0], v[-1]), "dxf: closed by its flag, first vertex not repeated")
    # The same vertices as the csv, whose polyline is checked in full.
    check(v.shape == csv_vertices.shape and np.abs(v - csv_vertices).max() < 1e-12,
          f"dxf: the {len(v)} vertices of the csv")
    circles = [e for e in msp if e.dxftype() == "CIRCLE"]
    check(all(c.dxf.layer == "HOLES" for c in circles), "dxf: circles on layer HOLES")
    match_holes("dxf", [(c.dxf.center[0], c.dxf.center[1], c.dxf.radius) for c in circles], prof)


def circle_through(p):
    """Centre and radius of the circle through the three points p (3, 2)."""
    (ax, ay), (bx, by), (cx, cy) = p
    d = 2 * (ax * (by - cy) + bx * (cy - ay) + cx * (ay - by))
    ux = ((ax**2 + ay**2) * (by - cy) + (bx**2 + by**2) * (cy - ay) + (cx**2 + cy**2) * (ay - by)) / d
    uy = ((ax**2 + ay**2) * (cx - bx) + (bx**2 + by**2) * (ax - cx) + (cx**2 + cy**2) * (bx - ax)) / d
    return ux, uy, math.hypot(ax - ux, ay - uy)


def check_step(directory, prof, tol):
    """profile.step through gmsh/OpenCASCADE: one face, the profile curve
    within tol of the exact curve both ways, the holes as circles."""
    import gmsh

    path = os.path.join(directory, "profile.step")
    check(re.search(r"SI_UNIT\(\.MILLI\.,\.METRE\.\)", open(path).read()) is not None, "step: length unit mm")
    gmsh.initialize()
    gmsh.option.setNumber("General.Terminal", 0)
    try:
        gmsh.model.occ.importShapes(path)
        gmsh.model.occ.synchronize()
        faces = gmsh.model.getEntities(2)
        check(len(faces) == 1, f"step: one face (found {len(faces)})")
        curves = [t for _, t in gmsh.model.getEntities(1)]
        circles = [t for t in curves if gmsh.model.getType(1, t) == "Circle"]
        others = [t for t in curves if t not in circles]
        check(len(others) == 1, f"step: one profile curve besides the circles ({[gmsh.model.getType(1, t) for t in others]})")
        tag = others[0]
        lo, hi = gmsh.model.getParametrizationBounds(1, tag)
        t = np.linspace(lo[0], hi[0], 30001)
        xyz = np.array(gmsh.model.getValue(1, tag, t)).reshape(-1, 3)
        check(np.linalg.norm(xyz[0] - xyz[-1]) < 1e-9 and np.abs(xyz[:, 2]).max() < 1e-12,
              "step: the profile curve is closed, in z = 0")
        check(signed_area(xyz[:-1, :2]) > 0, "step: the profile curve runs counter-clockwise")
        phi, d = prof.closest(xyz[:, :2])
        check(d.max() <= tol, f"step: spline within tol of the exact curve (max {d.max():.4e} mm, 30001 points)")
        step = (np.diff(phi) + prof.period / 2) % prof.period - prof.period / 2
        check(np.all(step < 0) and abs(step.sum() + prof.period) < 1e-6,
              "step: the spline follows the exact curve once around, counter-clockwise")
        # The other way by OpenCASCADE's projection (slow on a long spline:
        # 3000 points, offset from the spline's own points).
        exact = prof((np.arange(3000) + 0.37) * prof.period / 3000)
        coords = np.column_stack([exact, np.zeros(len(exact))]).ravel()
        closest, _ = gmsh.model.getClosestPoint(1, tag, coords)
        dd = np.linalg.norm(np.array(closest).reshape(-1, 3)[:, :2] - exact, axis=1)
        check(dd.max() <= tol, f"step: exact curve within tol of the spline (max {dd.max():.4e} mm, 3000 points)")
        found = []
        for c in circles:
            (clo,), (chi,) = gmsh.model.getParametrizationBounds(1, c)
            p = np.array(gmsh.model.getValue(1, c, [clo, clo + (chi - clo) / 3, clo + 2 * (chi - clo) / 3])).reshape(-1, 3)
            found.append(circle_through(p[:, :2]))
        match_holes("step", found, prof)
    finally:
        gmsh.finalize()


def check_output(directory, prof, tol):
    """Every check of one output directory; returns (vertices, max chord
    deviation)."""
    print(f"--- {directory} (chord tolerance {tol:g} mm)")
    v, dev = check_csv(directory, prof, tol)
    check_dxf(directory, prof, tol, v)
    check_step(directory, prof, tol)
    return v, dev


def coarse_run(prm, exe, tol, prof):
    """Run the executable with Chord tolerance = tol; check its output."""
    text = open(prm).read()
    text = re.sub(r"set Output directory *=.*", "set Output directory = coarse", text)
    text += f"\nsubsection Profile\n  set Chord tolerance = {tol!r}\nend\n"
    with open("coarse.prm", "w") as f:
        f.write(text)
    out = run_cycloid(None, exe, "coarse.prm", check=True).stdout
    print(out)
    v, dev = check_output("coarse", prof, tol)
    m = re.search(r"max chord deviation ([0-9.eE+-]+) um", out)
    check(m is not None and abs(float(m.group(1)) * 1e-3 - dev) <= 0.02 * dev,
          "console: the reported max chord deviation is the measured one")
    return v, dev


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("prm")
    parser.add_argument("np1")
    parser.add_argument("np2")
    parser.add_argument("exe")
    parser.add_argument("--coarse", type=float)
    args = parser.parse_args()
    get = parameter_getter(parameter_values(args.prm, args.exe))
    prof = Profile(get)
    tol = float(get("Profile", "Chord tolerance", "1e-4"))
    v, dev = check_output(args.np1, prof, tol)
    for name in ("profile.csv", "profile.dxf"):
        same = open(os.path.join(args.np1, name)).read() == open(os.path.join(args.np2, name)).read()
        check(same, f"{name}: 1 and 2 ranks write the same file")
    if args.coarse:
        vc, devc = coarse_run(args.prm, args.exe, args.coarse, prof)
        check(args.coarse / 10 <= devc <= args.coarse,
              f"coarse: max chord deviation {devc:.3e} mm in [tol/10, tol] (the tolerance is used)")
        check(len(vc) < len(v) / 3, f"coarse: {len(vc)} vertices, fewer than {len(v)} at {tol:g} mm")
    if FAILURES:
        print(f"{len(FAILURES)} check(s) failed")
        sys.exit(1)
    print("all checks passed")


if __name__ == "__main__":
    main()
