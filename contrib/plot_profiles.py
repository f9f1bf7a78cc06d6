#!/usr/bin/python3
"""Plot 1D profile-NNNN.csv files of one or more runs.

    contrib/plot_profiles.py OUT.png --column stress RUNDIR[:label] [RUNDIR[:label] ...]
        [--times 80,160,240] [--xlim 0,300] [--title TEXT]

Every profile of a run (or those at --times) is drawn; several runs are
overlaid with their labels. Uses Debian's python3-matplotlib (/usr/bin/python3).
"""
import argparse
import glob
import os

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def read_profile(path):
    with open(path) as f:
        time = float(f.readline().split("=")[1])
        header = f.readline().strip().split(",")
    data = np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)
    return time, header, data


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("output")
    p.add_argument("runs", nargs="+", help="RUNDIR or RUNDIR:label")
    p.add_argument("--column", default="stress")
    p.add_argument("--times", default="")
    p.add_argument("--xlim", default="")
    p.add_argument("--title", default="")
    a = p.parse_args()
    times = [float(t) for t in a.times.split(",")] if a.times else None

    fig, ax = plt.subplots(figsize=(10, 4))
    styles = ["-", "--", ":", "-."]
    for i, run in enumerate(a.runs):
        d, _, label = run.partition(":")
        for path in sorted(glob.glob(os.path.join(d, "profile-*.csv"))):
            t, header, data = read_profile(path)
            if t == 0 or (times and not any(abs(t - s) < 1e-9 for s in times)):
                continue
            col = header.index(a.column)
            ax.plot(data[:, 0], data[:, col], styles[i % 4], lw=1,
                    label=f"{label or d} t={t:g}")
    ax.set_xlabel("x")
    ax.set_ylabel(a.column)
    if a.xlim:
        ax.set_xlim(*[float(v) for v in a.xlim.split(",")])
    ax.set_title(a.title)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(a.output, dpi=120)


if __name__ == "__main__":
    main()
