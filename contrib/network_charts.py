#!/usr/bin/python3
"""Charts of the network studies (contrib/network_studies.sh writes their
convergence.csv files):

  work-precision: L1 error against CPU time for degrees 0-3 on Examples 7.3
                  and 7.5, grid levels 3-12;
  eoc:            L1 error against the grid level for the five examples at
                  degree 0 (the paper's scheme), with twice the values of the
                  paper's Table 1 for comparison;
  smooth:         L1 error against the grid level for the smooth case, per
                  degree, with the paper's vertex cell and without volume.

  /usr/bin/python3 contrib/network_charts.py STUDIES_DIR FIGURE_DIR
  /usr/bin/python3 contrib/network_charts.py STUDIES_DIR --tables   # doc/network.md's tables
"""
import csv
import math
import os
import sys

import matplotlib

matplotlib.use('Agg')
import matplotlib.pyplot as plt  # noqa: E402

# Table 1 of Musch, Fjordholm & Risebro, levels 3-12, as printed
TABLE_1 = {
    '7.1': [0.07087, 0.0546, 0.03117, 0.01903, 0.01115, 0.00644, 0.00330, 0.00173, 0.00085, 0.00042],
    '7.2': [0.09904, 0.04913, 0.02844, 0.01627, 0.00919, 0.00527, 0.00268, 0.00150, 0.00084, 0.00047],
    '7.3': [0.10877, 0.05496, 0.03649, 0.02629, 0.01830, 0.01255, 0.00883, 0.00625, 0.00442, 0.00312],
    '7.4': [0.14459, 0.08016, 0.04651, 0.02711, 0.01495, 0.00925, 0.00480, 0.00295, 0.00152, 0.00081],
    '7.5': [0.11630, 0.07136, 0.04372, 0.02255, 0.01360, 0.00653, 0.00325, 0.00160, 0.00086, 0.00040],
}
COLORS = ['tab:blue', 'tab:orange', 'tab:green', 'tab:red']


def read(path):
    with open(path) as f:
        rows = list(csv.DictReader(l for l in f if not l.startswith('#')))
    return [{k: float(v) for k, v in r.items()} for r in rows]


def by_degree(rows):
    out = {}
    for r in rows:
        out.setdefault(int(r['degree']), []).append(r)
    return out


def work_precision(studies, figures):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2))
    for ax, ex in zip(axes, ['7_3', '7_5']):
        rows = by_degree(read(os.path.join(studies, 'example_%s' % ex, 'convergence.csv')))
        for p, rs in sorted(rows.items()):
            ax.loglog([r['cpu_time_s'] for r in rs], [r['l1_error'] for r in rs], 'o-',
                      color=COLORS[p], ms=4,
                      label='degree %d%s' % (p, ' (paper: FV, Euler)' if p == 0 else ''))
            last = rs[-1]
            ax.annotate('l=%d' % last['level'], (last['cpu_time_s'], last['l1_error']),
                        fontsize=7, xytext=(3, -8), textcoords='offset points')
        ax.set_xlabel('CPU time of the time loop [s]')
        ax.set_ylabel('L1 error (edges + vertex) at T')
        ax.set_title('Example %s' % ex.replace('_', '.'))
        ax.grid(alpha=0.3, which='both')
        ax.legend(fontsize=8)
    fig.suptitle('Work precision, grid levels 3-12 (DG: SSPRK3, minmod limiter, '
                 'CFL 0.3 / 0.18 / 0.1)', fontsize=10)
    fig.tight_layout()
    path = os.path.join(figures, 'network_work_precision.png')
    fig.savefig(path, dpi=130)
    print('wrote ' + path)


def eoc(studies, figures):
    fig, axes = plt.subplots(1, 5, figsize=(16, 3.6), sharey=True)
    for ax, ex in zip(axes, ['7.1', '7.2', '7.3', '7.4', '7.5']):
        rows = by_degree(read(os.path.join(studies, 'example_%s' % ex.replace('.', '_'),
                                           'convergence.csv')))[0]
        levels = [r['level'] for r in rows]
        ax.semilogy(levels, [r['l1_error'] for r in rows], 'o-', ms=4, label='true L1 (ours)')
        ax.semilogy(range(3, 13), [2 * v for v in TABLE_1[ex]], 'k--', lw=1,
                    label='2 x Table 1')
        ax.semilogy(range(3, 13), TABLE_1[ex], 'k:', lw=1, label='Table 1')
        ax.set_title('Example %s' % ex)
        ax.set_xlabel('grid level l (dx = 2^-l)')
        ax.grid(alpha=0.3, which='both')
    axes[0].set_ylabel('L1 error at T')
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(figures, 'network_eoc.png')
    fig.savefig(path, dpi=130)
    print('wrote ' + path)


def smooth(studies, figures):
    fig, axes = plt.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, w, title in zip(axes, ['1', '0'],
                            ['vertex cell of width N dx/2 (the paper)',
                             'vertex without volume (Rankine-Hugoniot solved)']):
        rows = by_degree(read(os.path.join(studies, 'smooth_width_%s' % w, 'convergence.csv')))
        for p, rs in sorted(rows.items()):
            dx = [r['dx'] for r in rs]
            ax.loglog(dx, [r['l1_error'] for r in rs], 'o-', color=COLORS[p], ms=4,
                      label='degree %d' % p)
            # split: ingoing edges (upstream of the vertex) dashed
            ax.loglog(dx, [r['l1_error_edge_1'] + r['l1_error_edge_2'] for r in rs], ':',
                      color=COLORS[p], lw=1)
        ax.set_xlabel('dx')
        ax.set_title(title, fontsize=10)
        ax.grid(alpha=0.3, which='both')
    axes[0].set_ylabel('L1 error at T (solid: all, dotted: ingoing edges)')
    axes[0].legend(fontsize=8)
    fig.tight_layout()
    path = os.path.join(figures, 'network_smooth_order.png')
    fig.savefig(path, dpi=130)
    print('wrote ' + path)


def tables(studies):
    """The markdown tables of doc/network.md."""
    names = ['7.1', '7.2', '7.3', '7.4', '7.5']
    data = {ex: by_degree(read(os.path.join(studies, 'example_%s' % ex.replace('.', '_'),
                                            'convergence.csv')))
            for ex in names}
    print('| level | ' + ' | '.join('%s L1 | EOC | ratio' % ex for ex in names) + ' |')
    print('|---' * (1 + 3 * len(names)) + '|')
    for i in range(10):
        cells = []
        for ex in names:
            r = data[ex][0][i]
            eoc = '-' if r['eoc'] != r['eoc'] else '%.2f' % r['eoc']
            cells.append('%.4e | %s | %.2f' % (r['l1_error'], eoc, r['l1_error'] / TABLE_1[ex][i]))
        print('| %d | ' % (i + 3) + ' | '.join(cells) + ' |')
    print()
    for ex in ['7.3', '7.5']:
        print('Example %s' % ex)
        print('| degree | CFL | L1 level 8 | L1 level 12 | EOC 8/7 | EOC 12/11 | steps l=12 '
              '| CPU s l=12 | mass residual max |')
        print('|---' * 9 + '|')
        for p, rs in sorted(data[ex].items()):
            r8, r12 = rs[5], rs[9]
            print('| %d | %g | %.4e | %.4e | %.2f | %.2f | %d | %.1f | %.1e |' % (
                p, r8['cfl'], r8['l1_error'], r12['l1_error'], r8['eoc'], r12['eoc'],
                r12['time_steps'], r12['cpu_time_s'],
                max(r['mass_balance_residual_max'] for r in rs)))
        print()
    for w in ['1', '0']:
        rows = by_degree(read(os.path.join(studies, 'smooth_width_%s' % w, 'convergence.csv')))
        print('smooth, vertex width factor %s' % w)
        print('| degree | L1 level 9 | EOC all edges | EOC ingoing edges | EOC outgoing edges |')
        print('|---' * 5 + '|')
        for p, rs in sorted(rows.items()):
            a, b = rs[-2], rs[-1]

            def rate(key):
                return math.log2(sum(a[k] for k in key) / sum(b[k] for k in key))
            print('| %d | %.3e | %.2f | %.2f | %.2f |' % (
                p, b['l1_error'], rate(['l1_error']),
                rate(['l1_error_edge_1', 'l1_error_edge_2']),
                rate(['l1_error_edge_3', 'l1_error_edge_4', 'l1_error_edge_5'])))
        print()


if __name__ == '__main__':
    studies = sys.argv[1]
    if sys.argv[2] == '--tables':
        tables(studies)
        sys.exit(0)
    figures = sys.argv[2]
    eoc(studies, figures)
    work_precision(studies, figures)
    smooth(studies, figures)
