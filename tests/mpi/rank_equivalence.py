#!/usr/bin/python3
"""Runs one case on 1, 2, ... MPI ranks and compares what they wrote.

usage: rank_equivalence.py EXE PRM RANKS...   (run in an empty directory)

For every CSV file the one-rank run wrote (timeseries.csv, slice-NNNN.csv)
and every other rank count, prints per file

    max_ij (|a_ij - b_ij| - u_ij)+ / s_j

with s_j the scale of column j: max_i |a_ij| over the column and its vector
partners (columns named alike but for a trailing _x/_y: a velocity or
momentum component that vanishes by symmetry is measured against the
vector's size, not its own round-off), and u_ij one unit in the last
(12th) significant digit the CSV files print of a_ij and b_ij: differences
below the print resolution are not differences. The raw column-scaled
difference max |a - b| / s_j and its column go to stderr. The test
compares the printed numbers with 0 at the tolerance of its tests.cmake.
"""
import os
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import csv_compare  # noqa: E402

exe, prm, ranks = sys.argv[1], sys.argv[2], [int(r) for r in sys.argv[3:]]


def run(n):
    out = f'out-np{n}'
    cmd = ['mpirun', '--allow-run-as-root', '--oversubscribe', '-np', str(n), exe, prm,
           '--set', f'Output/directory={out}', '--set', 'Output/progress interval=0']
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f'rank_equivalence: {" ".join(cmd)} exited with {p.returncode}:\n{p.stderr}')
    return out


dirs = {n: run(n) for n in ranks}
ref = dirs[ranks[0]]
files = sorted(f for f in os.listdir(ref) if f.endswith('.csv'))
if not files:
    sys.exit('rank_equivalence: no CSV output to compare')
for n in ranks[1:]:
    for name in files:
        result = csv_compare.difference(os.path.join(ref, name), os.path.join(dirs[n], name))
        if result is None:
            sys.exit(f'rank_equivalence: {name} differs in shape on {n} ranks')
        worst, raw, where = result
        print(f'np{n} {name} = {worst:.3e}')
        print(f'np{n} {name}: beyond the print resolution {worst:.3e} ({where}); '
              f'column-scaled difference {raw:.3e}', file=sys.stderr)
