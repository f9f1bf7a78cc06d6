#!/usr/bin/python3
"""Profiles of layered_strip runs against a reference, like Figs
2.2-2.4 (naive flux) and 4.1-4.3 (interface-aware flux) of the central-upwind
paper on layered elasticity.

    contrib/plot_layered.py OUT.png --time 240 --xlim 160,220 REF_DIR:label RUN_DIR:label [...]

Strain (left) and stress (right) of the profile-NNNN.csv at the given time
(the first directory is drawn as the solid reference line, the others as
markers at the cell centres' sample points).
"""
import argparse
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def profile_at(directory, time):
    for path in sorted(glob.glob(os.path.join(directory, "profile-*.csv"))):
        with open(path) as f:
            t = float(f.readline().split("=")[1])
            header = f.readline().strip().split(",")
        if abs(t - time) < 1e-9 * max(1, time):
            return header, np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)
    raise SystemExit("no profile at t = %g in %s" % (time, directory))


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("output")
    p.add_argument("runs", nargs="+")
    p.add_argument("--time", type=float, required=True)
    p.add_argument("--xlim", default="")
    p.add_argument("--title", default="")
    a = p.parse_args()
    fig, ax = plt.subplots(1, 2, figsize=(12, 4))
    markers = ["o", "x", "+", "s", "^"]
    for i, run in enumerate(a.runs):
        d, _, label = run.partition(":")
        header, data = profile_at(d, a.time)
        x = data[:, 0]
        keep = np.ones_like(x, dtype=bool)
        if a.xlim:
            lo, hi = [float(v) for v in a.xlim.split(",")]
            keep = (x >= lo) & (x <= hi)
        for k, name in enumerate(("strain", "stress")):
            y = data[:, header.index(name)]
            if i == 0:
                ax[k].plot(x[keep], y[keep], "k-", lw=1, label=label)
            else:
                ax[k].plot(x[keep], y[keep], markers[(i - 1) % 5], ms=3, mfc="none", label=label)
    for k, name in enumerate(("strain", "stress")):
        ax[k].set_xlabel("x")
        ax[k].set_ylabel(name)
        ax[k].grid(alpha=0.3)
        ax[k].legend(fontsize=7)
        if a.xlim:
            ax[k].set_xlim(*[float(v) for v in a.xlim.split(",")])
    fig.suptitle(a.title or "t = %g" % a.time)
    fig.tight_layout()
    fig.savefig(a.output, dpi=110)


if __name__ == "__main__":
    main()
