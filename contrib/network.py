#!/usr/bin/python3
"""The network scene's studies, tables and figures (doc/network.md,
"Reproducing the tables and figures"); BUILD: the build directory, STUDIES:
the studies' directory (default output/network_studies):

  network.py studies [BUILD [STUDIES]]   the EOC tables of the five examples of Musch,
      Fjordholm & Risebro, Section 7, at grid levels 3-12 (degree 0, the paper's
      scheme) and for Examples 7.3 and 7.5 degrees 1-3 with the limiter; the smooth
      order study (all of them about 2.5 min of CPU, doc/network.md);
  network.py tables [STUDIES]            doc/network.md's tables (markdown);
  network.py charts STUDIES FIGURE_DIR   network_eoc.png (L1 error against the level at
      degree 0 beside the paper's Table 1 and twice it), network_work_precision.png
      (degrees 0-3 on Examples 7.3 and 7.5), network_smooth_order.png (the smooth case
      per degree, with the paper's vertex cell and without volume).
"""
import math
import os

from granular_dg import main, outputs, plot
from granular_dg.run import run_case
# Table 1 of Musch, Fjordholm & Risebro, levels 3-12, as printed
TABLE_1 = {
    '7.1': [0.07087, 0.0546, 0.03117, 0.01903, 0.01115, 0.00644, 0.00330, 0.00173, 0.00085, 0.00042],
    '7.2': [0.09904, 0.04913, 0.02844, 0.01627, 0.00919, 0.00527, 0.00268, 0.00150, 0.00084, 0.00047],
    '7.3': [0.10877, 0.05496, 0.03649, 0.02629, 0.01830, 0.01255, 0.00883, 0.00625, 0.00442, 0.00312],
    '7.4': [0.14459, 0.08016, 0.04651, 0.02711, 0.01495, 0.00925, 0.00480, 0.00295, 0.00152, 0.00081],
    '7.5': [0.11630, 0.07136, 0.04372, 0.02255, 0.01360, 0.00653, 0.00325, 0.00160, 0.00086, 0.00040],
}


def by_degree(studies, case):
    """{degree: convergence rows} of a study's case (example_7_3, smooth_width_0, ...)."""
    return {int(p): t.rows() for p, t in outputs.convergence(os.path.join(studies, case)).groups('degree').items()}


def work_precision(studies, figures):
    fig, axes = plot.subplots(1, 2, figsize=(10, 4.2))
    for ax, ex in zip(axes, ['7_3', '7_5']):
        for p, rs in sorted(by_degree(studies, 'example_' + ex).items()):
            ax.loglog([r['cpu_time_s'] for r in rs], [r['l1_error'] for r in rs], 'o-', color='C%d' % p, ms=4,
                      label='degree %d%s' % (p, ' (paper: FV, Euler)' if p == 0 else ''))
            ax.annotate('l=%d' % rs[-1]['level'], (rs[-1]['cpu_time_s'], rs[-1]['l1_error']),
                        fontsize=7, xytext=(3, -8), textcoords='offset points')
        plot.label(ax, 'CPU time of the time loop [s]', 'L1 error (edges + vertex) at T',
                   'Example %s' % ex.replace('_', '.'), legend=8)
    fig.suptitle('Work precision, grid levels 3-12 (DG: SSPRK3, minmod limiter, '
                 'CFL 0.3 / 0.18 / 0.1)', fontsize=10)
    plot.save(fig, os.path.join(figures, 'network_work_precision.png'), dpi=130, say=True)


def eoc(studies, figures):
    fig, axes = plot.subplots(1, 5, figsize=(16, 3.6), sharey=True)
    for ax, ex in zip(axes, sorted(TABLE_1)):
        rows = by_degree(studies, 'example_' + ex.replace('.', '_'))[0]
        ax.semilogy([r['level'] for r in rows], [r['l1_error'] for r in rows], 'o-', ms=4, label='true L1 (ours)')
        ax.semilogy(range(3, 13), [2 * v for v in TABLE_1[ex]], 'k--', lw=1, label='2 x Table 1')
        ax.semilogy(range(3, 13), TABLE_1[ex], 'k:', lw=1, label='Table 1')
        plot.label(ax, 'grid level l (dx = 2^-l)', title='Example %s' % ex)
    plot.label(axes[0], y='L1 error at T', legend=8, grid=0)
    plot.save(fig, os.path.join(figures, 'network_eoc.png'), dpi=130, say=True)


def smooth(studies, figures):
    fig, axes = plot.subplots(1, 2, figsize=(10, 4), sharey=True)
    for ax, w, title in zip(axes, ['1', '0'], ['vertex cell of width N dx/2 (the paper)',
                                               'vertex without volume (Rankine-Hugoniot solved)']):
        for p, rs in sorted(by_degree(studies, 'smooth_width_' + w).items()):
            dx = [r['dx'] for r in rs]
            ax.loglog(dx, [r['l1_error'] for r in rs], 'o-', color='C%d' % p, ms=4, label='degree %d' % p)
            # ingoing edges (upstream of the vertex) dotted
            ax.loglog(dx, [r['l1_error_edge_1'] + r['l1_error_edge_2'] for r in rs], ':', color='C%d' % p, lw=1)
        plot.label(ax, 'dx', title=title, size=10)
    plot.label(axes[0], y='L1 error at T (solid: all, dotted: ingoing edges)', legend=8, grid=0)
    plot.save(fig, os.path.join(figures, 'network_smooth_order.png'), dpi=130, say=True)


def tables(studies):
    """The markdown tables of doc/network.md."""
    data = {ex: by_degree(studies, 'example_' + ex.replace('.', '_')) for ex in sorted(TABLE_1)}
    rows = []
    for i in range(10):
        rows.append([i + 3])
        for ex, r in ((ex, data[ex][0][i]) for ex in data):
            rows[-1] += ['%.4e' % r['l1_error'], '-' if math.isnan(r['eoc']) else '%.2f' % r['eoc'],
                         '%.2f' % (r['l1_error'] / TABLE_1[ex][i])]
    print(outputs.markdown(['level'] + [h for ex in data for h in ('%s L1' % ex, 'EOC', 'ratio')], rows))
    for ex in ['7.3', '7.5']:
        print('Example %s' % ex)
        print(outputs.markdown(
            ['degree', 'CFL', 'L1 level 8', 'L1 level 12', 'EOC 8/7', 'EOC 12/11', 'steps l=12', 'CPU s l=12',
             'mass residual max'],
            [['%d' % p, '%g' % r8['cfl'], '%.4e' % r8['l1_error'], '%.4e' % r12['l1_error'], '%.2f' % r8['eoc'],
              '%.2f' % r12['eoc'], '%d' % r12['time_steps'], '%.1f' % r12['cpu_time_s'],
              '%.1e' % max(r['mass_balance_residual_max'] for r in rs)]
             for p, rs in sorted(data[ex].items()) for r8, r12 in [(rs[5], rs[9])]]))
    for w in ['1', '0']:
        print('smooth, vertex width factor %s' % w)
        print(outputs.markdown(
            ['degree', 'L1 level 9', 'EOC all edges', 'EOC ingoing edges', 'EOC outgoing edges'],
            [['%d' % p, '%.3e' % rs[-1]['l1_error']] + [rate(rs[-2], rs[-1], edges) for edges in EDGE_GROUPS]
             for p, rs in sorted(by_degree(studies, 'smooth_width_' + w).items())]))


EDGE_GROUPS = (['l1_error'], ['l1_error_edge_1', 'l1_error_edge_2'],
               ['l1_error_edge_3', 'l1_error_edge_4', 'l1_error_edge_5'])


def rate(coarse, fine, keys):
    """The EOC of the sum of the errors named by keys between two levels."""
    return '%.2f' % math.log2(sum(coarse[k] for k in keys) / sum(fine[k] for k in keys))


def studies(a):
    def run(name, prm, *sets):
        run_case(a.build, prm, os.path.join(a.studies, name), ("Convergence/enabled=true",) + sets,
                 check=True, keep=False)

    levels = "Convergence/cells=8,16,32,64,128,256,512,1024,2048,4096"
    for e in (1, 2, 4):
        run("example_7_%d" % e, "prm/network_example_7_%d.prm" % e, levels)
    for e in (3, 5):
        run("example_7_%d" % e, "prm/network_example_7_%d.prm" % e, levels, "Convergence/degrees=0,1,2,3",
            "Convergence/CFL numbers=0.5,0.3,0.18,0.1", "Limiter/scheme=componentwise")
    for w in (1, 0):
        run("smooth_width_%d" % w, "prm/network_smooth.prm", "Network/vertex width factor=%d" % w,
            "Convergence/CFL numbers=0.5,0.3,0.18,0.03", "Convergence/cells=8,16,32,64,128,256,512")


def charts(a):
    for chart in (eoc, work_precision, smooth):
        chart(a.studies, a.figures)


if __name__ == "__main__":
    build = ("build", dict(nargs="?", default="build"))
    out = ("studies", dict(nargs="?", default="output/network_studies"))
    main(__doc__, {"studies": (studies, [build, out]), "tables": (lambda a: tables(a.studies), [out]),
                   "charts": (charts, ["studies", "figures"])})
