#!/usr/bin/python3
"""Draw what a cycloid-contact output directory holds, as PNG files.

Usage: plot.py OUTPUT_DIR

Reads the CSV files a run wrote (and its parameters.prm, if present) and
writes into OUTPUT_DIR/plots/, each figure only when its data exist:

* pin_forces_polar.png   Fn per pin around the pin circle (polar) and
                         against the pin number, every disc, for one
                         representative state (pin_forces.csv);
* stiffness_vs_crank.png K_tangent and K_secant [N·m/arcmin] against the
                         crank angle, one curve per torque (>= 2 angles);
* stiffness_vs_torque.png the same against the torque, one curve per crank
                         angle (>= 2 torques; stiffness.csv);
* torsion_curve.png      the torque-cycle curve with the +-3 % rated points,
                         lost motion, backlash and the rigidity slope
                         (torsion_curve.csv, rigidity.csv);
* transmission_error.png the output rotation's deviation from the kinematic
                         one [arcsec] against the crank angle per torque,
                         peak-to-peak in the legend (against time for a
                         transient);
* contact_pressure.png   peak contact pressure per pin (FE and Hertz p0)
                         and the largest shear stress, if pin_forces.csv
                         has those columns;
* energy.png             the energy terms of a transient and its balance
                         error (energy.csv);
* tolerance_distributions.png  a tolerance study's CDFs of K_secant, the
                         load sharing λ (with the seed's 0.7), the peak pin
                         force and the rotation, one curve per torque, the
                         nominal stage marked (samples.csv);
* pin_force_spread.png   a tolerance study's spread of each pin's force: a
                         box per pin (P5-P95, median, min-max whiskers) and
                         the nominal stage's force (pin_force_summary.csv);
* compliance_breakdown.png  each loaded state's rotation stacked from its
                         parts: pin contacts, elastic bodies, crank
                         bearings (compliance_breakdown.csv), the bearings'
                         share in the legend.

It also writes plots/index.json: per figure its file, title, and per panel
the title, axis labels and the curves drawn (label, number of points), read
back from the drawn figure, so that tests and scripts can check what was
drawn without looking at pixels. It prints the paths of the PNGs written.
"""
import json
import math
import os
import sys
import textwrap

import matplotlib

matplotlib.use("Agg")  # no display: files only
import matplotlib.pyplot as plt  # noqa: E402
import numpy as np  # noqa: E402

from cycloid_tools import parameter_values, read_csv  # noqa: E402

ARCSEC_PER_RAD = 180.0 * 3600.0 / math.pi
ARCMIN_PER_RAD = 180.0 * 60.0 / math.pi
KNOWN_FILES = ("stiffness.csv", "pin_forces.csv", "fluctuation.csv",
               "energy.csv", "torsion_curve.csv", "rigidity.csv", "samples.csv",
               "compliance_breakdown.csv")
DISC_STYLE = [dict(color="tab:blue", marker="o"),
              dict(color="tab:orange", marker="s"),
              dict(color="tab:green", marker="^")]

plt.rcParams.update({
    # An offset ("+4.2e1" above the axis) is unreadable for values such as
    # a transmission error of 41.90-41.95 arcsec: always print full values.
    "axes.formatter.useoffset": False,
    "axes.grid": True,
    "grid.alpha": 0.3,
    "font.size": 9,
    "legend.fontsize": 8,
    "figure.dpi": 100,
})


# --- reading ---------------------------------------------------------------

def read_columns(path):
    """Columns of a one-header-line CSV file as float arrays (nan kept);
    None if the file is absent or has no row."""
    rows = read_csv(path, numbers=(float,), missing_ok=True)
    if not rows:
        return None
    return {name.strip(): np.array([r[name] for r in rows], dtype=float) for name in rows[0]}


def _one_state_per_load(s):
    """The rows of stiffness columns @p s with a non-zero torque, the first
    of each (crank angle, torque)."""
    seen, keep = set(), []
    for i, (c, t) in enumerate(zip(s["crank_deg"], s["torque_Nm"])):
        if t != 0 and (c, t) not in seen:
            seen.add((c, t))
            keep.append(i)
    return {name: column[keep] for name, column in s.items()}


def distinct(values, digits=9):
    """Sorted distinct values, equal to `digits` significant digits."""
    return sorted({float(f"{v:.{digits}g}") for v in values})


def same(a, b, digits=9):
    return float(f"{a:.{digits}g}") == float(f"{b:.{digits}g}")


def fmt(v, digits=4):
    """A number for a label: 4 significant digits, no exponent for 1e-3..1e6."""
    if v == 0 or 1e-3 <= abs(v) < 1e6:
        return f"{v:.{digits}g}" if abs(v) < 10 ** digits else f"{v:.0f}"
    return f"{v:.{digits - 1}e}"


def _number(text):
    """A prm value for a title: ParameterHandler may print 0.3 as
    0.29999999999999999, so numbers are shown with fmt()."""
    try:
        return fmt(float(text))
    except ValueError:
        return text


class Run:
    """The files of one output directory and what the figures share: the
    load groups (torques, or rotations under rotation control), the crank
    angles, the representative state and the title line of key parameters."""

    def __init__(self, directory):
        self.dir = directory
        # As deal.II read them (parameters.json, which every run writes);
        # an output directory without it gives the plots without the title
        # line's parameters.
        prm = os.path.join(directory, "parameters.json")
        self.prm = parameter_values(prm) if os.path.isfile(prm) else {}
        self.stiffness = read_columns(os.path.join(directory, "stiffness.csv"))
        self.pins = read_columns(os.path.join(directory, "pin_forces.csv"))
        self.fluctuation = read_columns(os.path.join(directory, "fluctuation.csv"))
        self.energy = read_columns(os.path.join(directory, "energy.csv"))
        self.torsion = read_columns(os.path.join(directory, "torsion_curve.csv"))
        self.rigidity = read_columns(os.path.join(directory, "rigidity.csv"))
        # A tolerance study: every sample's states, and each pin's spread.
        self.samples = read_columns(os.path.join(directory, "samples.csv"))
        self.pin_spread = read_columns(os.path.join(directory, "pin_force_summary.csv"))
        self.breakdown = read_columns(os.path.join(directory, "compliance_breakdown.csv"))
        self.transient = self.energy is not None or self.prm.get("Run") == "transient"
        self.by_rotation = self._rotation_control()
        # A torque cycle passes each torque twice at a crank angle (loading
        # and unloading, the same state without friction) and its zero
        # torque as the two ends of the clearance, where K is undefined:
        # the stiffness and TE figures show each torque once.
        self.cycle = self.torsion is not None
        if self.cycle and self.stiffness is not None:
            self.stiffness = _one_state_per_load(self.stiffness)

    def _rotation_control(self):
        """Under rotation control the torque varies with the crank angle and
        the prescribed rotation is what the states share."""
        control = self.prm.get("Loading/Control")
        if control:
            return control.strip().lower() == "rotation"
        return self.fluctuation is not None and "rotation_rad" in self.fluctuation

    # Load groups: the prescribed torque (or rotation) of each state.
    def load_values(self):
        s = self.stiffness
        return s["rotation_rad"] if self.by_rotation else s["torque_Nm"]

    def load_label(self, value):
        if self.by_rotation:
            return f"β = {fmt(math.degrees(value))}°"
        return f"T = {fmt(value)} N·m"

    def loads(self):
        return distinct(self.load_values())

    def cranks(self):
        return distinct(self.stiffness["crank_deg"])

    def representative_step(self):
        """The state the per-pin figures show: the last step of a transient
        (full load), else the largest load at the first crank angle."""
        s = self.stiffness
        if s is None:
            return int(self.pins["step"][-1])
        if self.transient:
            return int(s["step"][-1])
        first = np.array([same(c, s["crank_deg"][0]) for c in s["crank_deg"]])
        load = np.where(first, np.abs(self.load_values()), -np.inf)
        return int(s["step"][int(np.argmax(load))])

    def state_label(self, step):
        s = self.stiffness
        if s is None:
            return f"step {step}"
        i = int(np.flatnonzero(s["step"] == step)[0])
        label = f"T = {fmt(s['torque_Nm'][i])} N·m, ψ = {fmt(s['crank_deg'][i])}°"
        if self.energy is not None:
            j = np.flatnonzero(self.energy["step"] == step)
            if j.size:
                label += f", t = {fmt(self.energy['time_s'][j[0]] * 1e3)} ms"
        return label

    def title(self, subject):
        """Figure title: the subject, then the run's key parameters, wrapped
        so that no line runs past the figure."""
        return subject + "\n" + textwrap.fill(self.key_parameters(), 110)

    def key_parameters(self):
        p = self.prm
        return " · ".join(part for part in self._prm_parts(p) + self._load_parts() if part)

    def _prm_parts(self, p):
        mode = p.get("Run") or self._guessed_mode()
        parts = [f"Run = {mode}"]
        if mode != "analytic" and "Scene/Dimension" in p:
            parts.append(f"{p['Scene/Dimension']}D")
        discs = p.get("Scene/Number of discs")
        if not discs or discs == "auto":
            discs = self._count_discs()
        if discs:
            parts.append(f"{discs} disc" + ("s" if str(discs) != "1" else ""))
        if mode != "analytic" and "Scene/Pins" in p:
            support = p.get("Scene/Pin support", "")
            parts.append(f"{p['Scene/Pins']} pins" + (f" ({support})" if support else ""))
        zp = p.get("Geometry/Number of pins") or self._count_pins()
        geometry = [f"zp = {zp}" if zp else ""]
        for key, name, unit in (("Pin radius", "rrp", " mm"), ("Eccentricity", "e", " mm"),
                                ("Shortening coefficient", "K1", ""),
                                ("Pin circle radius modification", "Δrp", " mm"),
                                ("Pin radius modification", "Δrrp", " mm")):
            if "Geometry/" + key in p:
                geometry.append(f"{name} = {_number(p['Geometry/' + key])}{unit}")
        parts.append(", ".join(g for g in geometry if g))
        return parts

    def _load_parts(self):
        """Loads and crank angles as the states have them (a transient: the
        ramp's top), so they also serve without parameters.prm."""
        parts = []
        if self.stiffness is not None:
            loads = self.loads()
            if self.transient:
                parts.append(f"T up to {fmt(max(np.abs(self.stiffness['torque_Nm'])))} N·m")
            elif self.cycle:
                parts.append(f"torque cycle 0 → ±{fmt(max(np.abs(self.torsion['torque_Nm'])))} N·m → 0")
            else:
                unit = "°" if self.by_rotation else " N·m"
                shown = [fmt(math.degrees(v) if self.by_rotation else v) for v in loads]
                if len(shown) > 5:
                    shown = [shown[0], "…", shown[-1], f"({len(shown)} values)"]
                parts.append(("β = " if self.by_rotation else "T = ") + ", ".join(shown) + unit)
            cranks = self.cranks()
            if len(cranks) == 1:
                parts.append(f"ψ = {fmt(cranks[0])}°")
            elif self.transient:
                parts.append(f"ψ = {fmt(self.stiffness['crank_deg'][0])}° → "
                             f"{fmt(self.stiffness['crank_deg'][-1])}°")
            else:
                parts.append(f"ψ = {fmt(cranks[0])}…{fmt(cranks[-1])}° ({len(cranks)} angles)")
        elif self.rigidity is not None:
            parts.append(f"rated T = {fmt(self.rigidity['rated_torque_Nm'][0])} N·m")
        elif self.samples is not None:
            n = len(distinct(self.samples["sample"])) - 1
            parts.append(f"{n} samples, T = "
                         + ", ".join(fmt(t) for t in distinct(self.samples["torque_Nm"]))
                         + " N·m")
        return parts

    def _guessed_mode(self):
        if self.samples is not None:
            return "tolerance"
        if self.transient:
            return "transient"
        if self.stiffness is not None and np.all(self.stiffness["dofs"] == 0):
            return "analytic"
        if self.fluctuation is not None:
            return "phase-sweep"
        return "quasi-static" if self.stiffness is not None else "?"

    def _count_discs(self):
        return len(distinct(self.pins["disc"])) if self.pins is not None else None

    def _count_pins(self):
        return len(distinct(self.pins["pin"])) if self.pins is not None else None


# --- figures ----------------------------------------------------------------

def pin_forces_polar(run):
    """Fn of every pin at its place on the pin circle, one curve per disc;
    beside it the same forces against the pin number, to read values."""
    if run.pins is None:
        return None
    step = run.representative_step()
    rows = run.pins["step"] == step
    fig = plt.figure(figsize=(10, 5), layout="constrained")
    polar = fig.add_subplot(1, 2, 1, projection="polar")
    flat = fig.add_subplot(1, 2, 2)
    for d in distinct(run.pins["disc"][rows]):
        sel = rows & (run.pins["disc"] == d)
        order = np.argsort(run.pins["pin"][sel])
        pin = run.pins["pin"][sel][order]
        fn = run.pins["Fn_N"][sel][order]
        zp = len(pin)
        label = f"disc {int(d)} (max {fmt(fn.max())} N)"
        style = DISC_STYLE[int(d) % len(DISC_STYLE)]
        polar.plot(2 * np.pi * pin / zp, fn, ls="-", ms=4, label=label, **style)
        flat.plot(pin, fn, ls="-", ms=4, label=label, **style)
    polar.set_title("Fn around the pin circle [N]", pad=14)
    polar.set_xlabel("pin position 360°·j/zp")
    polar.set_rlabel_position(_quietest_angle(run.pins, rows))
    flat.set_title("Fn per pin")
    flat.set_xlabel("pin j (at 360°·j/zp)")
    flat.set_ylabel("normal force Fn [N]")
    _legend_outside(flat)
    fig.suptitle(run.title(f"Pin forces, {run.state_label(step)}"))
    fig.index_state = step
    return fig


def _quietest_angle(pins, rows):
    """Angle [°] in the middle of the widest zone of unloaded pins (all
    discs together): the radial tick labels go there, off the curves."""
    zp = int(pins["pin"][rows].max()) + 1
    load = np.zeros(zp)
    np.add.at(load, pins["pin"][rows].astype(int), pins["Fn_N"][rows])
    loaded = np.flatnonzero(load > 0.05 * load.max()) if load.max() > 0 else []
    if len(loaded) == 0:
        return 22.5
    j = np.arange(zp)[:, None]
    gap = np.abs(j - loaded[None, :])
    distance = np.minimum(gap, zp - gap).min(axis=1)  # to the nearest loaded pin
    smooth = load + np.roll(load, 1) + np.roll(load, -1)
    best = np.lexsort((smooth, -distance))[0]  # farthest; of those, least loaded
    return 360.0 * int(best) / zp


def _per_load(run):
    """Rows of stiffness.csv per load group, ordered by crank angle."""
    values = run.load_values()
    for load in run.loads():
        sel = np.array([same(v, load) for v in values])
        order = np.argsort(run.stiffness["crank_deg"][sel])
        yield load, np.flatnonzero(sel)[order]


def stiffness_vs_crank(run):
    """K over one mesh period: the fluctuation a designer must accept."""
    if run.stiffness is None or run.transient or len(run.cranks()) < 2:
        return None
    s = run.stiffness
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.5), layout="constrained")
    for ax, kind in zip(axes, ("tangent", "secant")):
        for load, idx in _per_load(run):
            ax.plot(s["crank_deg"][idx], s[f"K_{kind}_Nm_per_arcmin"][idx], marker="o", ms=3,
                    label=run.load_label(load))
        ax.set_title(f"K_{kind} ({'dT/dβ' if kind == 'tangent' else 'T/β'})")
        ax.set_xlabel("crank angle ψ [°]")
        ax.set_ylabel(f"K_{kind} [N·m/arcmin]")
    _legend_outside(axes[1])
    fig.suptitle(run.title("Torsional stiffness against crank angle"))
    return fig


def stiffness_vs_torque(run):
    """K against the load: the stiffening as more pins engage. One curve per
    crank angle; with many angles their mean and min-max band instead."""
    if run.stiffness is None or run.transient or len(run.loads()) < 2:
        return None
    s, cranks = run.stiffness, run.cranks()
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.5), layout="constrained")
    for ax, kind in zip(axes, ("tangent", "secant")):
        k = s[f"K_{kind}_Nm_per_arcmin"]
        if len(cranks) <= 6:
            for c in cranks:
                idx = np.flatnonzero([same(v, c) for v in s["crank_deg"]])
                idx = idx[np.argsort(s["torque_Nm"][idx])]
                ax.plot(s["torque_Nm"][idx], k[idx], marker="o", ms=3, label=f"ψ = {fmt(c)}°")
        else:
            _mean_band(ax, run, k)
        ax.set_title(f"K_{kind} ({'dT/dβ' if kind == 'tangent' else 'T/β'})")
        ax.set_xlabel("torque T [N·m]")
        ax.set_ylabel(f"K_{kind} [N·m/arcmin]")
    _legend_outside(axes[1])
    fig.suptitle(run.title("Torsional stiffness against torque"))
    return fig


def _mean_band(ax, run, k):
    """Mean over the crank angles per load, with the min-max band."""
    torque, mean, low, high = [], [], [], []
    values = run.load_values()
    for load in run.loads():
        sel = np.array([same(v, load) for v in values])
        torque.append(np.mean(run.stiffness["torque_Nm"][sel]))
        mean.append(np.nanmean(k[sel]))
        low.append(np.nanmin(k[sel]))
        high.append(np.nanmax(k[sel]))
    ax.fill_between(torque, low, high, alpha=0.25,
                    label=f"min–max over {len(run.cranks())} crank angles")
    ax.plot(torque, mean, marker="o", ms=3, label="mean over crank angles")


def transmission_error(run):
    """TE per load against the crank angle (a transient: against time)."""
    s = run.stiffness
    if s is None:
        return None
    te = s["transmission_error_arcsec"] if "transmission_error_arcsec" in s \
        else s["rotation_rad"] * ARCSEC_PER_RAD
    if run.transient:
        return _transmission_error_in_time(run, te)
    if len(run.cranks()) < 2:
        return None
    fig, (ax, dev) = plt.subplots(1, 2, figsize=(10, 4.5), layout="constrained")
    for load, idx in _per_load(run):
        pp = _pp_from_fluctuation(run, load)
        if pp is None:
            pp = np.nanmax(te[idx]) - np.nanmin(te[idx])
        label = f"{run.load_label(load)} (p-p {fmt(pp, 3)}″)"
        ax.plot(s["crank_deg"][idx], te[idx], marker="o", ms=3, label=label)
        # The fluctuation is small beside the mean wind-up: shown on its own.
        dev.plot(s["crank_deg"][idx], te[idx] - np.nanmean(te[idx]), marker="o", ms=3,
                 label=label)
    ax.set_title("loaded output rotation − kinematic rotation")
    ax.set_ylabel("transmission error [arcsec]")
    dev.set_title("its fluctuation about the mean per load")
    dev.set_ylabel("transmission error − mean [arcsec]")
    for a in (ax, dev):
        a.set_xlabel("crank angle ψ [°]")
    _legend_outside(dev)
    fig.suptitle(run.title("Transmission error"))
    return fig


def _pp_from_fluctuation(run, load):
    """The run's own peak-to-peak, if fluctuation.csv has the column."""
    f = run.fluctuation
    if f is None or "transmission_error_pp_arcsec" not in f:
        return None
    key = "rotation_rad" if run.by_rotation else "torque_Nm"
    for value, pp in zip(f.get(key, []), f["transmission_error_pp_arcsec"]):
        if same(value, load):
            return pp
    return None


def _transmission_error_in_time(run, te):
    s = run.stiffness
    if len(s["step"]) < 2:
        return None
    t = _time_of_steps(run, s["step"])
    fig, ax = plt.subplots(figsize=(10, 4.5), layout="constrained")
    ax.plot(t * 1e3, te, marker="o", ms=3,
            label=f"TE (p-p {fmt(np.nanmax(te) - np.nanmin(te), 3)}″)")
    ax.set_xlabel("time t [ms]")
    ax.set_ylabel("transmission error [arcsec]")
    ax.set_title("loaded output rotation − kinematic rotation")
    right = ax.twinx()
    right._index_twin_of = ax
    right.plot(t * 1e3, s["torque_Nm"], color="0.5", ls="--", label="torque T")
    right.set_ylabel("torque T [N·m]")
    right.grid(False)
    _joint_legend(ax, right)
    fig.suptitle(run.title("Transmission error during the transient"))
    return fig


def _time_of_steps(run, steps):
    """Time of each step from energy.csv; the step number if it is absent."""
    e = run.energy
    if e is None:
        return np.asarray(steps, dtype=float)
    return np.interp(steps, e["step"], e["time_s"])


def _joint_legend(ax, right):
    """One legend for an axes and its twin (right axis), outside both."""
    lines, labels = ax.get_legend_handles_labels()
    lines2, labels2 = right.get_legend_handles_labels()
    ax.legend(lines + lines2, labels + labels2, loc="upper left", bbox_to_anchor=(0, -0.13),
              ncols=min(len(labels + labels2), 3), frameon=False)


def _legend_outside(ax):
    """Legend beside the axes: it never hides a curve (constrained layout
    makes room for it)."""
    ax.legend(loc="upper left", bbox_to_anchor=(1.02, 1), borderaxespad=0)


def contact_pressure(run):
    """Peak contact pressure per pin, both discs; FE against Hertz p0 when
    the file has both; the largest shear stress beside it if present."""
    p = run.pins
    if p is None or not any(c in p for c in ("max_contact_pressure_MPa", "hertz_pressure_MPa")):
        return None
    shear = "max_shear_stress_MPa" in p
    step = run.representative_step()
    rows = p["step"] == step
    fig, axes = plt.subplots(1, 2 if shear else 1, figsize=(10, 4.5), layout="constrained",
                             squeeze=False)
    ax = axes[0][0]
    for d in distinct(p["disc"][rows]):
        sel = rows & (p["disc"] == d)
        order = np.argsort(p["pin"][sel])
        style = DISC_STYLE[int(d) % len(DISC_STYLE)]
        for column, name, ls in (("max_contact_pressure_MPa", "peak", "-"),
                                 ("hertz_pressure_MPa", "Hertz p0", "--")):
            if column in p:
                values = p[column][sel][order]
                # Hertz p0 open markers, dashed: it lies close on the FE peak.
                ax.plot(p["pin"][sel][order], values, ls=ls, ms=4,
                        mfc="none" if ls == "--" else None,
                        label=f"disc {int(d)} {name} (max {fmt(values.max())} MPa)", **style)
        if shear:
            _shear_panel(axes[0][1], p, sel, order, d, style)
    ax.set_title("contact pressure per pin")
    ax.set_xlabel("pin j (at 360°·j/zp)")
    ax.set_ylabel("pressure [MPa]")
    ax.legend(loc="upper left", bbox_to_anchor=(0, -0.13), ncols=2, frameon=False)
    fig.suptitle(run.title(f"Contact pressure, {run.state_label(step)}"))
    fig.index_state = step
    return fig


def _shear_panel(ax, p, sel, order, disc, style):
    tau = p["max_shear_stress_MPa"][sel][order]
    label = f"disc {int(disc)} (max {fmt(tau.max())} MPa"
    if "max_shear_depth_um" in p and tau.max() > 0:
        label += f" at {fmt(p['max_shear_depth_um'][sel][order][np.argmax(tau)], 3)} µm depth"
    ax.plot(p["pin"][sel][order], tau, ls="-", ms=4, label=label + ")", **style)
    ax.set_title("largest shear stress below the surface")
    ax.set_xlabel("pin j (at 360°·j/zp)")
    ax.set_ylabel("τ_max [MPa]")
    ax.legend(loc="upper left", bbox_to_anchor=(0, -0.13), frameon=False)


def energy(run):
    """Energy terms of a transient, and the balance error on its own axis
    (it is orders of magnitude smaller than the terms)."""
    e = run.energy
    if e is None or len(e["step"]) < 2:
        return None
    terms = [("kinetic_J", "kinetic", "tab:blue"), ("elastic_J", "elastic", "tab:orange"),
             ("external_work_J", "external work W", "tab:green"),
             ("dissipated_J", "dissipated D", "tab:purple")]
    terms = [term for term in terms if term[0] in e]
    scale, unit = _energy_unit(max(np.nanmax(np.abs(e[term[0]])) for term in terms))
    t = e["time_s"] * 1e3
    fig, ax = plt.subplots(figsize=(10, 4.5), layout="constrained")
    for column, name, color in terms:
        ax.plot(t, e[column] / scale, marker="o", ms=3, color=color, label=name)
    ax.set_xlabel("time t [ms]")
    ax.set_ylabel(f"energy [{unit}]")
    ax.set_title("energy terms")
    if "balance_error_J" in e:
        right = ax.twinx()
        right._index_twin_of = ax
        bscale, bunit = _energy_unit(np.nanmax(np.abs(e["balance_error_J"])))
        right.plot(t, e["balance_error_J"] / bscale, color="tab:red", ls=":", marker="x",
                   ms=4, label="balance error E_kin + E_el + D − W (right axis)")
        right.set_ylabel(f"balance error [{bunit}]")
        right.grid(False)
        _joint_legend(ax, right)
    else:
        _legend_outside(ax)
    fig.suptitle(run.title("Energy of the transient"))
    return fig


def _energy_unit(largest):
    for scale, unit in ((1.0, "J"), (1e-3, "mJ"), (1e-6, "µJ")):
        if largest >= scale:
            return scale, unit
    return 1e-9, "nJ"


# --- torsion curve -----------------------------------------------------------

def _theta_at(torque, theta, target):
    """Mean rotation at which the curve passes `target`, over every branch
    that crosses it (the mid-point of a hysteresis width)."""
    hits = []
    for i in range(len(torque) - 1):
        t0, t1 = torque[i], torque[i + 1]
        if t0 != t1 and min(t0, t1) <= target <= max(t0, t1):
            hits.append(theta[i] + (target - t0) / (t1 - t0) * (theta[i + 1] - theta[i]))
    return float(np.mean(hits)) if hits else None


def _zero_torque_span(torque, theta, rated):
    """Rotations at zero torque: the ends of the dead zone (or crossings)."""
    zero = np.abs(torque) <= 1e-9 * rated
    candidates = list(theta[zero])
    for i in range(len(torque) - 1):
        if torque[i] * torque[i + 1] < 0:
            candidates.append(theta[i] - torque[i] / (torque[i + 1] - torque[i])
                              * (theta[i + 1] - theta[i]))
    return (min(candidates), max(candidates)) if candidates else None


def torsion_curve(run):
    """T against θ over the cycle 0 -> +rated -> -rated -> 0 per crank
    angle, with the figures of rigidity.csv drawn where they are measured
    (marked on the first crank angle's curve, so the marks stay legible)."""
    c = run.torsion
    if c is None:
        return None
    fig, ax = plt.subplots(figsize=(10, 5.5), layout="constrained")
    cranks = distinct(c["crank_deg"]) if "crank_deg" in c else [None]
    for n, crank in enumerate(cranks):
        sel = np.ones(len(c["torque_Nm"]), bool) if crank is None else \
            np.array([same(v, crank) for v in c["crank_deg"]])
        label = "torsion curve" + ("" if crank is None else f", ψ = {fmt(crank)}°")
        row = _rigidity_row(run, crank)
        if row and n > 0:  # the first curve's figures are on its marks
            label += (f": rigidity {fmt(row['torsional_rigidity_Nm_per_arcmin'])} N·m/arcmin, "
                      f"lost motion {fmt(row['lost_motion_arcmin'], 3)}, "
                      f"backlash {fmt(row['backlash_arcmin'], 3)} arcmin")
        ax.plot(c["rotation_arcmin"][sel], c["torque_Nm"][sel], marker=".", ms=4, label=label)
        if n == 0:
            _torsion_marks(ax, c["torque_Nm"][sel], c["rotation_arcmin"][sel], row)
    ax.axhline(0, color="0.3", lw=0.8)
    ax.axvline(0, color="0.3", lw=0.8)
    ax.set_xlabel("output rotation θ [arcmin]")
    ax.set_ylabel("torque T [N·m]")
    ax.set_title("torque cycle 0 → +rated → −rated → 0")
    ax.legend(loc="upper left")
    fig.suptitle(run.title("Torsion curve"))
    return fig


def _rigidity_row(run, crank):
    """rigidity.csv's row for this crank angle (the first row without one)."""
    r = run.rigidity
    if r is None:
        return None
    i = 0
    if crank is not None and "crank_deg" in r:
        match = [k for k, v in enumerate(r["crank_deg"]) if same(v, crank)]
        i = match[0] if match else 0
    return {k: v[i] for k, v in r.items()}


def _torsion_marks(ax, torque, theta, row):
    """The +-3 % points with the lost motion between them, the backlash at
    zero torque (both as dimension lines clear of the curve) and the
    rigidity slope between 50 % and 100 % of rated torque. Positions come
    from the curve, the values in the legend from rigidity.csv if present."""
    rated = row["rated_torque_Nm"] if row else np.max(np.abs(torque))
    plus, minus = _theta_at(torque, theta, 0.03 * rated), _theta_at(torque, theta, -0.03 * rated)
    if plus is not None and minus is not None:
        lost = row["lost_motion_arcmin"] if row else plus - minus
        ax.plot([minus, plus], [-0.03 * rated, 0.03 * rated], ls="none", marker="D", ms=6,
                color="tab:red", label=f"±3 % rated torque (±{fmt(0.03 * rated)} N·m)")
        _dimension(ax, minus, plus, 0.15 * rated, (-0.03 * rated, 0.03 * rated), "tab:red",
                   f"lost motion {fmt(lost, 3)} arcmin")
    span = _zero_torque_span(torque, theta, rated)
    if span is not None:
        backlash = row["backlash_arcmin"] if row else span[1] - span[0]
        _dimension(ax, span[0], span[1], -0.15 * rated, (0, 0), "tab:purple",
                   f"backlash {fmt(backlash, 3)} arcmin (at T = 0)")
    half, full = _theta_at(torque, theta, 0.5 * rated), _theta_at(torque, theta, rated)
    if half is not None and full is not None and full != half:
        k = row["torsional_rigidity_Nm_per_arcmin"] if row else 0.5 * rated / (full - half)
        x = np.array([half - 0.15 * (full - half), full + 0.15 * (full - half)])
        ax.plot(x, 0.5 * rated + k * (x - half), color="k", ls="--", lw=1.2,
                label=f"rigidity {fmt(k)} N·m/arcmin (50–100 % rated)")


def _dimension(ax, x0, x1, y, feet, color, label):
    """A drawing's dimension line from x0 to x1 at height y, with dotted
    extension lines down (or up) to the points it measures at heights feet."""
    for x, foot in zip((x0, x1), feet):
        ax.plot([x, x], [foot, y], color=color, ls=":", lw=0.8)
    ax.annotate("", xy=(x1, y), xytext=(x0, y),
                arrowprops=dict(arrowstyle="<->", color=color, lw=1.2, shrinkA=0, shrinkB=0))
    ax.plot([x0, x1], [y, y], color=color, lw=1.2, label=label)


# --- tolerance studies ------------------------------------------------------

def _cdf(ax, values, label, style):
    x = np.sort(values[np.isfinite(values)])
    if x.size:
        ax.step(x, np.arange(1, x.size + 1) / x.size, where="post", label=label, **style)


def tolerance_distributions(run):
    """Empirical CDFs over the samples (sample 0, the nominal stage, left
    out and marked by a dashed line) at the first crank angle, one curve
    per torque."""
    s = run.samples
    if s is None:
        return None
    crank = s["crank_deg"][0]
    fig, axes = plt.subplots(2, 2, figsize=(10, 7.5), layout="constrained")
    panels = [("K_secant_Nm_per_rad", "K_secant", "K_secant [N·m/arcmin]", 1 / ARCMIN_PER_RAD),
              ("load_sharing", "load sharing λ", "λ = K_secant / nominal K_secant [-]", 1.0),
              ("max_pin_force_N", "peak pin force", "peak pin force [N]", 1.0),
              ("rotation_rad", "output rotation", "output rotation [arcmin]", ARCMIN_PER_RAD)]
    colors = plt.rcParams["axes.prop_cycle"].by_key()["color"]
    for ax, (key, name, label, scale) in zip(axes.flat, panels):
        for i, t in enumerate(distinct(s["torque_Nm"])):
            at = (s["torque_Nm"] == t) & np.array([same(c, crank) for c in s["crank_deg"]])
            nominal = at & (s["sample"] == 0)
            drawn = at & (s["sample"] != 0)
            if t == 0 or not np.any(nominal):
                continue
            k0 = s["K_secant_Nm_per_rad"][nominal][0]
            values = (s["K_secant_Nm_per_rad"][drawn] / k0 if key == "load_sharing"
                      else s[key][drawn] * scale)
            ref = 1.0 if key == "load_sharing" else s[key][nominal][0] * scale
            style = dict(color=colors[i % len(colors)])
            p5, p95 = np.percentile(values, [5, 95])
            _cdf(ax, values, f"T = {fmt(t)} N·m: P5 {fmt(p5)}, P95 {fmt(p95)}", style)
            ax.axvline(ref, ls="--", lw=1, **style)
        if key == "load_sharing":
            ax.axvline(0.7, color="k", ls=":", lw=1.2, label="the seed's λ = 0.7")
        ax.set_xlabel(label)
        ax.set_ylabel("fraction of samples ≤ x")
        ax.set_title(name + " (dashed: nominal stage)")
        ax.legend(loc="lower right")
    n = len(distinct(s["sample"])) - 1
    fig.suptitle(run.title(f"Tolerance study: {n} samples, crank angle {fmt(crank)}°"))
    return fig


def pin_force_spread(run):
    """A box per pin at the largest torque and first crank angle: P5 to P95,
    the median, whiskers to the smallest and largest sample; the nominal
    stage's force as a dot."""
    p = run.pin_spread
    if p is None:
        return None
    crank = p["crank_deg"][0]
    torque = max(p["torque_Nm"])
    sel = (p["torque_Nm"] == torque) & np.array([same(c, crank) for c in p["crank_deg"]])
    fig, ax = plt.subplots(figsize=(10, 5), layout="constrained")
    for d in distinct(p["disc"][sel]):
        on = sel & (p["disc"] == d)
        order = np.argsort(p["pin"][on])
        pin = p["pin"][on][order]
        offset = 0.2 * (d - 0.5) if len(distinct(p["disc"][sel])) > 1 else 0.0
        stats = [{"med": m, "q1": a, "q3": b, "whislo": lo, "whishi": hi, "fliers": []}
                 for m, a, b, lo, hi in zip(p["p50"][on][order], p["p05"][on][order],
                                            p["p95"][on][order], p["min"][on][order],
                                            p["max"][on][order])]
        style = DISC_STYLE[int(d) % len(DISC_STYLE)]
        ax.bxp(stats, positions=pin + offset, widths=0.35, showfliers=False,
               boxprops=dict(color=style["color"]), medianprops=dict(color=style["color"]),
               whiskerprops=dict(color=style["color"]), capprops=dict(color=style["color"]),
               manage_ticks=False)
        ax.plot(pin + offset, p["nominal"][on][order], ls="", marker=style["marker"], ms=4,
                color="k", label=f"disc {int(d)}: nominal stage")
    ax.set_xlabel("pin j")
    ax.set_ylabel("normal force Fn [N]")
    ax.set_title(f"Fn per pin over the samples, T = {fmt(torque)} N·m, ψ = {fmt(crank)}° "
                 "(box P5-P95, line median, whiskers min-max)")
    _legend_outside(ax)
    fig.suptitle(run.title("Spread of the pin forces"))
    return fig


# --- compliance breakdown -------------------------------------------------------

BREAKDOWN_PARTS = [("contacts_rad", "pin contacts", "tab:blue"),
                   ("bodies_rad", "elastic bodies", "tab:green"),
                   ("bearings_rad", "crank bearings", "tab:red")]


def compliance_breakdown(run):
    """Each loaded state's rotation as stacked bars of its parts [µrad]
    (magnitudes: a negative torque's parts are all negative)."""
    b = run.breakdown
    if b is None:
        return None
    sel = np.isfinite(b["total_rad"]) & (b["torque_Nm"] != 0)
    if not sel.any():
        return None
    n = int(sel.sum())
    x = np.arange(n)
    fig, ax = plt.subplots(figsize=(max(10.0, 0.6 * n + 6), 5), layout="constrained")
    bottom = np.zeros(n)
    total = np.abs(b["total_rad"][sel]) * 1e6
    for column, label, color in BREAKDOWN_PARTS:
        part = np.abs(b[column][sel]) * 1e6
        share = part / total
        ax.bar(x, part, bottom=bottom, color=color, width=0.6,
               label=f"{label}: {fmt(100 * share.min(), 3)} to {fmt(100 * share.max(), 3)} % of β")
        bottom += part
    ax.plot(x, total, ls="", marker="_", ms=14, color="k", label="total β")
    ax.set_xticks(x)
    ax.set_xticklabels([f"{fmt(t)} N·m\nψ {fmt(c)}°" for t, c in
                        zip(b["torque_Nm"][sel], b["crank_deg"][sel])], fontsize=7)
    ax.set_xlabel("state (torque [N·m], crank angle [°])")
    ax.set_ylabel("|β| and its parts [µrad]")
    ax.set_title("where the output rotation comes from: each part's share of the work T β")
    _legend_outside(ax)
    fig.suptitle(run.title("Compliance breakdown"))
    return fig


# --- index and main ------------------------------------------------------------

def describe(fig, filename):
    """What a figure shows, read back from its axes (twin axes folded into
    their panel): title, labels, and each labelled curve with its points."""
    panels, by_axes = [], {}
    for ax in fig.axes:
        parent = getattr(ax, "_index_twin_of", None)
        if parent is not None:
            panel = by_axes[id(parent)]
            panel["ylabel_right"] = ax.get_ylabel()
        else:
            panel = {"title": ax.get_title(), "xlabel": ax.get_xlabel(),
                     "ylabel": ax.get_ylabel(), "polar": ax.name == "polar", "curves": []}
            by_axes[id(ax)] = panel
            panels.append(panel)
        side = "right" if parent is not None else "left"
        for line in ax.get_lines():
            if not line.get_label().startswith("_"):
                panel["curves"].append({"label": line.get_label(), "kind": "line",
                                        "points": len(line.get_xdata()), "axis": side})
        for coll in ax.collections:
            if not coll.get_label().startswith("_"):
                panel["curves"].append({"label": coll.get_label(), "kind": "band",
                                        "points": len(coll.get_paths()), "axis": side})
        for bars in ax.containers:
            if not bars.get_label().startswith("_"):
                panel["curves"].append({"label": bars.get_label(), "kind": "bars",
                                        "points": len(bars), "axis": side})
    title = fig._suptitle.get_text() if fig._suptitle else ""
    entry = {"file": filename, "title": title, "panels": panels}
    if hasattr(fig, "index_state"):  # the step of the per-pin figures
        entry["step"] = fig.index_state
    return entry


FIGURES = [("pin_forces_polar.png", pin_forces_polar),
           ("stiffness_vs_crank.png", stiffness_vs_crank),
           ("stiffness_vs_torque.png", stiffness_vs_torque),
           ("torsion_curve.png", torsion_curve),
           ("transmission_error.png", transmission_error),
           ("contact_pressure.png", contact_pressure),
           ("energy.png", energy),
           ("tolerance_distributions.png", tolerance_distributions),
           ("pin_force_spread.png", pin_force_spread),
           ("compliance_breakdown.png", compliance_breakdown)]


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.split("\n\n")[1], file=sys.stderr)
        return 2
    directory = argv[1]
    if not os.path.isdir(directory):
        print(f"plot: error: output directory '{directory}' does not exist.", file=sys.stderr)
        return 1
    if not any(os.path.isfile(os.path.join(directory, f)) for f in KNOWN_FILES):
        print(f"plot: error: '{directory}' holds none of the files a run writes "
              f"({', '.join(KNOWN_FILES)}).", file=sys.stderr)
        return 1
    run = Run(directory)
    out = os.path.join(directory, "plots")
    os.makedirs(out, exist_ok=True)
    index = {"directory": os.path.abspath(directory), "parameters": run.key_parameters(),
             "figures": []}
    for filename, draw in FIGURES:
        fig = draw(run)
        if fig is None:
            continue
        path = os.path.join(out, filename)
        fig.savefig(path)
        index["figures"].append(describe(fig, filename))
        plt.close(fig)
        print(path)
    with open(os.path.join(out, "index.json"), "w") as f:
        json.dump(index, f, indent=1, ensure_ascii=False)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
