#!/usr/bin/python3
"""Plots the edge profiles of a network run (profile-NNNN-edge-K.csv, with
the exact solution when the run had one): one panel per edge, numerical
solution against exact, the vertex value marked at the vertex end.

  /usr/bin/python3 contrib/network_plot_profiles.py OUTPUT_DIR PNG [--snapshot N] [--title T]
"""
import argparse
import csv
import glob
import os
import re

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402


def read_profile(path):
    comments, rows = [], []
    with open(path) as f:
        lines = f.readlines()
    body = [l for l in lines if not l.startswith('#')]
    comments = [l[1:].strip() for l in lines if l.startswith('#')]
    reader = csv.DictReader(body)
    for r in reader:
        rows.append({k: float(v) for k, v in r.items()})
    return comments, rows


def main():
    p = argparse.ArgumentParser()
    p.add_argument('directory')
    p.add_argument('png')
    p.add_argument('--snapshot', type=int, default=-1, help='index (default: the last)')
    p.add_argument('--title', default='')
    a = p.parse_args()
    files = sorted(glob.glob(os.path.join(a.directory, 'profile-*-edge-*.csv')))
    snapshots = sorted({int(re.search(r'profile-(\d+)-edge', f).group(1)) for f in files})
    snap = snapshots[a.snapshot]
    edges = sorted((f for f in files if '-%04d-edge-' % snap in f),
                   key=lambda f: int(re.search(r'edge-(\d+)\.csv', f).group(1)))
    fig, axes = plt.subplots(1, len(edges), figsize=(3.1 * len(edges), 2.9), sharey=True)
    time = ''
    for ax, path in zip(axes, edges):
        comments, rows = read_profile(path)
        time = comments[0].split('=')[1].strip()
        info = comments[1]
        label, rest = info.split(':', 1)
        direction = rest.split(',')[0].strip()
        vertex = float(re.search(r'vertex value ([-+0-9.eE]+)', info).group(1))
        x = [r['x'] for r in rows]
        if 'exact' in rows[0]:
            ax.plot(x, [r['exact'] for r in rows], 'k-', lw=1.0, label='exact')
        ax.plot(x, [r['u'] for r in rows], '-', color='tab:blue', lw=1.2, label='numerical')
        # the vertex cell at the vertex end of the edge
        ends = []
        if direction in ('in', 'loop'):
            ends.append(max(x))
        if direction in ('out', 'loop'):
            ends.append(min(x))
        for e in ends:
            ax.plot([e], [vertex], 'o', color='tab:red', ms=5, label='vertex $u_0$')
        ax.set_title('%s (%s)' % (label.strip(), direction), fontsize=9)
        ax.set_xlabel('x')
        ax.grid(alpha=0.3)
    axes[0].set_ylabel('u')
    axes[0].legend(fontsize=7, loc='best')
    fig.suptitle((a.title + ', ' if a.title else '') + 't = ' + time, fontsize=10)
    fig.tight_layout()
    fig.savefig(a.png, dpi=130)
    print('wrote ' + a.png)


if __name__ == '__main__':
    main()
