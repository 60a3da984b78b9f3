#!/usr/bin/python3
"""Independent check of an `analytic` run's stiffness.csv and pin_forces.csv.

Re-implements from the documented formulas (doc/design-basis.md,
doc/theory.md; not from the C++ sources) the profile in its x/y form, the
kinematic assembly, a brute-force closest-point search, the curvature by
finite differences, the disc depth and the pair models, and checks the
program's output through the guaranteed column names (doc/design-basis.md,
section 5.3):

  * clearance, arm and force direction of every pin;
  * torque balance sum(Fn * arm) = T and the pins in contact;
  * the load distribution: Fn > 0 exactly where beta * arm > clearance, and
    the pair model's force at the written approach;
  * K_tangent = sum(k l^2) and K_secant = T / beta;
  * periodicity between the first and last phase of a closed period (when
    the load introduction is axisymmetric);
  * the Hertz pressure p0 = 2F/(pi a b) and the subsurface shear stress of
    every loaded pin, the transmission error (beta in arcsec) and its
    peak-to-peak over a sweep;
  * for a catalogue torque cycle: the torques in cycle order, zero-torque
    states at the rigid take-up of their side, and rigidity.csv recomputed
    from torsion_curve.csv (rigidity b/a between 50 and 100 % of the rated
    torque, lost motion at +-3 %, backlash = the two take-ups).

Usage: check_analytic_output.py FILE.prm OUTPUT_DIR
"""
import csv
import math
import sys
from pathlib import Path

import numpy as np

from catalogue_figures import ARCMIN, ARCSEC, catalogue
from checker import check, rows as read_csv, verdict

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import parameter_getter, parameter_values  # noqa: E402

# The seed's sizes for the entries the program derives (`auto`), as this
# independent check assumes them.
AUTO = {
    ("Geometry", "Number of cycloid teeth"): "39",
    ("Geometry", "Bore radius"): "25",
    ("Geometry", "Crank hole radius"): "15",
    ("Geometry", "Crank hole circle radius"): "65",
    ("Scene", "Number of discs"): "2",
}


def torque_cycle(get):
    """The catalogue cycle's torques as doc/user-guide.md describes them
    (empty if the run has none): 0 -> +R -> 0 -> -R -> 0 in steps/4 equal
    steps per branch, plus 3 % and 50 % of R; the middle zero twice."""
    if get("Loading", "Torque cycle") != "true":
        return []
    rated, steps = float(get("Loading", "Rated torque")), int(get("Loading", "Torque cycle steps"))
    q = steps // 4
    branch = sorted(set([0.0, 0.03, 0.5] + [i / q for i in range(1, q + 1)]))
    loads = []
    for sign in (1, -1):
        loads += [sign * f * rated for f in branch] + [sign * f * rated for f in branch[-2::-1]]
    return loads


def hertz_shear(nu):
    """(tau_max / p0, depth / a) of the line contact: the largest Tresca
    stress on the axis of the closed-form plane-strain Hertz field."""
    def tresca(t):
        root = np.sqrt(1 + t * t)
        sx, sz = -((1 + 2 * t * t) / root - 2 * t), -1 / root
        principal = np.stack([sx, nu * (sx + sz), sz])
        return (principal.max(axis=0) - principal.min(axis=0)) / 2
    t = np.linspace(0, 3, 30001)
    centre = t[int(np.argmax(tresca(t)))]
    t = np.linspace(max(centre - 2e-4, 0), centre + 2e-4, 400001)  # zoom in
    tau = tresca(t)
    i = int(np.argmax(tau))
    return tau[i], t[i]


def check_torque_cycle(outdir, stiffness, cycle, takeup, rated):
    """torsion_curve.csv is the states in cycle order; rigidity.csv holds the
    figures recomputed from it; the backlash is the two take-ups."""
    curve = read_csv(f"{outdir}/torsion_curve.csv")
    figures = read_csv(f"{outdir}/rigidity.csv")
    check(len(curve) == len(stiffness), "torsion_curve.csv: one row per state")
    for c, s in zip(curve, stiffness):
        check(c["torque_Nm"] == s["torque_Nm"] and c["rotation_rad"] == s["rotation_rad"], "torsion curve != states")
        check(abs(float(c["rotation_arcmin"]) - float(c["rotation_rad"]) * ARCMIN) <= 1e-9, "rotation_arcmin")
    cranks = sorted(set(c["crank_deg"] for c in curve), key=float)
    check(len(figures) == len(cranks), "rigidity.csv: one row per crank angle")
    for row, crank in zip(figures, cranks):
        one = [(float(c["torque_Nm"]), float(c["rotation_rad"])) for c in curve if c["crank_deg"] == crank]
        check(len(one) == len(cycle) and all(abs(T - c) <= 1e-9 * rated for (T, _), c in zip(one, cycle)),
              f"crank {crank}: the torques are not the catalogue cycle")
        rigidity, lost, backlash = catalogue(one, rated, check)
        # No friction: the loading and unloading branches are one curve.
        key = round(math.radians(float(crank)), 12)
        for T, th in one:
            same = [u for U, u in one if U == T]
            tk = takeup[(key, 1 if T >= 0 else -1)]
            check(T == 0 or all(abs(u - th) <= 1e-9 * abs(th - math.copysign(tk, T)) + 1e-15 for u in same),
                  f"crank {crank}, T = {T}: the branches differ")
        independent = (takeup[(key, 1)] + takeup[(key, -1)]) * ARCMIN
        print(f"crank {crank} deg: rigidity {rigidity:.6g} N m/arcmin, lost motion {lost:.6g}, "
              f"backlash {backlash:.6g} arcmin (independent take-ups {independent:.6g})")
        for name, value in (("torsional_rigidity_Nm_per_arcmin", rigidity), ("lost_motion_arcmin", lost),
                            ("backlash_arcmin", backlash), ("rated_torque_Nm", rated)):
            check(abs(float(row[name]) - value) <= 1e-9 * max(abs(value), 1e-9), f"rigidity.csv {name}")
        check(abs(backlash - independent) <= 1e-7 * max(independent, 1e-3), "backlash is not the two take-ups")
        check(abs(float(row["lost_motion_clearance_arcmin"]) - independent) <= 1e-7 * max(independent, 1e-3),
              "the clearance part of the lost motion is not the take-ups")


def check_fluctuation(outdir, stiffness):
    """fluctuation.csv's transmission error: mean and peak-to-peak of beta
    over the crank angles (a torque met twice at one crank angle, as in a
    torque cycle, counts once: its first state)."""
    for row in read_csv(f"{outdir}/fluctuation.csv"):
        first = {}
        for s in stiffness:
            if s["torque_Nm"] == row["torque_Nm"]:
                first.setdefault(s["crank_deg"], float(s["rotation_rad"]) * ARCSEC)
        te = list(first.values())
        check(abs(float(row["transmission_error_pp_arcsec"]) - (max(te) - min(te))) <= 1e-9 * max(abs(x) for x in te) + 1e-12,
              "fluctuation.csv: transmission error peak-to-peak")
        check(abs(float(row["transmission_error_mean_arcsec"]) - sum(te) / len(te)) <= 1e-9 * abs(sum(te) / len(te)),
              "fluctuation.csv: transmission error mean")
        check(row["K_tangent_noise_floor"] == "0" and row["K_tangent_fluctuation_resolved"] == "1",
              "fluctuation.csv: the analytic model has no mesh noise")


def main(prm_path, outdir):
    get = parameter_getter(parameter_values(outdir), AUTO)
    zp = int(get("Geometry", "Number of pins"))
    zc = int(get("Geometry", "Number of cycloid teeth"))
    rrp = float(get("Geometry", "Pin radius"))
    e = float(get("Geometry", "Eccentricity"))
    k1 = float(get("Geometry", "Shortening coefficient"))
    b = float(get("Geometry", "Tooth width"))
    d_rp = float(get("Geometry", "Pin circle radius modification"))
    d_rrp = float(get("Geometry", "Pin radius modification"))
    delta = math.radians(float(get("Geometry", "Rotation modification")))
    n_discs = int(get("Scene", "Number of discs"))
    rp = e * zp / k1
    R, r = rp + d_rp, rrp + d_rrp
    K = e * zp / R
    ih = zp / zc

    def profile(phi):
        s = 1 + K * K - 2 * K * np.cos(phi)
        w = 1 / np.sqrt(s)
        x = (R - r * w) * np.cos((1 - ih) * phi) - (e - K * r * w) * np.cos(ih * phi)
        y = (R - r * w) * np.sin((1 - ih) * phi) + (e - K * r * w) * np.sin(ih * phi)
        c, sn = math.cos(-delta), math.sin(-delta)
        return c * x - sn * y, sn * x + c * y

    # Dense samples of the closed profile.
    n = zc * 2000
    grid = np.arange(n) * (2 * math.pi * zc / n)
    gx, gy = profile(grid)
    h = grid[1] - grid[0]

    def d_profile(phi):
        """dP/dphi by the complex-step method (exact to round-off)."""
        hc = 1e-30
        x, y = profile(phi + 1j * hc)
        return np.array([np.imag(x) / hc, np.imag(y) / hc])

    def closest(q):
        """Brute force over the dense samples, then Newton on (P-q).P' = 0."""
        d2 = (gx - q[0]) ** 2 + (gy - q[1]) ** 2
        phi = grid[int(np.argmin(d2))]
        for _ in range(30):
            p = np.array(profile(phi))
            t = d_profile(phi)
            eps = 1e-5
            tt = (d_profile(phi + eps) - d_profile(phi - eps)) / (2 * eps)
            step = np.dot(p - q, t) / (np.dot(t, t) + np.dot(p - q, tt))
            phi -= step
            if abs(step) < 1e-15 * max(1.0, abs(phi)):
                break
        return phi

    def local(phi):
        """Point, outward normal, signed curvature radius (concave > 0)."""
        p = np.array(profile(phi))
        t = d_profile(phi)
        eps = 1e-5
        tt = (d_profile(phi + eps) - d_profile(phi - eps)) / (2 * eps)
        normal = np.array([-t[1], t[0]]) / np.linalg.norm(t)
        kappa = (t[0] * tt[1] - t[1] * tt[0]) / np.linalg.norm(t) ** 3
        return p, normal, 1 / kappa

    holes = []
    if get("Scene", "Load introduction") == "crank holes":
        nh = int(get("Geometry", "Number of crank holes"))
        rc = float(get("Geometry", "Crank hole circle radius"))
        holes = [(rc * math.cos(2 * math.pi * k / nh), rc * math.sin(2 * math.pi * k / nh)) for k in range(nh)]
    rh = float(get("Geometry", "Crank hole radius"))
    bore = float(get("Geometry", "Bore radius"))

    def depth(p):
        if holes:
            return min(math.hypot(p[0] - hx, p[1] - hy) - rh for hx, hy in holes)
        return math.hypot(*p) - bore

    ed, nd = float(get("Material", "Disc Young's modulus")), float(get("Material", "Disc Poisson's ratio"))
    ep, np_ = float(get("Material", "Pin Young's modulus")), float(get("Material", "Pin Poisson's ratio"))
    c_d = (1 - nd**2) / ed
    c_p = 0.0 if get("Scene", "Pins") == "rigid" else (1 - np_**2) / ep
    model = get("Analytic", "Pair stiffness model")
    lam = float(get("Analytic", "Load sharing coefficient"))

    def pair(force, rho, L):
        """(approach, compliance d approach/dF) of the pair at force F."""
        inv_rstar = 1 / rrp - 1 / rho
        if model == "seed":
            a = 1 / inv_rstar
            cmp = 4 * a / (math.pi * b) * (c_p / rrp + c_d * abs(1 / rho)) / lam
            return force * cmp, cmp
        a = math.sqrt(4 * force * (c_p + c_d) / (math.pi * b * inv_rstar))
        app = 2 * force / (math.pi * b) * (c_p * (math.log(4 * rrp / a) - 0.5) + c_d * (math.log(4 * L / a) - 0.5))
        cmp = 2 / (math.pi * b) * (c_p * (math.log(4 * rrp / a) - 1) + c_d * (math.log(4 * L / a) - 1))
        return app, cmp

    stiffness = read_csv(f"{outdir}/stiffness.csv")
    pins = read_csv(f"{outdir}/pin_forces.csv")
    n_phases = int(get("Loading", "Number of phases"))
    cycle = torque_cycle(get)
    n_torques = len(cycle) if cycle else len(get("Loading", "Torque").split(","))
    shear_ratio, depth_ratio = hertz_shear(nd)
    check(len(stiffness) == n_phases * n_torques, f"{len(stiffness)} states, expected {n_phases * n_torques}")
    check(len(pins) == len(stiffness) * n_discs * zp, "pin_forces.csv row count")

    by_step = {}
    for row in pins:
        by_step.setdefault(int(row["step"]), []).append(row)

    geometry_cache = {}
    takeup = {}  # (crank, side) -> rigid take-up rotation [rad]
    worst = {"clearance_um": 0, "arm_mm": 0, "torque": 0, "approach": 0, "K": 0, "stress": 0}
    for state in stiffness:
        step = int(state["step"])
        psi = math.radians(float(state["crank_deg"]))
        torque = float(state["torque_Nm"])
        beta = float(state["rotation_rad"])
        rows = by_step[step]
        total, k_tan, engaged = 0.0, 0.0, 0
        for row in rows:
            d, j = int(row["disc"]), int(row["pin"])
            key = (round(psi, 12), d, j)
            if key not in geometry_cache:
                psi_d = psi + d * math.pi
                centre = np.array([e * math.cos(psi_d), e * math.sin(psi_d)])
                pin = rp * np.array([math.cos(2 * math.pi * j / zp), math.sin(2 * math.pi * j / zp)])
                rot = psi_d / zc
                v = pin - centre
                q = np.array([math.cos(rot) * v[0] - math.sin(rot) * v[1], math.sin(rot) * v[0] + math.cos(rot) * v[1]])
                p, normal, rho = local(closest(q))
                gap = float(np.dot(q - p, normal)) - rrp
                arm = float(p[0] * normal[1] - p[1] * normal[0])
                # normal in the housing frame
                c, s = math.cos(-rot), math.sin(-rot)
                nh = np.array([c * normal[0] - s * normal[1], s * normal[0] + c * normal[1]])
                geometry_cache[key] = (gap, arm, nh, rho, depth(p))
            gap, arm, nh, rho, L = geometry_cache[key]
            for side in (1, -1):
                if side * arm > 1e-9:
                    t = max(gap, 0) / (side * arm)
                    takeup[(key[0], side)] = min(takeup.get((key[0], side), 1e300), t)
            clearance = float(row["clearance_um"]) * 1e-3
            worst["clearance_um"] = max(worst["clearance_um"], abs(clearance - gap) * 1e3)
            worst["arm_mm"] = max(worst["arm_mm"], abs(float(row["arm_mm"]) - arm))
            fn, fx, fy = float(row["Fn_N"]), float(row["Fx_N"]), float(row["Fy_N"])
            check(abs(fx + fn * nh[0]) <= 1e-6 * max(fn, 1) and abs(fy + fn * nh[1]) <= 1e-6 * max(fn, 1),
                  f"step {step} disc {d} pin {j}: force direction")
            approach = beta * arm - max(gap, 0)
            if fn > 0:
                engaged += 1
                check(approach > -1e-12, f"step {step} disc {d} pin {j}: force without approach")
                app, cmp = pair(fn, rho, L)
                worst["approach"] = max(worst["approach"], abs(app - approach) / max(approach, 1e-9))
                k_tan += arm * arm / cmp
                # Hertz stresses from the independent half-width.
                a = math.sqrt(4 * fn * (c_p + c_d) / (math.pi * b * (1 / rrp - 1 / rho)))
                p0 = 2 * fn / (math.pi * a * b)
                for column, value in (("hertz_pressure_MPa", p0), ("max_contact_pressure_MPa", p0),
                                      ("max_shear_stress_MPa", shear_ratio * p0),
                                      ("max_shear_depth_um", depth_ratio * a * 1e3)):
                    worst["stress"] = max(worst["stress"], abs(float(row[column]) - value) / value)
            else:
                check(approach < 1e-9, f"step {step} disc {d} pin {j}: approach {approach} without force")
            total += fn * arm * 1e-3
        check(abs(float(state["transmission_error_arcsec"]) - beta * ARCSEC) <= 1e-9 * abs(beta * ARCSEC) + 1e-12,
              f"step {step}: transmission error is not beta in arcsec")
        if torque == 0:
            # A torque cycle's zero: the branch's limit, the rigid take-up.
            check(engaged == 0 and cycle, f"step {step}: a zero-torque state with force, or outside a cycle")
            # The side from the place in the cycle: the branch the zero
            # ends (the torque before it), or for a branch's first zero
            # the branch it starts.
            i = step % len(cycle)
            before = cycle[i - 1] if i > 0 else 0
            side = math.copysign(1, before if before != 0 else cycle[i + 1])
            t = takeup[(round(psi, 12), side)]
            check(abs(beta - side * t) <= 1e-9 * t + 1e-12, f"step {step}: zero-torque rotation {beta} is not the take-up {side * t}")
            continue
        worst["torque"] = max(worst["torque"], abs(total - torque) / abs(torque))
        check(engaged == int(state["pins_in_contact"]), f"step {step}: pins_in_contact")
        k_tan *= 1e-3
        worst["K"] = max(worst["K"], abs(k_tan - float(state["K_tangent_Nm_per_rad"])) / k_tan)
        check(abs(float(state["K_secant_Nm_per_rad"]) - torque / beta) <= 1e-9 * abs(torque / beta), f"step {step}: K_secant")

    print("largest deviations from the independent computation:", {k: f"{v:.3g}" for k, v in worst.items()})
    check(worst["clearance_um"] < 1e-6, "clearance differs by more than 1e-6 um")
    check(worst["arm_mm"] < 1e-7, "arm differs by more than 1e-7 mm")
    check(worst["torque"] < 1e-10, "torque balance worse than 1e-10")
    check(worst["approach"] < 1e-6, "pair model force/approach differs by more than 1e-6")
    check(worst["K"] < 1e-7, "K_tangent differs from sum k l^2 by more than 1e-7")
    check(worst["stress"] < 1e-6, "Hertz pressure or subsurface shear differs by more than 1e-6")
    if cycle:
        check_torque_cycle(outdir, stiffness, cycle, takeup, float(get("Loading", "Rated torque")))

    axisymmetric = get("Scene", "Load introduction") == "bore" or int(get("Geometry", "Number of crank holes")) == 0
    if n_phases > 1:
        check_fluctuation(outdir, stiffness)
        first, last = stiffness[:n_torques], stiffness[-n_torques:]
        period = float(last[0]["crank_deg"]) - float(first[0]["crank_deg"])
        check(abs(period - 360 / zp) < 1e-9, f"sweep spans {period} deg, not one period 360/zp")
        if axisymmetric:
            for a, z in zip(first, last):
                ka, kz = float(a["K_tangent_Nm_per_rad"]), float(z["K_tangent_Nm_per_rad"])
                check(abs(ka - kz) <= 1e-9 * ka, f"periodicity of K: {ka} vs {kz}")
                fa = {(int(r["disc"]), int(r["pin"])): float(r["Fn_N"]) for r in by_step[int(a["step"])]}
                fz = {(int(r["disc"]), int(r["pin"])): float(r["Fn_N"]) for r in by_step[int(z["step"])]}
                for (d, j), f in fz.items():
                    check(abs(f - fa[(d, (j - 1) % zp)]) <= 1e-8 * max(f, 1), f"periodicity of pin {j} force")
    return verdict(f"all checks passed ({len(stiffness)} states, {len(pins)} pin rows)")


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], sys.argv[2]))
