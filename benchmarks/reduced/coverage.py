#!/usr/bin/python3
"""Does the reduced model's own error estimate cover its error? Three
reducers other than the seed, against the full FE model (issue #51 item 2).

For every reducer, dimension, crank angle and torque the reduced model (at
its defaults, with `Reduced/Error estimate = true`) and the full FE model
solve the same state. Per state and quantity (K_secant, K_tangent, every
pin force as a fraction of the largest) the script writes

- `diff`: the reduced model against the FE (relative; for the pins the
  largest |dF| over the FE's largest pin force);
- `est`: the reduced model's own estimate (stiffness.csv *_error);
- `fe_est`: the FE reference's own estimate (2D: its nested contact levels
  with the bulk part; 3D: the contact-resolution indicator for the pins,
  none for K);
- `covered`: est >= |diff|, and `covered_with_fe`: est + fe_est >= |diff|
  (the reference is not exact: a difference inside its own band says
  nothing about the reduced model).

    /usr/bin/python3 benchmarks/reduced/coverage.py [--dims 2,3]
        [--exe build/cycloid-contact] [--ranks 2] [--out doc/reduced]
        [--reducers small,thirty,large]

2D: one disc, elastic pins seated in the housing, the FE at Contact
refinements 4 within 0.3 mm (its error estimate on). 3D: two discs, the FE
at one axial layer per disc and Contact refinements 3 within 0.3 mm at the
loaded pins (prm/quasi-static-3d.prm's mesh), 1.5-4 min a state.
Output: coverage-<dim>d.csv in --out.
"""
import argparse
import csv
import math
import os
import sys
from pathlib import Path

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

# name: (zp, rrp [mm], e [mm], rp [mm], b [mm], Delta rp [mm],
#        Delta rrp [mm], torques [N m] of the 2D one-disc scene)
REDUCERS = {
    'small': (20, 3, 1.2, 40, 8, -0.01, 0.01, '30, 100'),
    'thirty': (30, 4, 1.5, 75, 12, 0, 0, '150, 500'),
    'large': (50, 5, 2.5, 170, 20, -0.02, 0.015, '1000, 3000'),
}

FE_MESH = {
    2: ('  set Contact refinements = 4\n'
        '  set Contact refinement radius = 0.3\n'),
    3: ('  set Axial layers per disc = 1\n'
        '  set Contact refinements = 3\n'
        '  set Contact refinement radius = 0.3\n'
        '  set Contact refinement side = loaded\n'
        '  set Triangulation = distributed\n'),
}


def prm_text(run, out, dim, reducer, crank):
    zp, rrp, e, rp, b, drp, drrp, torques = REDUCERS[reducer]
    text = ('set Run = %s\nset Output directory = %s\nset Write solution = false\n'
            'subsection Geometry\n  set Number of pins = %d\n  set Pin radius = %g\n'
            '  set Eccentricity = %g\n  set Pin circle radius = %g\n'
            '  set Tooth width = %g\n  set Pin circle radius modification = %g\n'
            '  set Pin radius modification = %g\nend\n'
            'subsection Scene\n  set Dimension = %d\n  set Number of discs = %d\n'
            '  set Pins = elastic\n  set Pin support = housing\nend\n'
            'subsection Loading\n  set Torque = %s\n  set Crank angle = %g\nend\n'
            % (run, out, zp, rrp, e, rp, b, drp, drrp, dim, 1 if dim == 2 else 2,
               torques, crank))
    if run != 'reduced':
        text += 'subsection Mesh\n%send\n' % FE_MESH[dim]
    return text


def number(row, key):
    text = row.get(key, '')
    return float(text) if text not in ('', None) else math.nan


def forces(pins, step):
    return {(p['disc'], p['pin']): float(p['Fn_N']) for p in pins if p['step'] == step}


def compare(red, fe, dim):
    """One row per state of RED matched with FE by torque."""
    rows = []
    fe_states = {float(b['torque_Nm']): b for b in fe[0]}
    for a in red[0]:
        b = fe_states.get(float(a['torque_Nm']))
        if b is None:
            continue
        fa, fb = forces(red[1], a['step']), forces(fe[1], b['step'])
        fmax = max(fb.values())
        row = dict(torque_Nm=a['torque_Nm'],
                   engaged_reduced=sum(v > 0 for v in fa.values()),
                   engaged_fe=sum(v > 0 for v in fb.values()),
                   reduced_dofs=a['dofs'], fe_dofs=b['dofs'])
        for q, key in [('K_secant', 'K_secant_Nm_per_rad'),
                       ('K_tangent', 'K_tangent_Nm_per_rad')]:
            row[q + '_diff'] = float(a[key]) / float(b[key]) - 1
            row[q + '_est'] = number(a, q + '_error')
            row[q + '_fe_est'] = number(b, q + '_error')
        row['pins_diff'] = max(abs(fa.get(k, 0) - fb.get(k, 0))
                               for k in set(fa) | set(fb)) / fmax
        row['pins_est'] = number(a, 'max_pin_force_error')
        fe_pins = number(b, 'max_pin_force_error')
        row['pins_fe_est'] = fe_pins if dim == 2 else number(b, 'resolution_error')
        for q in ['K_secant', 'K_tangent', 'pins']:
            d, e, f = abs(row[q + '_diff']), row[q + '_est'], row[q + '_fe_est']
            row[q + '_covered'] = int(e >= d)
            row[q + '_covered_with_fe'] = (int(e + f >= d) if not math.isnan(f)
                                           else row[q + '_covered'])
        rows.append(row)
    return rows


def read(out):
    return (read_csv(os.path.join(out, 'stiffness.csv')),
            read_csv(os.path.join(out, 'pin_forces.csv')))


def main():
    ap = argparse.ArgumentParser(description=__doc__.split('\n')[0])
    ap.add_argument('--dims', default='2')
    ap.add_argument('--exe', default='build/cycloid-contact')
    ap.add_argument('--ranks', type=int, default=2)
    ap.add_argument('--out', default='doc/reduced')
    ap.add_argument('--reducers', default=','.join(REDUCERS))
    ap.add_argument('--work', default='/tmp/reduced-coverage')
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    for dim in [int(d) for d in args.dims.split(',')]:
        rows = []
        for reducer in args.reducers.split(','):
            zp = REDUCERS[reducer][0]
            cranks = [0, 180. / zp] if dim == 2 else [0]
            for crank in cranks:
                name = '%dd-%s-%g' % (dim, reducer, crank)
                times = {}
                for mode in ['reduced', 'quasi-static']:
                    out = os.path.join(args.work, name + '-' + mode)
                    prm = out + '.prm'
                    with open(prm, 'w') as f:
                        f.write(prm_text(mode, out, dim, reducer, crank))
                    p = run_cycloid(args.ranks, exe, prm, log=out + '.log')
                    if p.returncode != 0:
                        sys.exit('failed: %s (see %s.log)' % (prm, out))
                    times[mode] = p.wall_s
                for r in compare(read(os.path.join(args.work, name + '-reduced')),
                                 read(os.path.join(args.work, name + '-quasi-static')), dim):
                    r.update(reducer=reducer, dim=dim, crank_deg='%g' % crank,
                             reduced_wall_s='%.1f' % times['reduced'],
                             fe_wall_s='%.1f' % times['quasi-static'])
                    rows.append(r)
                    print('%-18s T %6s  ' % (name, r['torque_Nm']) + '  '.join(
                        '%s %.2f%% est %.2f%% (FE %.2f%%)%s' % (
                            q, 100 * abs(r[q + '_diff']), 100 * r[q + '_est'],
                            100 * r[q + '_fe_est'], '' if r[q + '_covered'] else
                            (' +FE' if r[q + '_covered_with_fe'] else ' MISSED'))
                        for q in ['K_secant', 'K_tangent', 'pins']), flush=True)
        keys = ['reducer', 'dim', 'crank_deg', 'torque_Nm']
        for q in ['K_secant', 'K_tangent', 'pins']:
            keys += [q + s for s in ['_diff', '_est', '_fe_est', '_covered',
                                     '_covered_with_fe']]
        keys += ['engaged_reduced', 'engaged_fe', 'reduced_dofs', 'fe_dofs',
                 'reduced_wall_s', 'fe_wall_s']
        with open(os.path.join(args.out, 'coverage-%dd.csv' % dim), 'w') as f:
            w = csv.DictWriter(f, keys)
            w.writeheader()
            for r in rows:
                w.writerow({k: ('%.5f' % r[k]) if isinstance(r[k], float) else r[k]
                            for k in keys})


if __name__ == '__main__':
    main()
