#!/usr/bin/python3
"""The two engines discretise alike: a 1D case run with the lean line engine
and with MatrixFree (Discretization/engine = line | matrix_free) must give
the same outputs up to round-off.

usage: engines_agree.py EXE PRM [--tolerance T] [--set Section/name=value ...]

Compares the solution the two runs wrote, every profile-*.csv (the DG
polynomials sampled in every cell; tests/common/csv_compare.py:
column-scaled, beyond the print resolution), and prints one line per check;
the test compares them with the stored output. Diagnostics that are
round-off themselves (a mass-balance residual of 1e-16, the sign of a
velocity of 1e-40) are not compared. The largest difference goes to stderr.
"""
import argparse
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import csv_compare  # noqa: E402
import granular_run  # noqa: E402

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
a.add_argument('--tolerance', type=float, default=1e-11)
a.add_argument('--set', action='append', default=[])
args = a.parse_args()

for engine in ('line', 'matrix_free'):
    granular_run.run(args.exe, args.prm, engine, [f'Discretization/engine={engine}'] + args.set)

files = sorted(f for f in os.listdir('line') if f.startswith('profile-') and f.endswith('.csv'))
worst, where = 0., '-'
for f in files:
    d = csv_compare.difference(os.path.join('line', f), os.path.join('matrix_free', f))
    if d is None:
        print(f'{f}: differs in shape')
        worst = float('inf')
        continue
    if d[0] > worst or where == '-':
        worst, where = d[0], f + ':' + d[2]
print(f'CSV files compared: {len(files)}')
print(f'engines agree to {args.tolerance:g} (column-scaled): {"yes" if worst <= args.tolerance else "no"}')
print(f'largest difference {worst:.3e} in {where}', file=sys.stderr)
