"""The catalogue figures of one crank angle's torsion curve, as
doc/catalogue.md defines them, for the test checkers (an independent
re-implementation of source/postprocess/catalogue.cc)."""
import math

ARCSEC = 180 * 3600 / math.pi
ARCMIN = 180 * 60 / math.pi


def catalogue(curve, rated, check):
    """(rigidity b/a [N m/arcmin] between 50 and 100 % of the rated torque
    in both directions, lost motion [arcmin] between +-3 %, backlash
    [arcmin] = the spread of the rotations at zero torque) of the (torque,
    rotation) points @p curve; @p check(condition, message) reports a
    missing state."""
    def theta(f):
        values = [th for T, th in curve if abs(T - f * rated) <= 1e-9 * rated]
        check(values, f"no state at {f * 100} % of the rated torque")
        return sum(values) / len(values) if values else float("nan")
    a = theta(1) - theta(0.5) + theta(-0.5) - theta(-1)
    zeros = [th for T, th in curve if T == 0]
    check(len(zeros) >= 2, "fewer than two zero-torque states")
    return rated / a / ARCMIN, (theta(0.03) - theta(-0.03)) * ARCMIN, (max(zeros) - min(zeros)) * ARCMIN
