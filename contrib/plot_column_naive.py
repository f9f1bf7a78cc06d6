#!/usr/bin/python3
"""Where the naive friction fails: the strain of material at rest (the probe
at z = 0.5) and max_z v over time, for the implicit projection and the naive
explicit variants (history.csv of each run).

    contrib/plot_column_naive.py OUT.png RUNDIR:label [RUNDIR:label ...]
"""
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def main():
    out, runs = sys.argv[1], sys.argv[2:]
    fig, ax = plt.subplots(1, 2, figsize=(11, 4))
    for i, run in enumerate(runs):
        d, _, label = run.partition(":")
        h = np.genfromtxt(os.path.join(d, "history.csv"), delimiter=",", names=True)
        style = ["-", "--", ":", "-."][i % 4]
        ax[0].plot(h["time"], h["probe_strain"], style, lw=1.2, label=label)
        v = np.where(h["max_velocity"] > 0, h["max_velocity"], np.nan)
        ax[1].semilogy(h["time"], v, style, lw=1.2, label=label)
    ax[0].set_xlabel("t")
    ax[0].set_ylabel("strain at z = 0.5")
    ax[0].set_title("material at rest must keep its strain")
    ax[1].set_xlabel("t")
    ax[1].set_ylabel("max_z v")
    for a in ax:
        a.grid(alpha=0.3)
        a.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(out, dpi=110)


if __name__ == "__main__":
    main()
