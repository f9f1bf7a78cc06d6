#!/usr/bin/python3
"""Extra runs behind two hopper figures and a table (doc/hopper.md), written
to OUTPUT_DIR (default output/):

  /usr/bin/python3 contrib/hopper_runs.py range [BUILD]       # Fig. 9 bar
  /usr/bin/python3 contrib/hopper_runs.py precision [BUILD]   # work-precision
  /usr/bin/python3 contrib/hopper_runs.py indicators [BUILD]  # 4.7's last table

range: 30 deg cone to lower angles theta_w in RANGE_ANGLES, P1, N = 400, marched
  to r = 0.05 r0; output/hopper_march_range/range.csv says which completed.
precision: P1-P3 on several meshes, (a) the 30 deg cone's radial field at
  tau = 1 against the exact field, (b) the 30 -> 25 deg cone at tau = 0.5
  against P3 on N = 800, (c) as (a) without the limiter; relative L1 error of (T_rr, T_rtheta) at 2001
  equidistant theta and the CPU time (user + system of the run, and minus
  that of a one-step run: the march);
  output/hopper_work_precision/work-precision.csv.
indicators: the whole march (to r = 0.05 r0) of the cone and wedge 30 -> 25
  as shipped (P1, CFL 1/3) on N = 100, 200, 400 with the limiter in every
  cell and with the kxrcf indicator, against P2 N = 1600 references run with
  each of the two (CFL 1/5); the error at tau = 1 and at the outlet, and the
  CPU time of the run; output/hopper_indicators/whole-march.csv. About 40 min
  of CPU, most of it the four references.
BUILD is the build directory with granular_dg (default build).
"""
import csv
import os
import resource
import subprocess
import sys

import numpy as np

mode = sys.argv[1]
build = sys.argv[2] if len(sys.argv) > 2 else 'build'
exe = os.path.join(build, 'granular_dg')
OUT = os.environ.get('OUTPUT_DIR', 'output')
RANGE_ANGLES = [18.5, 19, 20, 21, 21.5, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 31.5, 32, 33]


def run(prm, directory, *sets, reuse=False):
    """Run the program; with reuse, a completed run in directory (with its
    cpu_s.txt) is not repeated."""
    done = os.path.join(directory, 'cpu_s.txt')
    if reuse and os.path.exists(done):
        return 0, float(open(done).read()), ''
    cmd = [exe, prm, '--set', 'Output/overwrite=true', '--set', 'Output/directory=' + directory,
           '--set', 'Output/progress interval=0']
    for s in sets:
        cmd += ['--set', s]
    before = resource.getrusage(resource.RUSAGE_CHILDREN)
    p = subprocess.run(cmd, capture_output=True, text=True)
    after = resource.getrusage(resource.RUSAGE_CHILDREN)
    cpu = (after.ru_utime - before.ru_utime) + (after.ru_stime - before.ru_stime)
    if p.returncode == 0:
        with open(done, 'w') as f:
            f.write('%.6f\n' % cpu)
    return p.returncode, cpu, p.stderr.strip()


def read_csv(path):
    with open(path) as f:
        skip = 1 if f.readline().startswith('#') else 0
    return np.genfromtxt(path, delimiter=',', names=True, skip_header=skip)


def march_range():
    base = os.path.join(OUT, 'hopper_march_range')
    os.makedirs(base, exist_ok=True)
    rows = []
    for a in RANGE_ANGLES:
        d = os.path.join(base, 'theta_%g' % a)
        code, cpu, err = run('prm/hopper_cone_30_25.prm', d, 'Hopper/lower half-angle=%g' % a,
                             'Output/write vtu=false', 'Hopper output/step series interval=0',
                             'Output/output times=')
        import json
        s = json.load(open(os.path.join(d, 'summary.json')))
        diag = s.get('diagnostics', {})
        rows.append([a, 1 if code == 0 else 0, s.get('final_time', 0),
                     diag.get('min_hyperbolicity_margin', float('nan')), cpu])
        print('theta_w = %g: exit %d, tau = %s %s' % (a, code, s.get('final_time'), err[:160]))
    with open(os.path.join(base, 'range.csv'), 'w') as f:
        w = csv.writer(f)
        w.writerow(['theta_w', 'completed', 'final_tau', 'min_margin', 'cpu_s'])
        w.writerows(rows)


def l1(d, ref):
    num = np.abs(d['T_rr_over_r'] - ref[0]) + np.abs(d['T_rtheta_over_r'] - ref[1])
    den = np.abs(ref[0]) + np.abs(ref[1])
    return np.trapz(num, d['theta']) / np.trapz(den, d['theta'])


def precision():
    base = os.path.join(OUT, 'hopper_work_precision')
    os.makedirs(base, exist_ok=True)
    # CFL 1/(2k+1) (GM) for k = 1, 2; k = 3 is unstable at 1/7 (limit ~0.13, doc/hopper.md)
    cfl = {1: 1 / 3., 2: 1 / 5., 3: 0.12}
    meshes = {1: [50, 100, 200, 400], 2: [25, 50, 100, 200], 3: [25, 50, 100, 200]}
    rows = []
    common = ['Output/write vtu=false', 'Hopper output/step series interval=0',
              'Hopper output/sample points=2001']
    # (b)'s reference
    ref_dir = os.path.join(base, 'transition_reference')
    code, cpu, err = run('prm/hopper_cone_30_25.prm', ref_dir, 'Discretization/degree=3',
                         'Hopper/cells=800', 'Time stepping/CFL number=%.12g' % cfl[3],
                         'Time stepping/final time=0.5', 'Output/output times=', *common,
                         reuse=True)
    assert code == 0, err
    ref = read_csv(os.path.join(ref_dir, 'stress-0001.csv'))
    # the CPU time of start-up and set-up (a one-step run), subtracted below
    setup = {}
    for prm in ('prm/hopper_radial_cone.prm', 'prm/hopper_cone_30_25.prm'):
        d = os.path.join(base, 'setup_' + os.path.basename(prm)[:-4])
        setup[prm] = min(run(prm, d, 'Time stepping/final time=1e-9', 'Output/output times=',
                             *common)[1] for _ in range(3))
    for case, prm, final, extra in ((0, 'prm/hopper_radial_cone.prm', 1.0, []),
                                    (1, 'prm/hopper_cone_30_25.prm', 0.5, []),
                                    (2, 'prm/hopper_radial_cone.prm', 1.0,
                                     ['Limiter/scheme=none'])):
        for p, cells in meshes.items():
            for n in cells:
                d = os.path.join(base, 'case%d_p%d_n%d' % (case, p, n))
                code, cpu, err = run(prm, d, 'Discretization/degree=%d' % p,
                                     'Hopper/cells=%d' % n,
                                     'Time stepping/CFL number=%.12g' % cfl[p],
                                     'Time stepping/final time=%g' % final,
                                     'Output/output times=', *common, *extra, reuse=True)
                assert code == 0, err
                s = read_csv(os.path.join(d, 'stress-0001.csv'))
                if case != 1:
                    e = l1(s, (s['radial_T_rr_over_r'], s['radial_T_rtheta_over_r']))
                else:
                    e = l1(s, (ref['T_rr_over_r'], ref['T_rtheta_over_r']))
                import json
                loop = json.load(open(os.path.join(d, 'summary.json')))
                rows.append([case, p, n, e, cpu, max(cpu - setup[prm], 1e-3), loop['time_loop_s'],
                             loop['dof_updates_per_s']])
                print('case %d P%d N = %d: L1 %.3e, cpu %.2f s, %.2f MDoF/s'
                      % (case, p, n, e, cpu, loop['dof_updates_per_s'] / 1e6))
    with open(os.path.join(base, 'work-precision.csv'), 'w') as f:
        w = csv.writer(f)
        w.writerow(['case', 'degree', 'cells', 'l1_error', 'cpu_s', 'cpu_march_s', 'time_loop_s',
                    'dof_updates_per_s'])
        w.writerows(rows)


def indicators():
    base = os.path.join(OUT, 'hopper_indicators')
    os.makedirs(base, exist_ok=True)
    common = ['Output/write vtu=false', 'Hopper output/step series interval=0',
              'Hopper output/sample points=2001', 'Output/output times=1']
    choices = ('everywhere', 'kxrcf')
    rows = []
    for case in ('cone_30_25', 'wedge_30_25'):
        prm = 'prm/hopper_%s.prm' % case
        refs = {}
        for k in choices:
            refs[k] = os.path.join(base, '%s_reference_%s' % (case, k))
            code, cpu, err = run(prm, refs[k], 'Limiter/indicator=' + k, 'Discretization/degree=2',
                                 'Hopper/cells=1600', 'Time stepping/CFL number=0.2', *common,
                                 reuse=True)
            assert code == 0, err
        for n in (100, 200, 400):
            for k in choices:
                d = os.path.join(base, '%s_%s_n%d' % (case, k, n))
                code, cpu, err = run(prm, d, 'Limiter/indicator=' + k, 'Hopper/cells=%d' % n,
                                     *common, reuse=True)
                assert code == 0, err
                # stress-0001: tau = 1; stress-0002: the outlet
                for i, tau in ((1, '1'), (2, 'outlet')):
                    s = read_csv(os.path.join(d, 'stress-%04d.csv' % i))
                    e = [l1(s, (r['T_rr_over_r'], r['T_rtheta_over_r']))
                         for r in (read_csv(os.path.join(refs[c], 'stress-%04d.csv' % i))
                                   for c in choices)]
                    rows.append([case, k, n, tau, *e, cpu])
                    print('%s %s N = %d tau = %s: L1 %.3e / %.3e (references %s), cpu %.2f s'
                          % (case, k, n, tau, e[0], e[1], '/'.join(choices), cpu))
        r = [read_csv(os.path.join(refs[c], 'stress-0002.csv')) for c in choices]
        print('%s: the references differ at the outlet by %.2e'
              % (case, l1(r[0], (r[1]['T_rr_over_r'], r[1]['T_rtheta_over_r']))))
    with open(os.path.join(base, 'whole-march.csv'), 'w') as f:
        w = csv.writer(f)
        w.writerow(['case', 'indicator', 'cells', 'tau', 'l1_vs_reference_everywhere',
                    'l1_vs_reference_kxrcf', 'cpu_s'])
        w.writerows(rows)


if __name__ == '__main__':
    {'range': march_range, 'precision': precision, 'indicators': indicators}[mode]()
