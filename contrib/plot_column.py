#!/usr/bin/python3
"""Figures of a column run in the layout of Coffey & Gremaud, Figs 4.1-4.3.

    contrib/plot_column.py RUNDIR OUT.png [--title TEXT] [--zmax Z] [--tmax T] [--compare RUNDIR:label ...]

Top left: sgn(v) (the friction multiplier per cell) in the (z, t) plane from
sgn-map.csv, 0 ahead of the pressure front; top right: sgn(v) at the final
time; bottom left: the final strain beside Janssen's profile and beside the
stationary problem (4.1)-(4.2) with the final sgn(v) (final-profile.csv);
bottom right: max_z v(z, t) on a log scale (history.csv; --compare adds other
runs, e.g. another resolution)."""
import os

import numpy as np

from granular_dg import outputs, parser, plot


def sgn_map(ax, fig, run, history, zmax, tmax):
    """sgn(v) in the (z, t) plane: black -1 or 0, white 1, as in the paper."""
    t, z, s = outputs.sgn_map(run)
    # ahead of the pressure front (the running maximum of front_position, the
    # leading edge of |u| > 1e-3 |u_b|) the scheme leaves round-off-sized
    # precursor values whose multiplier means nothing: drawn as 0 (undisturbed)
    extent = np.maximum.accumulate(history["front_position"])
    s = np.where(z[None, :] > np.interp(t, history["time"], extent)[:, None] + 1e-9, 0., s)
    rows, keep = (t <= tmax) if tmax > 0 else np.ones(len(t), bool), z <= zmax
    t, s = t[rows], s[rows][:, keep]
    vmin = -1 if np.min(s) < 0 else 0
    im = ax.imshow(s, origin="lower", aspect="auto", cmap="gray", vmin=vmin, vmax=1,
                   extent=[z[keep][0], z[keep][-1], t[0], t[-1]], interpolation="nearest")
    fig.colorbar(im, ax=ax, label="sgn(v)")
    ax.set_title("sgn(v): black %d, white 1 (0: undisturbed)" % vmin)


p = parser(__doc__)
p.add_argument("run")
p.add_argument("output")
p.add_argument("--title", default="")
p.add_argument("--zmax", type=float, default=0)
p.add_argument("--tmax", type=float, default=0, help="time range of the sgn(v) map (0: all)")
p.add_argument("--compare", nargs="*", default=[])
a = p.parse_args()
final, history = outputs.read_table(os.path.join(a.run, "final-profile.csv")), outputs.history(a.run)
front = np.max(history["front_position"])
zmax = a.zmax or max(1.2 * front, 1.0)
fig, ax = plot.subplots(2, 2, figsize=(11, 8))
if os.path.exists(os.path.join(a.run, "sgn-map.csv")):
    sgn_map(ax[0, 0], fig, a.run, history, zmax, a.tmax)
plot.label(ax[0, 0], "z", "t", grid=0)
ax[0, 1].plot(final["z"], np.where(final["z"] > front + 1e-9, 0., final["sgn_v"]), "k-", lw=1)
ax[0, 1].set(xlim=(0, zmax), ylim=(-1.1, 1.1))
plot.label(ax[0, 1], "z", title="sgn(v) at the final time t = %g" % history["time"][-1], grid=0)
disturbed, z = final["z"] <= front, final["z"]
every = max(1, int(np.sum(disturbed) / 40))
ax[1, 0].plot(z, final["strain"], "k-", lw=1.5, label="final strain u_h")
ax[1, 0].plot(z, final["strain_janssen"], "k--", lw=1, label="Janssen")
ax[1, 0].plot(z[disturbed][::every], final["strain_auxiliary"][disturbed][::every], "o", mfc="none", ms=4,
              color="C0", label="stationary (4.1)-(4.2) with final sgn(v)")
ax[1, 0].set_xlim(0, zmax)
plot.label(ax[1, 0], "z", "u", legend=8, grid=0)
for i, (d, name) in enumerate([(a.run, os.path.basename(os.path.normpath(a.run)))] +
                              [plot.split_run(c) for c in a.compare]):
    h = history if i == 0 else outputs.history(d)
    v = np.where(h["max_velocity"] > 0, h["max_velocity"], np.nan)
    ax[1, 1].semilogy(h["time"], v, ["-", "--", ":", "-."][i % 4], color="k", lw=1, label=name)
plot.label(ax[1, 1], "t", "max_z v(z, t)", legend=8, which="major")
if a.title:
    fig.suptitle(a.title)
plot.save(fig, a.output)
