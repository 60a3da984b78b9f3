#!/usr/bin/python3
"""Reduced model against the full FE model of the same scene (issue #13).

For every case (scene x profile x crank angle) the reduced model
(`Run = reduced`, defaults of subsection Reduced) and the full FE model
(`Run = quasi-static`, the mesh given by --fe-mesh) solve the same torques;
the script writes per state the relative errors of K_secant, K_tangent and
K_secant_elastic, the largest pin-force difference over the largest FE pin
force, whether the engaged pins agree, and both wall times (the whole
command, timed from outside).

    /usr/bin/python3 benchmarks/reduced/validate.py [--dims 2,3] [--exe build/cycloid-contact]
        [--ranks 2] [--out doc/reduced] [--torques 300,1000]

2D: one disc, elastic pins on their axes and in the housing, the FE at
Contact refinements 4 within 0.3 mm (cr3 and cr4 agree to 0.02 % in K_secant
and 0.4 % in K_tangent and pin forces on the seed case).
3D: two discs, elastic pins in the housing, the FE on the in-plane mesh of
doc/ladder ("p25": Contact element size 0.25) with one axial layer per disc
and Contact refinements 2 at the loaded pins, which is the ladder's "p25 ax1
cr2 loaded" (within 0.3 % of the 3D reference in K_secant; ~4 min a state).
Output: validation-<dim>d.csv in --out.
"""
import argparse
import csv
import os
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parents[2] / "scripts"))
from cycloid_tools import read_csv, run_cycloid  # noqa: E402

PROFILES = {
    'zero': '',
    'modified': ('  set Pin circle radius modification = -0.01\n'
                 '  set Pin radius modification        = 0.01\n'),
}


def prm_text(run, out, dim, support, profile, crank, torques, mesh):
    scene = ('  set Dimension = %d\n  set Pins = elastic\n'
             '  set Pin support = %s\n' % (dim, support))
    if dim == 3:
        scene += '  set Number of discs = 2\n'
    text = ('set Run = %s\nset Output directory = %s\nset Write solution = false\n'
            'subsection Geometry\n%send\nsubsection Scene\n%send\n'
            'subsection Loading\n  set Torque = %s\n  set Crank angle = %g\nend\n'
            % (run, out, PROFILES[profile], scene, torques, crank))
    return text + ('subsection Mesh\n%send\n' % mesh if mesh else '')


def run(exe, ranks, prm, log):
    p = run_cycloid(ranks, exe, prm, log=log)
    if p.returncode != 0:
        sys.exit('failed: %s (see %s)' % (' '.join(p.args), log))
    return p.wall_s


def read(out):
    return read_csv(os.path.join(out, 'stiffness.csv')), read_csv(os.path.join(out, 'pin_forces.csv'))


def compare(red, fe):
    """Per state of RED that FE also has (states matched by torque): the
    relative errors of RED against FE, the largest pin-force difference
    over FE's largest pin force, the engaged pins, and RED's own
    contact-resolution indicator (nan for the reduced model)."""
    rows = []
    fe_states = {float(b['torque_Nm']): b for b in fe[0]}
    for a in red[0]:
        b = fe_states.get(float(a['torque_Nm']))
        if b is None:
            continue
        err = {k: float(a[k]) / float(b[k]) - 1 for k in
               ['K_secant_Nm_per_rad', 'K_tangent_Nm_per_rad',
                'K_secant_elastic_Nm_per_rad']}
        fa = {(p['disc'], p['pin']): float(p['Fn_N']) for p in red[1] if p['step'] == a['step']}
        fb = {(p['disc'], p['pin']): float(p['Fn_N']) for p in fe[1] if p['step'] == b['step']}
        fmax = max(fb.values())
        dev = max(abs(fa.get(k, 0) - fb.get(k, 0)) for k in set(fa) | set(fb)) / fmax
        ea = sorted(k for k, v in fa.items() if v > 0)
        eb = sorted(k for k, v in fb.items() if v > 0)
        rows.append(dict(torque_Nm=a['torque_Nm'],
                         K_secant_error=err['K_secant_Nm_per_rad'],
                         K_tangent_error=err['K_tangent_Nm_per_rad'],
                         K_secant_elastic_error=err['K_secant_elastic_Nm_per_rad'],
                         max_pin_force_error=dev,
                         F_max_error=float(a['max_pin_force_N']) / fmax - 1,
                         resolution_error=float(a.get('resolution_error') or 'nan'),
                         hertz_nodes=float(a.get('hertz_nodes') or 'nan'),
                         same_engaged_pins=int(ea == eb),
                         engaged_reduced=len(ea), engaged_fe=len(eb),
                         reduced_dofs=a['dofs'], fe_dofs=b['dofs']))
    return rows


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('--dims', default='2')
    ap.add_argument('--exe', default='build/cycloid-contact')
    ap.add_argument('--ranks', type=int, default=2)
    ap.add_argument('--out', default='doc/reduced')
    ap.add_argument('--torques', default='300, 1000')
    ap.add_argument('--work', default='/tmp/reduced-validation')
    args = ap.parse_args()
    exe = os.path.abspath(args.exe)
    os.makedirs(args.out, exist_ok=True)
    os.makedirs(args.work, exist_ok=True)
    for dim in [int(d) for d in args.dims.split(',')]:
        if dim == 2:
            supports = ['axis', 'housing']
            fe_mesh = ('  set Contact refinements = 4\n'
                       '  set Contact refinement radius = 0.3\n')
        else:
            supports = ['housing']
            fe_mesh = ('  set Axial layers per disc = 1\n'
                       '  set Contact refinements = 2\n'
                       '  set Contact refinement radius = 0.3\n'
                       '  set Contact refinement side = loaded\n')
        rows = []
        for support in supports:
            for profile in PROFILES:
                for crank in [0, 4.5]:
                    name = '%dd-%s-%s-%g' % (dim, support, profile, crank)
                    times = {}
                    for run_mode, mesh in [('reduced', ''), ('quasi-static', fe_mesh)]:
                        out = os.path.join(args.work, name + '-' + run_mode)
                        prm = out + '.prm'
                        open(prm, 'w').write(prm_text(run_mode, out, dim, support, profile,
                                                      crank, args.torques, mesh))
                        times[run_mode] = run(exe, args.ranks, prm, out + '.log')
                    for r in compare(read(os.path.join(args.work, name + '-reduced')),
                                     read(os.path.join(args.work, name + '-quasi-static'))):
                        r.update(dict(case=name, support=support, profile=profile,
                                      crank_deg=crank, reduced_wall_s='%.2f' % times['reduced'],
                                      fe_wall_s='%.2f' % times['quasi-static']))
                        rows.append(r)
                        print('%-28s T %6s  K_sec %+.2f%%  K_tan %+.2f%%  dF/Fmax %.2f%%  '
                              'pins %s  %.1f s vs %.1f s' % (
                                  name, r['torque_Nm'], 100 * r['K_secant_error'],
                                  100 * r['K_tangent_error'], 100 * r['max_pin_force_error'],
                                  'same' if r['same_engaged_pins'] else
                                  '%d vs %d' % (r['engaged_reduced'], r['engaged_fe']),
                                  times['reduced'], times['quasi-static']), flush=True)
        keys = ['case', 'support', 'profile', 'crank_deg', 'torque_Nm', 'K_secant_error',
                'K_tangent_error', 'K_secant_elastic_error', 'max_pin_force_error',
                'same_engaged_pins', 'engaged_reduced', 'engaged_fe', 'reduced_dofs',
                'fe_dofs', 'reduced_wall_s', 'fe_wall_s']
        with open(os.path.join(args.out, 'validation-%dd.csv' % dim), 'w') as f:
            w = csv.DictWriter(f, keys)
            w.writeheader()
            for r in rows:
                w.writerow({k: (('%.5f' % r[k]) if isinstance(r[k], float) else r[k])
                            for k in keys})


if __name__ == '__main__':
    main()
