#!/usr/bin/python3
"""Figures of a column run in the layout of Coffey & Gremaud, Figs 4.1-4.3.

    contrib/plot_column.py RUNDIR OUT.png [--title TEXT] [--zmax Z] [--tmax T] [--compare RUNDIR:label ...]

Top left: sgn(v) (the friction multiplier per cell) in the (z, t) plane from
sgn-map.csv, 0 ahead of the pressure front; top right: sgn(v) at the final time; bottom left: the final strain
beside Janssen's profile and beside the stationary problem (4.1)-(4.2) with the
final sgn(v) (final-profile.csv); bottom right: max_z v(z, t) on a log scale
(history.csv; --compare adds other runs, e.g. another resolution).
Uses Debian's python3-matplotlib (/usr/bin/python3).
"""
import argparse
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def read_csv(path):
    return np.genfromtxt(path, delimiter=",", names=True, comments="#")


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("run")
    p.add_argument("output")
    p.add_argument("--title", default="")
    p.add_argument("--zmax", type=float, default=0)
    p.add_argument("--tmax", type=float, default=0, help="time range of the sgn(v) map (0: all)")
    p.add_argument("--compare", nargs="*", default=[])
    a = p.parse_args()

    final = read_csv(os.path.join(a.run, "final-profile.csv"))
    history = read_csv(os.path.join(a.run, "history.csv"))
    zmax = a.zmax or max(1.2 * np.max(history["front_position"]), 1.0)

    fig, ax = plt.subplots(2, 2, figsize=(11, 8))
    sgn_file = os.path.join(a.run, "sgn-map.csv")
    if os.path.exists(sgn_file):
        with open(sgn_file) as f:
            f.readline()
            z = np.array([float(x) for x in f.readline().split(",")[1:]])
        data = np.loadtxt(sgn_file, delimiter=",", skiprows=2, ndmin=2)
        t, s = data[:, 0], data[:, 1:]
        # ahead of the pressure front (the running maximum of front_position,
        # the leading edge of |u| > 1e-3 |u_b|) the scheme leaves round-off-sized
        # precursor values whose multiplier means nothing: draw them as 0
        # (undisturbed), as in the paper
        extent = np.maximum.accumulate(history["front_position"])
        ahead = z[None, :] > np.interp(t, history["time"], extent)[:, None] + 1e-9
        s = np.where(ahead, 0., s)
        keep = z <= zmax
        if a.tmax > 0:
            rows = t <= a.tmax
            t, s = t[rows], s[rows]
        # black 0, white 1 as in the paper when sgn(v) >= 0 throughout
        vmin = -1 if np.min(s[:, keep]) < 0 else 0
        im = ax[0, 0].imshow(s[:, keep], origin="lower", aspect="auto", cmap="gray",
                             vmin=vmin, vmax=1, extent=[z[keep][0], z[keep][-1], t[0], t[-1]],
                             interpolation="nearest")
        fig.colorbar(im, ax=ax[0, 0], label="sgn(v)")
        ax[0, 0].set_title("sgn(v): black %d, white 1 (0: undisturbed)" % vmin)
    ax[0, 0].set_xlabel("z")
    ax[0, 0].set_ylabel("t")

    ahead = final["z"] > np.max(history["front_position"]) + 1e-9
    ax[0, 1].plot(final["z"], np.where(ahead, 0., final["sgn_v"]), "k-", lw=1)
    ax[0, 1].set_xlim(0, zmax)
    ax[0, 1].set_ylim(-1.1, 1.1)
    ax[0, 1].set_xlabel("z")
    ax[0, 1].set_title("sgn(v) at the final time t = %g" % history["time"][-1])

    disturbed = final["z"] <= np.max(history["front_position"])
    ax[1, 0].plot(final["z"], final["strain"], "k-", lw=1.5, label="final strain u_h")
    ax[1, 0].plot(final["z"], final["strain_janssen"], "k--", lw=1, label="Janssen")
    every = max(1, int(np.sum(disturbed) / 40))
    ax[1, 0].plot(final["z"][disturbed][::every], final["strain_auxiliary"][disturbed][::every],
                  "o", mfc="none", ms=4, color="C0", label="stationary (4.1)-(4.2) with final sgn(v)")
    ax[1, 0].set_xlim(0, zmax)
    ax[1, 0].set_xlabel("z")
    ax[1, 0].set_ylabel("u")
    ax[1, 0].legend(fontsize=8)

    runs = [(a.run, os.path.basename(os.path.normpath(a.run)))]
    for c in a.compare:
        d, _, label = c.partition(":")
        runs.append((d, label or d))
    for i, (d, label) in enumerate(runs):
        h = history if i == 0 else read_csv(os.path.join(d, "history.csv"))
        v = np.where(h["max_velocity"] > 0, h["max_velocity"], np.nan)
        ax[1, 1].semilogy(h["time"], v, ["-", "--", ":", "-."][i % 4], color="k", lw=1, label=label)
    ax[1, 1].set_xlabel("t")
    ax[1, 1].set_ylabel("max_z v(z, t)")
    ax[1, 1].legend(fontsize=8)
    ax[1, 1].grid(alpha=0.3)
    if a.title:
        fig.suptitle(a.title)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    main()
