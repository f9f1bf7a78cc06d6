#!/usr/bin/python3
"""A chain of edges with the same flux through vertices without volume equals
the same problem on one line, to round-off.

usage: chain_equals_line.py EXE CHAIN_PRM [--tolerance 1e-12] [--set Section/name=value ...]

Runs CHAIN_PRM (Edges 1..3 of length 1: free -> Vertex 1 -> Vertex 2 -> free)
and the line: Edge 1 from free to free with length 3 and the chain's Edge 1
data, Edges 2 and 3 switched off. With an upwind flux and positive states the
vertex without volume takes the trace of its incoming edge, so every flux the
chain computes at a vertex is the flux the line computes at that face. Compares
the sampled DG solution of every snapshot, relative to max |u|: the profile
files carry 12 significant digits, so 1e-12 is what the comparison resolves
(degree 0 agrees exactly; degree 2 differs in the printed last digit only).
"""
import argparse
import glob
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import granular_run  # noqa: E402

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
a.add_argument('--tolerance', type=float, default=1e-12)
a.add_argument('--set', action='append', default=[])
args = a.parse_args()

LINE = ['Network/Edge 1/to=free', 'Network/Edge 1/length=3',
        'Network/Edge 2/from=none', 'Network/Edge 2/to=none',
        'Network/Edge 3/from=none', 'Network/Edge 3/to=none']


def values(path):
    """the u column of a profile CSV"""
    with open(path) as f:
        rows = [line.split(',') for line in f if not line.startswith('#')]
    column = rows[0].index('u')
    return [float(r[column]) for r in rows[1:]]


chain = granular_run.run(args.exe, args.prm, 'chain', args.set, 'chain')
line = granular_run.run(args.exe, args.prm, 'line', args.set + LINE, 'line')
print('time steps equal:', 'yes' if chain['n_time_steps'] == line['n_time_steps'] else 'no')
worst = 0.
snapshots = sorted(glob.glob('line/profile-*-edge-1.csv'))
for path in snapshots:
    index = os.path.basename(path).split('-')[1]
    u_line = values(path)
    u_chain = []
    for k in (1, 2, 3):
        u_chain += values(f'chain/profile-{index}-edge-{k}.csv')
    if len(u_chain) != len(u_line):
        sys.exit(f'snapshot {index}: {len(u_chain)} chain samples, {len(u_line)} on the line')
    scale = max(abs(u) for u in u_line)
    worst = max(worst, max(abs(a - b) for a, b in zip(u_chain, u_line)) / scale)
print(f'{len(snapshots)} snapshots, chain = line to {args.tolerance:g} relative:',
      'yes' if worst <= args.tolerance else 'no')
print(f'largest difference {worst:.3e}', file=sys.stderr)
