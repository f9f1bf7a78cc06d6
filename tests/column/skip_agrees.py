#!/usr/bin/python3
"""Skipping quiet cells changes no result: a column run with Time stepping/skip
tolerance = T equals the full computation (skip tolerance = 0).

usage: skip_agrees.py EXE PRM [--tolerance 1e-12] [--skip 1e-15] [--set Section/name=value ...]

Compares every profile-*.csv and final-profile.csv (the DG polynomials
sampled in every cell) of the two runs, each column against its scale over
the whole run (the largest |value| of that column in any snapshot of the full
run: a velocity that has decayed to 1e-13 is measured against the velocities
the run had, not against itself). The sign of a velocity of 1e-40 and what is
computed from it (sgn_v, strain_auxiliary: the Janssen strain for that sign
field) are round-off and not compared. Prints one line per check and the
fraction of cell updates skipped and when the run came to rest (the stored
output fails the test if they change); the largest difference goes to stderr.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import granular_run  # noqa: E402

ROUND_OFF_COLUMNS = {'sgn_v', 'strain_auxiliary'}

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
a.add_argument('--tolerance', type=float, default=1e-12)
a.add_argument('--skip', type=float, default=1e-15)
a.add_argument('--set', action='append', default=[])
args = a.parse_args()


def run(name, skip):
    return granular_run.run(args.exe, args.prm, name, [f'Time stepping/skip tolerance={skip:g}'] + args.set)


def read(path):
    with open(path) as f:
        rows = [l.strip().split(',') for l in f if not l.startswith('#')]
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


full = run('full', 0.)
skip = run('skipping', args.skip)
files = sorted(f for f in os.listdir('full') if f.endswith('profile.csv') or
               (f.startswith('profile-') and f.endswith('.csv')))
missing = [f for f in files if not os.path.exists(os.path.join('skipping', f))]
if missing:
    sys.exit(f'skipping run lacks {missing}')
tables = {f: (read(os.path.join('full', f)), read(os.path.join('skipping', f))) for f in files}
scale = {}
for (header, rows), _ in tables.values():
    for j, name in enumerate(header):
        scale[name] = max([scale.get(name, 0.)] + [abs(r[j]) for r in rows])
worst, where = 0., '-'
for f, ((h0, a0), (h1, a1)) in tables.items():
    if h0 != h1 or len(a0) != len(a1):
        print(f'{f}: differs in shape')
        worst = float('inf')
        continue
    for j, name in enumerate(h0):
        if name in ROUND_OFF_COLUMNS or scale[name] == 0:
            continue
        d = max(abs(x[j] - y[j]) for x, y in zip(a0, a1)) / scale[name]
        if d > worst:
            worst, where = d, f'{f}:{name}'
print(f'profile files compared: {len(files)}')
print(f'skipping agrees with the full run to {args.tolerance:g} (run-scaled): '
      f'{"yes" if worst <= args.tolerance else "no"}')
fraction = skip['diagnostics']['skipped_cell_updates']
print(f'cell updates skipped: {fraction:.2f}')
print(f'steps: skipping {"<" if skip["n_time_steps"] < full["n_time_steps"] else "="} full')
print(f'at rest from t = {skip.get("at_rest_from", "never")} (the full run: '
      f'{full.get("at_rest_from", "never")})')
print(f'largest difference {worst:.3e} in {where}; skipped {fraction:.4f}', file=sys.stderr)
