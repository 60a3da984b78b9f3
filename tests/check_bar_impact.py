#!/usr/bin/python3
"""Elastic bar against a rigid wall (benchmarks/transient/bar_impact.cc).

Usage: check_bar_impact.py BAR_IMPACT_EXECUTABLE [RANKS]

1D theory: contact for 2L/c with the force rho c h v0, rebound at -v0.
- contact-stabilised and generalized-alpha: the mean contact force within
  2 %, the contact time within 2 steps, the rebound within 5 %, no
  penetration at the end of any step (1e-12 mm), and the energy never above
  its initial value (1e-9 relative): the balance error is a loss of at most
  5 % (measured -1.2 % and -1.5 % of E0 at CFL 1, doc/transient.md).
- newmark: the known failure (chatter) must be visible to the project's
  own measures: the contact force switches on and off during the contact
  period and the energy balance error exceeds 10 % of E0 (measured +600 %).
  If Newmark stopped chattering, the stability study would be wrong.
"""
import re
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402


def run(exe, scheme, ranks):
    out = run_cycloid(ranks if ranks > 1 else None, exe, scheme, "40", "1", "0.8", check=True,
                      oversubscribe=True).stdout
    header = out.splitlines()[0]
    meta = dict(re.findall(r"(dt|2L/c|v0|E0) ([-0-9.e+]+)", header))
    dt = float(re.search(r"dt ([-0-9.e+]+)", header).group(1))
    tc = float(re.search(r"2L/c ([-0-9.e+]+)", header).group(1))
    force = float(re.search(r"v0 ([-0-9.e+]+) N/mm", header).group(1))
    e0 = float(re.search(r"E0 ([-0-9.e+]+)", header).group(1))
    return dt, tc, force, e0, read_csv(out.splitlines()[1:], numbers=(float,))


def main(exe, ranks):
    failures = []
    for scheme in ("contact-stabilised", "generalized-alpha", "newmark"):
        dt, tc, f_exact, e0, rows = run(exe, scheme, ranks)
        in_contact = [r for r in rows if r["n_active"] > 0]
        t_release = max(r["time_s"] for r in in_contact)
        during = [r for r in rows if r["time_s"] <= tc - 2 * dt]
        mean_f = sum(r["contact_force_N_per_mm"] for r in during) / len(during)
        switches = sum(1 for a, b in zip(during, during[1:]) if (a["n_active"] > 0) != (b["n_active"] > 0))
        rebound = rows[-1]["velocity_mm_per_s"]
        worst_gain = max(r["balance_error_Nmm"] for r in rows) / e0
        final = rows[-1]["balance_error_Nmm"] / e0
        pen = max(r["max_penetration_mm"] for r in rows)
        print(f"{scheme}: mean force {mean_f:.4g} N/mm (1D {f_exact:.4g}), release at {t_release:.4g} s "
              f"(2L/c {tc:.4g}, dt {dt:.3g}), rebound {rebound:.5g} mm/s (-1000), contact on/off switches "
              f"{switches}, energy error max {worst_gain:+.3e} E0, final {final:+.3e} E0, penetration {pen:.2e} mm")
        if scheme == "newmark":
            if switches < 4 or abs(final) < 0.1:
                failures.append(f"newmark: no chatter detected (switches {switches}, energy error {final:+.3e})")
            continue
        if abs(mean_f / f_exact - 1) > 0.02:
            failures.append(f"{scheme}: mean contact force {mean_f} vs {f_exact}")
        if abs(t_release - tc) > 2 * dt:
            failures.append(f"{scheme}: contact time {t_release} vs {tc}")
        if abs(rebound / -1000 - 1) > 0.05:
            failures.append(f"{scheme}: rebound velocity {rebound}")
        if pen > 1e-12:
            failures.append(f"{scheme}: penetration {pen} mm at the end of a step")
        if worst_gain > 1e-9 or final < -0.05:
            failures.append(f"{scheme}: energy error {worst_gain} (max), {final} (final)")
        if switches != 0:
            failures.append(f"{scheme}: contact switched on and off {switches} times during contact")
    print("\n".join(failures) if failures else "all checks passed")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1], int(sys.argv[2]) if len(sys.argv) > 2 else 1))
