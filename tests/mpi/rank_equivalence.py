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
import csv
import math
import os
import subprocess
import sys

exe, prm, ranks = sys.argv[1], sys.argv[2], [int(r) for r in sys.argv[3:]]


def read(path):
    with open(path) as f:
        rows = list(csv.reader(l for l in f if not l.startswith('#')))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


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
        h0, a = read(os.path.join(ref, name))
        h1, b = read(os.path.join(dirs[n], name))
        if h0 != h1 or len(a) != len(b):
            sys.exit(f'rank_equivalence: {name} differs in shape on {n} ranks')
        worst, where, raw = 0., '-', 0.
        for j, col in enumerate(h0):
            partners = [k for k, c in enumerate(h0) if c.rstrip('xy') == col.rstrip('xy')
                        and c[-2:] in ('_x', '_y')] or [j]
            scale = max(abs(r[k]) for r in a for k in partners)
            if scale == 0:
                scale = 1.
            for r, q in zip(a, b):
                diff = abs(r[j] - q[j])
                raw = max(raw, diff / scale)
                # one unit of the 12th significant digit (format %.12g)
                unit = max(10 ** (math.floor(math.log10(abs(x))) - 11) if x else 0.
                           for x in (r[j], q[j]))
                d = max(diff - unit, 0.) / scale
                if d > worst:
                    worst, where = d, col
        print(f'np{n} {name} = {worst:.3e}')
        print(f'np{n} {name}: beyond the print resolution {worst:.3e} ({where}); '
              f'column-scaled difference {raw:.3e}', file=sys.stderr)
