#!/usr/bin/python3
"""Figures of the hopper scene (doc/hopper.md), like Figs. 9-14 of Gremaud &
Matthews, from the outputs of the prm/hopper_*.prm runs.

  /usr/bin/python3 contrib/hopper_figures.py [OUTPUT_DIR [FIGURE_DIR]]

OUTPUT_DIR (default output/) holds hopper_<case>/ as written by
`build/granular_dg prm/hopper_<case>.prm` (contrib/hopper_figures.sh runs them
all); PNGs go to FIGURE_DIR (default doc/figures/). A figure whose runs are
missing is skipped with a note.
"""
import os
import sys

import numpy as np

from granular_dg import outputs, plot

OUT = sys.argv[1] if len(sys.argv) > 1 else 'output'
FIG = sys.argv[2] if len(sys.argv) > 2 else os.path.join('doc', 'figures')
plt = plot.pyplot()


def read(case, name):
    return outputs.read_table(os.path.join(OUT, 'hopper_' + case, name))


def have(*cases):
    missing = [c for c in cases if not os.path.isdir(os.path.join(OUT, 'hopper_' + c))]
    if missing:
        print('skipped (no run): ' + ', '.join(missing))
    return not missing


def save(fig, name, tight=True):
    os.makedirs(FIG, exist_ok=True)
    plot.save(fig, os.path.join(FIG, name), dpi=130, tight=tight, bbox_inches='tight', say=True)


def fig9():
    if not have('fig9_scan'):
        return
    d = read('fig9_scan', 'fig9-scan.csv')
    fig, ax = plt.subplots(figsize=(6.4, 5))
    T = d['Theta_w_deg']
    ax.plot(T, T, 'k:', lw=1, label=r'$\theta_w = \Theta_w$')
    C = np.where(np.isfinite(d['lambda_max']), np.maximum(d['theta_w_min_C_deg'], 0), np.nan)
    ax.plot(T, C, 'b-', lw=2,
            label=r'C: $\Theta_w - \arctan|1/\lambda_{max}|$ (characteristics)')
    ax.plot(T, d['admissible_lower_min_deg'], 'g--',
            label=r'lowest $\theta_w$ with hyperbolic data on $\Gamma_0$')
    ax.plot(T, d['admissible_lower_max_deg'], 'g-.',
            label=r'highest $\theta_w$ with hyperbolic data on $\Gamma_0$')
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
        ax.plot(30 + 0 * r['theta_w'][~ok], r['theta_w'][~ok], 'rx', ms=6,
                label='lost hyperbolicity')
    ax.set(xlim=(T[0], T[-1] + 0.5), ylim=(0, 60))
    plot.label(ax, r'upper half-angle $\Theta_w$ (deg)', r'lower half-angle $\theta_w$ (deg)',
               r'Fig. 9: admissible transitions, cone, $\delta = 32.1^\circ$, $\mu = \tan 11.7^\circ$', size=10)
    ax.legend(fontsize=7, loc='upper left', bbox_to_anchor=(0.0, 0.93))
    save(fig, 'hopper_fig9_scan.png', tight=False)


def fig10():
    if not have('radial_wedge', 'radial_cone'):
        return
    fig, axes = plt.subplots(2, 2, figsize=(10, 7))
    for col, g, bound in ((0, 'wedge', 0.025), (1, 'cone', 0.5)):
        d = read('radial_' + g, 'hopper-steps.csv')
        ax = axes[0, col]
        ax.plot(d['tau'], 100 * d['max_rel_diff_radial'], lw=0.8)
        plot.label(ax, r'$\tau = -\ln(r/r_0)$', 'max relative difference to the radial field (%)',
                   '%s, 30$^\\circ$, P1, N = 400 (paper: < %g %%)' % (g, bound), size=10)
        ax.set_ylim(bottom=0)
        p = os.path.join(OUT, 'hopper_perturbed_' + g, 'hopper-steps.csv')
        ax = axes[1, col]
        if os.path.exists(p):
            e = outputs.read_table(p)
            ax.semilogy(e['tau'], e['max_rel_diff_radial'], lw=0.8,
                        label=r'$T_{rr}(\tau = 0)$ perturbed by $10^{-3}$')
            kappa = 0.9272 if g == 'wedge' else -0.8075
            t = np.linspace(0, e['tau'][-1], 50)
            i = np.searchsorted(e['tau'], 1.0)
            ax.semilogy(t, e['max_rel_diff_radial'][i] * np.exp(kappa * (t - e['tau'][i])), 'k--',
                        lw=1, label=r'$e^{\kappa\tau}$, $\kappa$ = %+.3f (linearised DG spectrum)'
                        % kappa)
            ax.legend(fontsize=8)
        plot.label(ax, r'$\tau$', 'max relative difference')
    fig.suptitle('Fig. 10: preservation of the radial field (top); growth/decay of a '
                 'perturbation (bottom)', fontsize=11)
    save(fig, 'hopper_fig10_preservation.png')


def profiles(case, axes, label=None):
    files = outputs.files(os.path.join(OUT, 'hopper_' + case), 'stress')
    cmap = plt.get_cmap('viridis')
    for k, d in enumerate(map(outputs.read_table, files)):
        tau, c = d.value('tau'), cmap(k / max(1, len(files) - 1))
        for ax, name in zip(axes, ('T_rr_over_r', 'T_rtheta_over_r', 'T_thetatheta_over_r')):
            ax.plot(d['theta_deg'], d[name] / 1e3, color=c, lw=1,
                    label=(r'$\tau$ = %.2f' % tau) if ax is axes[0] else None)
    for ax, name in zip(axes, (r'$T_{rr}/r$', r'$T_{r\theta}/r$', r'$T_{\theta\theta}/r$')):
        plot.label(ax, r'$\theta$ (deg)', name + ' (kPa/m)', label, size=9)
    axes[0].legend(fontsize=7)


def field_map(case, ax, name, title):
    d = read(case, 'hopper-field.csv')
    taus = np.unique(d['tau'])
    th = d['theta_deg'][d['tau'] == taus[0]]
    scale, cmap = (1, 'magma') if name == 'psi_deg' else (1e3, 'viridis')
    m = ax.pcolormesh(th, taus, d[name].reshape(len(taus), len(th)) / scale, shading='auto', cmap=cmap)
    plot.label(ax, r'$\theta$ (deg)', r'$\tau = -\ln(r/r_0)$', title, size=9, grid=0)
    plt.colorbar(m, ax=ax, label='deg' if name == 'psi_deg' else 'kPa/m')


def transition_figure(case, number, title):
    if not have(case):
        return
    fig = plt.figure(figsize=(13, 7.5))
    axes = [fig.add_subplot(2, 3, i + 1) for i in range(3)]
    profiles(case, axes)
    for i, (name, label) in enumerate((('T_rr_over_r', r'$T_{rr}/r$ over $(\theta, \tau)$'),
                                       ('T_rtheta_over_r', r'$T_{r\theta}/r$ over $(\theta, \tau)$'),
                                       ('psi_deg', r'Sokolovskii angle $\psi$ (limit 28.95$^\circ$)'))):
        field_map(case, fig.add_subplot(2, 3, 4 + i), name, label)
    fig.suptitle('Fig. %s: %s' % (number, title), fontsize=11)
    save(fig, 'hopper_fig%s_%s.png' % (number, case))


def fig11():
    if not have('cone_30_24_p1', 'cone_30_24_p2'):
        return
    fig, axes = plt.subplots(2, 3, figsize=(13, 7.5))
    profiles('cone_30_24_p1', axes[0], r'P$^1$, N = 400')
    profiles('cone_30_24_p2', axes[1], r'P$^2$, N = 200')
    fig.suptitle(r'Fig. 11: cone $30^\circ \to 24^\circ$, P$^1$ N = 400 (top) vs P$^2$ '
                 r'N = 200 (bottom), stresses scaled by $r$', fontsize=11)
    save(fig, 'hopper_fig11_p1_p2.png')


def work_precision():
    path = os.path.join(OUT, 'hopper_work_precision', 'work-precision.csv')
    if not os.path.exists(path):
        print('skipped (no run): work precision (contrib/hopper_runs.py precision)')
        return
    d = outputs.read_table(path)
    fig, axes = plt.subplots(1, 2, figsize=(11, 4.6))
    colors = {1: 'C0', 2: 'C1', 3: 'C2'}
    panels = ((axes[0], ((0, '-', 'limiter'), (2, '--', 'no limiter')),
               r'radial field, cone 30$^\circ$, $\tau$ = 1: error vs the exact field'),
              (axes[1], ((1, '-', 'limiter'),),
               r'cone 30$^\circ \to$ 25$^\circ$, $\tau$ = 0.5: error vs P3, N = 800'))
    for ax, cases, title in panels:
        for case, ls, what in cases:
            for p, mk in ((1, 'o'), (2, 's'), (3, '^')):
                sel = (d['case'] == case) & (d['degree'] == p)
                if not sel.any():
                    continue
                ax.loglog(d['cpu_march_s'][sel], d['l1_error'][sel], mk + ls, color=colors[p],
                          label='P%d, %s' % (p, what))
                for x, y, n in zip(d['cpu_march_s'][sel], d['l1_error'][sel], d['cells'][sel]):
                    ax.annotate('%d' % n, (x, y), fontsize=6, xytext=(2, 2),
                                textcoords='offset points')
        plot.label(ax, 'CPU time of the march (s; run minus a one-step run)',
                   r'relative L$^1$ error of $(T_{rr}, T_{r\theta})$', title, legend=7, size=9)
    fig.suptitle('Work-precision (labels: cells N; CFL 1/3, 1/5, 0.12 for P1, P2, P3; '
                 'characteristic minmod limiter, M = 0)', fontsize=10)
    save(fig, 'hopper_work_precision.png')


if __name__ == '__main__':
    fig9()
    fig10()
    fig11()
    transition_figure('cone_30_25', '12', r'cone $30^\circ \to 25^\circ$, P$^1$, N = 400')
    transition_figure('wedge_30_25', '13', r'wedge $30^\circ \to 25^\circ$, P$^1$, N = 400')
    transition_figure('wedge_30_35', '14', r'wedge $30^\circ \to 35^\circ$, P$^1$, N = 400')
    transition_figure('cone_30_31', '14b', r'cone $30^\circ \to 31^\circ$, P$^1$, N = 400')
    work_precision()
