#!/usr/bin/python3
"""The hopper scene's figures (doc/hopper.md, like Figs. 9-14 of Gremaud &
Matthews) and the extra runs behind some of them (BUILD: the build
directory, default build; the runs go to $OUTPUT_DIR, default output/):

  hopper.py figures [OUTPUT_DIR [FIGURE_DIR]]
      the PNGs (default doc/figures/) from OUTPUT_DIR/hopper_<case>/ as the
      prm/hopper_<case>.prm runs write them (a figure without its runs is skipped);
  hopper.py range [BUILD]       Fig. 9's bar: hopper_march_range/range.csv;
  hopper.py precision [BUILD]   4.7's work precision: hopper_work_precision/work-precision.csv;
  hopper.py indicators [BUILD]  4.7's whole-march table (about 40 min of CPU):
                                hopper_indicators/whole-march.csv.

precision and indicators reuse the runs that completed before.
"""
import os

import numpy as np

from granular_dg import main, outputs, plot
from granular_dg.compare import stress_l1
from granular_dg.run import HOPPER_SAMPLED, NO_SNAPSHOTS, Runs

OUT = os.environ.get('OUTPUT_DIR', 'output')
RANGE_ANGLES = [18.5, 19, 20, 21, 21.5, 22, 23, 24, 25, 26, 27, 28, 29, 30, 31, 31.5, 32, 33]
SAMPLED = (*HOPPER_SAMPLED, *NO_SNAPSHOTS)


def read(case, name):
    return outputs.read_table(os.path.join(OUT, 'hopper_' + case, name))


def save(fig, name, tight=True):
    os.makedirs(FIG, exist_ok=True)
    plot.save(fig, os.path.join(FIG, name), dpi=130, tight=tight, bbox_inches='tight', say=True)


def fig9():
    d = read('fig9_scan', 'fig9-scan.csv')
    fig, ax = plot.subplots(figsize=(6.4, 5))
    T = d['Theta_w_deg']
    ax.plot(T, T, 'k:', lw=1, label=r'$\theta_w = \Theta_w$')
    C = np.where(np.isfinite(d['lambda_max']), np.maximum(d['theta_w_min_C_deg'], 0), np.nan)
    ax.plot(T, C, 'b-', lw=2, label=r'C: $\Theta_w - \arctan|1/\lambda_{max}|$ (characteristics)')
    ax.plot(T, d['admissible_lower_min_deg'], 'g--', label=r'lowest $\theta_w$ with hyperbolic data on $\Gamma_0$')
    ax.plot(T, d['admissible_lower_max_deg'], 'g-.', label=r'highest $\theta_w$ with hyperbolic data on $\Gamma_0$')
    s = outputs.summary(os.path.join(OUT, 'hopper_fig9_scan'))['diagnostics']
    for key, txt in (('psi_monotone_up_to_deg', r'$\psi$ monotone up to %.2f$^\circ$'),
                     ('zero_transition_at_deg', r'no steeper transition from %.2f$^\circ$')):
        ax.axvline(s[key], color='gray', lw=0.8)
        ax.text(s[key] + 0.3, 2, txt % s[key], rotation=90, fontsize=8, color='gray')
    bar = os.path.join(OUT, 'hopper_march_range', 'range.csv')
    if os.path.exists(bar):
        r = outputs.read_table(bar)
        ok = r['completed'] > 0
        ax.plot(30 + 0 * r['theta_w'][ok], r['theta_w'][ok], 'rs', ms=4,
                label=r'$\Theta_w = 30^\circ$: marched to $r = 0.05 r_0$ (N = 400)')
        ax.plot(30 + 0 * r['theta_w'][~ok], r['theta_w'][~ok], 'rx', ms=6, label='lost hyperbolicity')
    ax.set(xlim=(T[0], T[-1] + 0.5), ylim=(0, 60))
    plot.label(ax, r'upper half-angle $\Theta_w$ (deg)', r'lower half-angle $\theta_w$ (deg)',
               r'Fig. 9: admissible transitions, cone, $\delta = 32.1^\circ$, $\mu = \tan 11.7^\circ$', size=10)
    ax.legend(fontsize=7, loc='upper left', bbox_to_anchor=(0.0, 0.93))
    save(fig, 'hopper_fig9_scan.png', tight=False)


def fig10():
    fig, axes = plot.subplots(2, 2, figsize=(10, 7))
    for top, bottom, g, bound in zip(axes[0], axes[1], ('wedge', 'cone'), (0.025, 0.5)):
        d = read('radial_' + g, 'hopper-steps.csv')
        top.plot(d['tau'], 100 * d['max_rel_diff_radial'], lw=0.8)
        plot.label(top, r'$\tau = -\ln(r/r_0)$', 'max relative difference to the radial field (%)',
                   '%s, 30$^\\circ$, P1, N = 400 (paper: < %g %%)' % (g, bound), size=10)
        top.set_ylim(bottom=0)
        p = os.path.join(OUT, 'hopper_perturbed_' + g, 'hopper-steps.csv')
        if os.path.exists(p):
            e = outputs.read_table(p)
            bottom.semilogy(e['tau'], e['max_rel_diff_radial'], lw=0.8,
                            label=r'$T_{rr}(\tau = 0)$ perturbed by $10^{-3}$')
            kappa = 0.9272 if g == 'wedge' else -0.8075
            t = np.linspace(0, e['tau'][-1], 50)
            i = np.searchsorted(e['tau'], 1.0)
            bottom.semilogy(t, e['max_rel_diff_radial'][i] * np.exp(kappa * (t - e['tau'][i])), 'k--', lw=1,
                            label=r'$e^{\kappa\tau}$, $\kappa$ = %+.3f (linearised DG spectrum)' % kappa)
        plot.label(bottom, r'$\tau$', 'max relative difference', legend=8 if os.path.exists(p) else None)
    fig.suptitle('Fig. 10: preservation of the radial field (top); growth/decay of a '
                 'perturbation (bottom)', fontsize=11)
    save(fig, 'hopper_fig10_preservation.png')


def profiles(case, axes, label=None):
    files = outputs.files(os.path.join(OUT, 'hopper_' + case), 'stress')
    cmap = plot.pyplot().get_cmap('viridis')
    for k, d in enumerate(map(outputs.read_table, files)):
        tau, c = d.value('tau'), cmap(k / max(1, len(files) - 1))
        for ax, name in zip(axes, ('T_rr_over_r', 'T_rtheta_over_r', 'T_thetatheta_over_r')):
            ax.plot(d['theta_deg'], d[name] / 1e3, color=c, lw=1,
                    label=(r'$\tau$ = %.2f' % tau) if ax is axes[0] else None)
    for ax, name in zip(axes, (r'$T_{rr}/r$', r'$T_{r\theta}/r$', r'$T_{\theta\theta}/r$')):
        plot.label(ax, r'$\theta$ (deg)', name + ' (kPa/m)', label, size=9, legend=7 if ax is axes[0] else None)


def transition_figure(case, number):
    fig, axes = plot.subplots(2, 3, figsize=(13, 7.5))
    profiles(case, axes[0])
    d = read(case, 'hopper-field.csv')
    taus = np.unique(d['tau'])
    th = d['theta_deg'][d['tau'] == taus[0]]
    for ax, (name, label) in zip(axes[1], (('T_rr_over_r', r'$T_{rr}/r$ over $(\theta, \tau)$'),
                                           ('T_rtheta_over_r', r'$T_{r\theta}/r$ over $(\theta, \tau)$'),
                                           ('psi_deg', r'Sokolovskii angle $\psi$ (limit 28.95$^\circ$)'))):
        scale, cmap = (1, 'magma') if name == 'psi_deg' else (1e3, 'viridis')
        m = ax.pcolormesh(th, taus, d[name].reshape(len(taus), len(th)) / scale, shading='auto', cmap=cmap)
        plot.label(ax, r'$\theta$ (deg)', r'$\tau = -\ln(r/r_0)$', label, size=9, grid=0)
        fig.colorbar(m, ax=ax, label='deg' if name == 'psi_deg' else 'kPa/m')
    fig.suptitle(r'Fig. %s: %s $%s^\circ \to %s^\circ$, P$^1$, N = 400' % (number, *case.split('_')), fontsize=11)
    save(fig, 'hopper_fig%s_%s.png' % (number, case))


def fig11():
    fig, axes = plot.subplots(2, 3, figsize=(13, 7.5))
    profiles('cone_30_24_p1', axes[0], r'P$^1$, N = 400')
    profiles('cone_30_24_p2', axes[1], r'P$^2$, N = 200')
    fig.suptitle(r'Fig. 11: cone $30^\circ \to 24^\circ$, P$^1$ N = 400 (top) vs P$^2$ '
                 r'N = 200 (bottom), stresses scaled by $r$', fontsize=11)
    save(fig, 'hopper_fig11_p1_p2.png')


def work_precision_figure():
    path = os.path.join(OUT, 'hopper_work_precision', 'work-precision.csv')
    if not os.path.exists(path):
        print('skipped (no run): work precision (contrib/hopper.py precision)')
        return
    d = outputs.read_table(path)
    fig, axes = plot.subplots(1, 2, figsize=(11, 4.6))
    panels = ((axes[0], ((0, '-', 'limiter'), (2, '--', 'no limiter')),
               r'radial field, cone 30$^\circ$, $\tau$ = 1: error vs the exact field'),
              (axes[1], ((1, '-', 'limiter'),), r'cone 30$^\circ \to$ 25$^\circ$, $\tau$ = 0.5: error vs P3, N = 800'))
    for ax, cases, title in panels:
        for case, ls, what in cases:
            for p, mk in ((1, 'o'), (2, 's'), (3, '^')):
                sel = (d['case'] == case) & (d['degree'] == p)
                if not sel.any():
                    continue
                ax.loglog(d['cpu_march_s'][sel], d['l1_error'][sel], mk + ls, color='C%d' % (p - 1),
                          label='P%d, %s' % (p, what))
                for x, y, n in zip(d['cpu_march_s'][sel], d['l1_error'][sel], d['cells'][sel]):
                    ax.annotate('%d' % n, (x, y), fontsize=6, xytext=(2, 2), textcoords='offset points')
        plot.label(ax, 'CPU time of the march (s; run minus a one-step run)',
                   r'relative L$^1$ error of $(T_{rr}, T_{r\theta})$', title, legend=7, size=9)
    fig.suptitle('Work-precision (labels: cells N; CFL 1/3, 1/5, 0.12 for P1, P2, P3; '
                 'characteristic minmod limiter, M = 0)', fontsize=10)
    save(fig, 'hopper_work_precision.png')


def figures(a):
    """The figures whose runs are there (the others are skipped, naming the runs missing)."""
    global OUT, FIG
    OUT, FIG = a.output, a.figures
    drawings = [(fig9, (), ['fig9_scan']), (fig10, (), ['radial_wedge', 'radial_cone']),
                (fig11, (), ['cone_30_24_p1', 'cone_30_24_p2'])]
    drawings += [(transition_figure, (case, number), [case]) for case, number in
                 (('cone_30_25', '12'), ('wedge_30_25', '13'), ('wedge_30_35', '14'), ('cone_30_31', '14b'))]
    for draw, args, cases in drawings:
        missing = [c for c in cases if not os.path.isdir(os.path.join(OUT, 'hopper_' + c))]
        if missing:
            print('skipped (no run): ' + ', '.join(missing))
        else:
            draw(*args)
    work_precision_figure()


def stress(directory, i):
    return outputs.read_table(os.path.join(directory, 'stress-%04d.csv' % i))


def march_range(a):
    """The 30 deg cone to the lower angles RANGE_ANGLES, P1, N = 400, to r = 0.05 r0."""
    runs, rows = Runs(a.build, os.path.join(OUT, 'hopper_march_range'), sets=NO_SNAPSHOTS), []
    for angle in RANGE_ANGLES:
        r = runs.run('theta_%g' % angle, 'prm/hopper_cone_30_25.prm', [
            'Hopper/lower half-angle=%g' % angle, 'Hopper output/step series interval=0'], reuse=False)
        s = r.summary
        rows.append(dict(theta_w=angle, completed=int(r.code == 0), final_tau=s.get('final_time', 0),
                         min_margin=s.get('diagnostics', {}).get('min_hyperbolicity_margin', np.nan), cpu_s=r.cpu_s))
        print('theta_w = %g: exit %d, tau = %s %s' % (angle, r.code, s.get('final_time'), r.stderr[:160]))
    runs.csv('range', rows)


def precision(a):
    """P1-P3 on several meshes: (0) the 30 deg cone's radial field at tau = 1,
    (1) the 30 -> 25 deg cone at tau = 0.5 against P3 on N = 800, (2) as (0)
    without the limiter; the relative L1 error of (T_rr, T_rtheta) at 2001
    theta, the CPU time of the run and of the march (minus a one-step run)."""
    runs = Runs(a.build, os.path.join(OUT, 'hopper_work_precision'), sets=SAMPLED, check=True)
    # CFL 1/(2k+1) (GM) for k = 1, 2; k = 3 is unstable at 1/7 (limit ~0.13, doc/hopper.md)
    cfl = {1: 1 / 3., 2: 1 / 5., 3: 0.12}
    meshes = {1: [50, 100, 200, 400], 2: [25, 50, 100, 200], 3: [25, 50, 100, 200]}
    ref = stress(runs.run('transition_reference', 'prm/hopper_cone_30_25.prm', [
        'Discretization/degree=3', 'Hopper/cells=800', 'Time stepping/CFL number=%.12g' % cfl[3],
        'Time stepping/final time=0.5']).directory, 1)
    # the CPU time of start-up and set-up (a one-step run), subtracted below
    setup = {prm: min(runs.run('setup_' + os.path.basename(prm)[:-4], prm, ['Time stepping/final time=1e-9'],
                               reuse=False).cpu_s for _ in range(3))
             for prm in ('prm/hopper_radial_cone.prm', 'prm/hopper_cone_30_25.prm')}
    rows = []
    for case, prm, final, extra in ((0, 'prm/hopper_radial_cone.prm', 1.0, []),
                                    (1, 'prm/hopper_cone_30_25.prm', 0.5, []),
                                    (2, 'prm/hopper_radial_cone.prm', 1.0, ['Limiter/scheme=none'])):
        for p, n in ((p, n) for p, cells in meshes.items() for n in cells):
            r = runs.run('case%d_p%d_n%d' % (case, p, n), prm, ['Discretization/degree=%d' % p, 'Hopper/cells=%d' % n,
                         'Time stepping/CFL number=%.12g' % cfl[p], 'Time stepping/final time=%g' % final] + extra)
            e = stress_l1(stress(r.directory, 1), ref if case == 1 else None)
            rows.append(dict(case=case, degree=p, cells=n, l1_error=e, cpu_s=r.cpu_s,
                             cpu_march_s=max(r.cpu_s - setup[prm], 1e-3), time_loop_s=r.summary['time_loop_s'],
                             dof_updates_per_s=r.summary['dof_updates_per_s']))
            print('case %d P%d N = %d: L1 %.3e, cpu %.2f s, %.2f MDoF/s'
                  % (case, p, n, e, r.cpu_s, r.summary['dof_updates_per_s'] / 1e6))
    runs.csv('work-precision', rows)


def indicators(a):
    """The whole march of the cone and wedge 30 -> 25 as shipped on N = 100-400,
    the limiter everywhere and kxrcf, against P2 N = 1600 references of each."""
    runs = Runs(a.build, os.path.join(OUT, 'hopper_indicators'), sets=SAMPLED + ('Output/output times=1',), check=True)
    choices, rows = ('everywhere', 'kxrcf'), []
    for case in ('cone_30_25', 'wedge_30_25'):
        prm = 'prm/hopper_%s.prm' % case
        refs = [runs.run('%s_reference_%s' % (case, k), prm, ['Limiter/indicator=' + k, 'Discretization/degree=2',
                         'Hopper/cells=1600', 'Time stepping/CFL number=0.2']).directory for k in choices]
        for n, k in ((n, k) for n in (100, 200, 400) for k in choices):
            r = runs.run('%s_%s_n%d' % (case, k, n), prm, ['Limiter/indicator=' + k, 'Hopper/cells=%d' % n])
            for i, tau in ((1, '1'), (2, 'outlet')):  # stress-0001: tau = 1; stress-0002: the outlet
                e = [stress_l1(stress(r.directory, i), stress(d, i)) for d in refs]
                rows.append(dict(case=case, indicator=k, cells=n, tau=tau, l1_vs_reference_everywhere=e[0],
                                 l1_vs_reference_kxrcf=e[1], cpu_s=r.cpu_s))
                print('%s %s N = %d tau = %s: L1 %.3e / %.3e (references %s), cpu %.2f s'
                      % (case, k, n, tau, e[0], e[1], '/'.join(choices), r.cpu_s))
        print('%s: the references differ at the outlet by %.2e'
              % (case, stress_l1(stress(refs[0], 2), stress(refs[1], 2))))
    runs.csv('whole-march', rows)


if __name__ == '__main__':
    build = ('build', dict(nargs='?', default='build'))
    main(__doc__, {'figures': (figures, [('output', dict(nargs='?', default='output')),
                                         ('figures', dict(nargs='?', default=os.path.join('doc', 'figures')))]),
                   'range': (march_range, [build]), 'precision': (precision, [build]),
                   'indicators': (indicators, [build])})
