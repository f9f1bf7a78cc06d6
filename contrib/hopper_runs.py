#!/usr/bin/python3
"""Extra runs behind two hopper figures and a table (doc/hopper.md), written
to OUTPUT_DIR (default output/); BUILD is the build directory (default build):

  /usr/bin/python3 contrib/hopper_runs.py range [BUILD]       # Fig. 9 bar: hopper_march_range/range.csv
  /usr/bin/python3 contrib/hopper_runs.py precision [BUILD]   # 4.7: hopper_work_precision/work-precision.csv
  /usr/bin/python3 contrib/hopper_runs.py indicators [BUILD]  # 4.7's last table: hopper_indicators/whole-march.csv

range: the 30 deg cone to lower angles RANGE_ANGLES, P1, N = 400, to r = 0.05 r0.
precision: P1-P3 on several meshes, (a) the 30 deg cone's radial field at
  tau = 1, (b) the 30 -> 25 deg cone at tau = 0.5 against P3 on N = 800, (c)
  as (a) without the limiter: relative L1 error of (T_rr, T_rtheta) at 2001
  theta, and the CPU time of the run and of the march (minus a one-step run).
indicators: the whole march of the cone and wedge 30 -> 25 as shipped on
  N = 100-400, limiter everywhere and kxrcf, against P2 N = 1600 references
  of each (about 40 min of CPU). precision and indicators reuse completed runs."""
import math
import os
import sys

from granular_dg import outputs
from granular_dg.compare import stress_l1
from granular_dg.run import NO_SNAPSHOTS, run_case

BUILD = sys.argv[2] if len(sys.argv) > 2 else 'build'
OUT = os.environ.get('OUTPUT_DIR', 'output')
RANGE_ANGLES = [18.5, 19, 20, 21, 21.5, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 31.5, 32, 33]
SAMPLED = ('Hopper output/step series interval=0', 'Hopper output/sample points=2001') + NO_SNAPSHOTS


def run(prm, directory, *sets, reuse=False, check=False):
    """A run and its CPU time (a reused run without one is repeated)."""
    r = run_case(BUILD, prm, directory, sets, reuse=reuse, check=check)
    return run_case(BUILD, prm, directory, sets, check=check) if math.isnan(r.cpu_s) else r


def stress(directory, i):
    return outputs.read_table(os.path.join(directory, 'stress-%04d.csv' % i))


def march_range():
    base = os.path.join(OUT, 'hopper_march_range')
    rows = []
    for a in RANGE_ANGLES:
        r = run('prm/hopper_cone_30_25.prm', os.path.join(base, 'theta_%g' % a),
                'Hopper/lower half-angle=%g' % a, 'Hopper output/step series interval=0', *NO_SNAPSHOTS)
        s = r.summary
        rows.append(dict(theta_w=a, completed=int(r.code == 0), final_tau=s.get('final_time', 0),
                         min_margin=s.get('diagnostics', {}).get('min_hyperbolicity_margin', float('nan')),
                         cpu_s=r.cpu_s))
        print('theta_w = %g: exit %d, tau = %s %s' % (a, r.code, s.get('final_time'), r.stderr[:160]))
    outputs.write_csv(os.path.join(base, 'range.csv'), rows)


def precision():
    base = os.path.join(OUT, 'hopper_work_precision')
    # CFL 1/(2k+1) (GM) for k = 1, 2; k = 3 is unstable at 1/7 (limit ~0.13, doc/hopper.md)
    cfl = {1: 1 / 3., 2: 1 / 5., 3: 0.12}
    meshes = {1: [50, 100, 200, 400], 2: [25, 50, 100, 200], 3: [25, 50, 100, 200]}
    ref = stress(run('prm/hopper_cone_30_25.prm', os.path.join(base, 'transition_reference'),
                     'Discretization/degree=3', 'Hopper/cells=800', 'Time stepping/CFL number=%.12g' % cfl[3],
                     'Time stepping/final time=0.5', *SAMPLED, reuse=True, check=True).directory, 1)
    # the CPU time of start-up and set-up (a one-step run), subtracted below
    setup = {prm: min(run(prm, os.path.join(base, 'setup_' + os.path.basename(prm)[:-4]),
                          'Time stepping/final time=1e-9', *SAMPLED).cpu_s for _ in range(3))
             for prm in ('prm/hopper_radial_cone.prm', 'prm/hopper_cone_30_25.prm')}
    rows = []
    for case, prm, final, extra in ((0, 'prm/hopper_radial_cone.prm', 1.0, []),
                                    (1, 'prm/hopper_cone_30_25.prm', 0.5, []),
                                    (2, 'prm/hopper_radial_cone.prm', 1.0, ['Limiter/scheme=none'])):
        for p, n in ((p, n) for p, cells in meshes.items() for n in cells):
            r = run(prm, os.path.join(base, 'case%d_p%d_n%d' % (case, p, n)), 'Discretization/degree=%d' % p,
                    'Hopper/cells=%d' % n, 'Time stepping/CFL number=%.12g' % cfl[p],
                    'Time stepping/final time=%g' % final, *SAMPLED, *extra, reuse=True, check=True)
            e = stress_l1(stress(r.directory, 1), ref if case == 1 else None)
            rows.append(dict(case=case, degree=p, cells=n, l1_error=e, cpu_s=r.cpu_s,
                             cpu_march_s=max(r.cpu_s - setup[prm], 1e-3), time_loop_s=r.summary['time_loop_s'],
                             dof_updates_per_s=r.summary['dof_updates_per_s']))
            print('case %d P%d N = %d: L1 %.3e, cpu %.2f s, %.2f MDoF/s'
                  % (case, p, n, e, r.cpu_s, r.summary['dof_updates_per_s'] / 1e6))
    outputs.write_csv(os.path.join(base, 'work-precision.csv'), rows)


def indicators():
    base = os.path.join(OUT, 'hopper_indicators')
    common = SAMPLED + ('Output/output times=1',)
    choices = ('everywhere', 'kxrcf')
    rows = []
    for case in ('cone_30_25', 'wedge_30_25'):
        prm = 'prm/hopper_%s.prm' % case
        refs = [run(prm, os.path.join(base, '%s_reference_%s' % (case, k)), 'Limiter/indicator=' + k,
                    'Discretization/degree=2', 'Hopper/cells=1600', 'Time stepping/CFL number=0.2', *common,
                    reuse=True, check=True).directory for k in choices]
        for n, k in ((n, k) for n in (100, 200, 400) for k in choices):
            r = run(prm, os.path.join(base, '%s_%s_n%d' % (case, k, n)), 'Limiter/indicator=' + k,
                    'Hopper/cells=%d' % n, *common, reuse=True, check=True)
            for i, tau in ((1, '1'), (2, 'outlet')):  # stress-0001: tau = 1; stress-0002: the outlet
                e = [stress_l1(stress(r.directory, i), stress(d, i)) for d in refs]
                rows.append(dict(case=case, indicator=k, cells=n, tau=tau, l1_vs_reference_everywhere=e[0],
                                 l1_vs_reference_kxrcf=e[1], cpu_s=r.cpu_s))
                print('%s %s N = %d tau = %s: L1 %.3e / %.3e (references %s), cpu %.2f s'
                      % (case, k, n, tau, e[0], e[1], '/'.join(choices), r.cpu_s))
        print('%s: the references differ at the outlet by %.2e'
              % (case, stress_l1(stress(refs[0], 2), stress(refs[1], 2))))
    outputs.write_csv(os.path.join(base, 'whole-march.csv'), rows)


if __name__ == '__main__':
    {'range': march_range, 'precision': precision, 'indicators': indicators}[sys.argv[1]]()
