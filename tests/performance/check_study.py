#!/usr/bin/python3
"""Smoke test of the study driver: runs `contrib/study.py BUILD OUT --quick`
(the quick variant: two meshes, one or two degrees and choices per scene,
every chart kind) and checks what it wrote: every chart as PNG and SVG with
its CSV, the stability limits table, the failure notes, every stability run
classified into one of the documented states, the stability maps' limits
found, and the failure modes' runs present. It prints only what does not
vary between machines (file names and checks, no errors, limits or times;
the study itself is never timed here).

    check_study.py --study=contrib/study.py --exe=GRANULAR_DG [--set Output/directory=OUT ...]
"""
import csv
import os
import subprocess
import sys

opts = dict(a[2:].split('=', 1) for a in sys.argv[1:] if a.startswith('--') and '=' in a)
sets = [sys.argv[i + 1] for i, a in enumerate(sys.argv[:-1]) if a == '--set']
out = [s.split('=', 1)[1] for s in sets if s.startswith('Output/directory=')][-1]
build = os.path.dirname(os.path.abspath(opts['exe']))
p = subprocess.run(['/usr/bin/python3', opts['study'], build, out, '--quick', '--jobs', '2'],
                   capture_output=True, text=True)
if p.returncode != 0:
    sys.stdout.write(p.stdout[-3000:])
    sys.exit('study.py --quick exited with %d: %s' % (p.returncode, p.stderr[-3000:]))


def rows(name):
    with open(os.path.join(out, name)) as f:
        return list(csv.DictReader(f))


good = True


def check(what, ok):
    global good
    print('%s: %s' % (what, 'ok' if ok else 'FAILED'))
    good &= bool(ok)


charts = ['%s-work-precision' % s for s in ('column', 'layered_1d', 'layered_2d', 'network', 'hopper')]
charts += ['%s-stability' % m for m in ('layered_1d', 'layered_interfaces', 'column', 'network')]
charts += ['failure-%s' % f for f in ('interfaces', 'friction', 'rk3', 'shock', 'hopper')]
for c in charts:
    check(c + '.png/.svg/.csv written and not empty',
          all(os.path.getsize(os.path.join(out, c + ext)) > 0 for ext in ('.png', '.svg', '.csv')))
for f in ('cheapest.md', 'stability-limits.csv', 'stability-limits.md', 'failures.md', 'runtime.txt'):
    check(f + ' written', os.path.getsize(os.path.join(out, f)) > 0)

states = {'stable', 'oscillatory', 'inadmissible', 'blown up'}
for m in ('layered_1d', 'layered_interfaces', 'column', 'network'):
    r = rows(m + '-stability.csv')
    check('%s-stability: every run classified (%s)' % (m, ', '.join(sorted(states))),
          r and all(x['state'] in states for x in r))
limits = rows('stability-limits.csv')
check('stability-limits: a limit for every (map, choice, degree)',
      limits and all(l['cfl_limit'] != '' for l in limits))
# the linear wave without limiter: unstable just above SSP-RK3's linear limit
lin = [l for l in limits if l['map'] == 'layered_1d']
check('layered_1d: limit within 15 % below to 10 % above the linear RK3-DG limit',
      lin and all(0.85 <= float(l['limit_over_linear']) <= 1.1 for l in lin))
r = rows('failure-interfaces.csv')
check('failure-interfaces: naive and aware runs at two resolutions',
      {x['flux'] for x in r} == {'local_lax_friedrichs', 'impedance'} and
      len({x['cells_per_layer'] for x in r}) == 2)
r = rows('failure-friction.csv')
check('failure-friction: the projection keeps stuck material at rest (0 sign flips)',
      all(float(x['velocity_sign_flips']) == 0 for x in r if x['friction'] == 'projection'))
r = rows('failure-shock.csv')
check('failure-shock: limited and unlimited runs completed',
      len(r) == 2 and all(x['exit'] == '0' for x in r))
r = rows('failure-hopper.csv')
check('failure-hopper: every transition run ended with exit 0 or 3',
      r and all(x['exit'] in ('0', '3') for x in r))
with open(os.path.join(out, 'failures.md')) as f:
    text = f.read()
check('failures.md names every mode',
      all('**%s**' % m in text for m in ('interfaces', 'friction', 'rk3', 'shock', 'hopper')))
sys.exit(0 if good else 1)
