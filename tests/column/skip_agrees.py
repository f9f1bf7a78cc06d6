#!/usr/bin/python3
"""Skipping quiet cells changes no result: a column run with Time stepping/skip
tolerance = T equals the full computation (skip tolerance = 0).

usage: skip_agrees.py EXE PRM [--tolerance 1e-12] [--skip 1e-15] [--set Section/name=value ...]

Compares every profile-*.csv and final-profile.csv (the DG polynomials
sampled in every cell) and the rows of timeseries.csv and history.csv (one
per snapshot and per sample time: a run that skips steps must still write
each of them, with the full run's time, step counter and dt) of the two
runs, each column against its scale over the whole run (the largest |value|
of that column in any file of that kind of the full run: a velocity that has
decayed to 1e-13 is measured against the velocities the run had, not against
itself). The sign of a velocity of 1e-40 and what is computed from it
(sgn_v, strain_auxiliary: the Janssen strain for that sign field) are
round-off and not compared, nor are the counts of cells that round-off
decides (troubled, flagged and stuck cells); in the rows, differences within
their print resolution (12 digits) do not count. Prints one line per check, the fraction of cell updates skipped
and when the run came to rest (the stored output fails the test if they
change); the largest differences go to stderr.
"""
import argparse
import math
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import granular_run  # noqa: E402

ROUND_OFF_COLUMNS = {'sgn_v', 'strain_auxiliary'}
# counts of cells that round-off decides: the limiter's flags and the stuck
# cells ahead of the front (loads of 1e-30); a full run whose wall strain
# differs by one ulp differs in them as well
ROUND_OFF_COUNTS = {'troubled_cells', 'flagged_cells', 'stuck_cells'}

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


def print_unit(x):
    """One unit of the 12th significant digit of x (format %.12g)."""
    return 10 ** (math.floor(math.log10(abs(x))) - 11) if x else 0.


def worst_difference(files, ignore=ROUND_OFF_COLUMNS, resolution=False):
    """The largest difference of the files (names in full/ and skipping/),
    column by column against the column's scale over all of them, and
    where; inf when a file is missing or its shape differs. resolution:
    differences within the print resolution (12 digits) do not count."""
    missing = [f for f in files if not os.path.exists(os.path.join('skipping', f))]
    if missing:
        return float('inf'), f'skipping run lacks {missing}'
    tables = {f: (read(os.path.join('full', f)), read(os.path.join('skipping', f))) for f in files}
    scale = {}
    for (header, rows), _ in tables.values():
        for j, name in enumerate(header):
            scale[name] = max([scale.get(name, 0.)] + [abs(r[j]) for r in rows])
    worst, where = 0., '-'
    for f, ((h0, a0), (h1, a1)) in tables.items():
        if h0 != h1 or len(a0) != len(a1):
            return float('inf'), f'{f} differs in shape ({len(a0)} rows, {len(a1)} skipping)'
        for j, name in enumerate(h0):
            if name in ignore or scale[name] == 0:
                continue
            d = max((max(abs(x[j] - y[j]) - (max(print_unit(x[j]), print_unit(y[j]))
                                             if resolution else 0.), 0.)
                     for x, y in zip(a0, a1)), default=0.) / scale[name]
            if d > worst:
                worst, where = d, f'{f}:{name}'
    return worst, where


full = run('full', 0.)
skip = run('skipping', args.skip)
profiles = sorted(f for f in os.listdir('full') if f.endswith('profile.csv') or
                  (f.startswith('profile-') and f.endswith('.csv')))
print(f'profile files compared: {len(profiles)}')
worst, where = worst_difference(profiles)
print(f'skipping agrees with the full run to {args.tolerance:g} (run-scaled): '
      f'{"yes" if worst <= args.tolerance else "no"}')
print(f'largest profile difference {worst:.3e} in {where}', file=sys.stderr)
for f in ('timeseries.csv', 'history.csv'):
    worst_rows, where = worst_difference([f], ROUND_OFF_COUNTS, True)
    print(f'{f}: the same rows, agreeing to {args.tolerance:g}: '
          f'{"yes" if worst_rows <= args.tolerance else "no"}')
    print(f'largest {f} difference {worst_rows:.3e} in {where}', file=sys.stderr)
fraction = skip['diagnostics']['skipped_cell_updates']
print(f'cell updates skipped: {fraction:.2f}')
print(f'time steps: skipping {skip["n_time_steps"]}, full {full["n_time_steps"]}')
print(f'at rest from t = {skip.get("at_rest_from", "never")} (the full run: '
      f'{full.get("at_rest_from", "never")})')
print(f'skipped {fraction:.4f}', file=sys.stderr)
