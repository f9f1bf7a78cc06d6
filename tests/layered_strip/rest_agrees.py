#!/usr/bin/python3
"""Leaving out the cells at rest changes no result: a 2D run with Time
stepping/skip cells at rest = true equals the full computation.

usage: rest_agrees.py EXE PRM (--bitwise | --tolerance T) [--skip S] [--set Section/name=value ...]

Runs PRM twice, in full (skip cells at rest = false) and with skip cells at
rest = true and rest tolerance = S (default 0), and compares every CSV file the full run wrote
(timeseries.csv, slice-NNNN.csv) and the numbers of summary.json's
diagnostics (what the skipping run adds, skipped_cell_updates, aside):
--bitwise: the files are byte for byte the same (rest tolerance 0: the cells
left out are exactly at rest, and their rate is exactly zero);
--tolerance T: every column agrees to T times its scale (the largest |value|
of the column over the full run; a velocity component that vanishes by
symmetry against its vector partner's: tests/common/csv_compare.py).
Prints one line per check and the fraction of cell updates left out (2
digits: the stored output fails the test when the skipping stops paying), or
with --min-skipped F whether it is at least F (the fraction itself on
stderr): where cells are skipped in SIMD batches of cells, as in 2D, the
fraction depends on the batch width of the machine (0.64 at 4 lanes, 0.63 at
8 on the strip below).
"""
import argparse
import filecmp
import json
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import csv_compare  # noqa: E402
import granular_run  # noqa: E402

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
mode = a.add_mutually_exclusive_group(required=True)
mode.add_argument('--bitwise', action='store_true')
mode.add_argument('--tolerance', type=float)
a.add_argument('--skip', type=float, default=0.)
a.add_argument('--min-skipped', type=float)
a.add_argument('--set', action='append', default=[])
args = a.parse_args()

full = granular_run.run(args.exe, args.prm, 'full',
                        args.set + ['Time stepping/skip cells at rest=false'], label='full')
rest = granular_run.run(args.exe, args.prm, 'rest',
                        args.set + ['Time stepping/skip cells at rest=true',
                                    f'Time stepping/rest tolerance={args.skip:g}'],
                        label='skipping cells at rest')
files = sorted(f for f in os.listdir('full') if f.endswith('.csv'))
if not files:
    sys.exit('rest_agrees: the full run wrote no CSV file')
for name in files:
    a_path, b_path = os.path.join('full', name), os.path.join('rest', name)
    if args.bitwise:
        same = os.path.exists(b_path) and filecmp.cmp(a_path, b_path, shallow=False)
        print(f'{name}: byte for byte the same: {"yes" if same else "no"}')
        continue
    result = csv_compare.difference(a_path, b_path)
    if result is None:
        print(f'{name}: differs in shape')
        continue
    worst, raw, where = result
    print(f'{name}: agrees to {args.tolerance:g} (column-scaled): {"yes" if raw <= args.tolerance else "no"}')
    print(f'{name}: column-scaled difference {raw:.3e} ({where})', file=sys.stderr)

skipped = rest['diagnostics'].pop('skipped_cell_updates')
a_diag = {k: v for k, v in full['diagnostics'].items() if isinstance(v, (int, float))}
b_diag = {k: v for k, v in rest['diagnostics'].items() if isinstance(v, (int, float))}
if args.bitwise:
    same = a_diag == b_diag
else:
    # each number against itself or, for a vector component, the vector's size
    names = list(a_diag)
    same = a_diag.keys() == b_diag.keys() and all(
        abs(a_diag[k] - b_diag[k]) <=
        args.tolerance * max(abs(a_diag[names[i]]) for i in csv_compare.partners(names, j))
        for j, k in enumerate(names))
print(f'summary.json diagnostics the same{"" if args.bitwise else " to the tolerance"}: '
      f'{"yes" if same else "no"}')
print(f'steps: {rest["n_time_steps"]} (full run: {full["n_time_steps"]})')
if args.min_skipped is None:
    print(f'cell updates left out: {skipped:.2f}')
else:
    print(f'cell updates left out: {skipped:.2f}', file=sys.stderr)
    print(f'cell updates left out at least {args.min_skipped:g}: '
          f'{"yes" if skipped >= args.min_skipped else "no"}')
