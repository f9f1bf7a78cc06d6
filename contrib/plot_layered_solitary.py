#!/usr/bin/python3
"""Case (b'): the layered strip periodic from t = 60 on; the wave train breaks
into solitary waves. Stress profiles at the given times for several runs, and
a table of the highest peaks (height, position) per run and time.

    contrib/plot_layered_solitary.py OUT.png --times 840,1500,2850 RUN_DIR:label [...]

Peaks are local maxima of the cell-average-free sampled stress that exceed 5%
of the largest; positions are on the periodic domain [0, 300).
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
        if abs(t - time) < 1e-6 * max(1, time):
            d = np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)
            return d[:, 0], d[:, header.index("stress")]
    raise SystemExit("no profile at t = %g in %s" % (time, directory))


def peaks(x, s, n):
    """The n highest local maxima (height, position), highest first."""
    i = np.nonzero((s[1:-1] > s[:-2]) & (s[1:-1] >= s[2:]) & (s[1:-1] > 0.05 * s.max()))[0] + 1
    # one peak per 5 length units, periodically (a solitary wave spans several layers;
    # the layering modulates the stress within it)
    order = i[np.argsort(-s[i])]
    kept = []
    for k in order:
        if all(min(abs(x[k] - x[j]), 300 - abs(x[k] - x[j])) > 5 for j in kept):
            kept.append(k)
        if len(kept) == n:
            break
    return [(s[k], x[k]) for k in kept]


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("out")
    p.add_argument("runs", nargs="+", help="DIR:label")
    p.add_argument("--times", default="840,1500,2850")
    p.add_argument("--peaks", type=int, default=4)
    a = p.parse_args()
    times = [float(t) for t in a.times.split(",")]
    runs = [r.split(":", 1) for r in a.runs]
    fig, axes = plt.subplots(len(times), 1, figsize=(10, 2.6 * len(times)), sharex=True)
    axes = np.atleast_1d(axes)
    print("| run | t | peaks: stress height @ x |")
    print("|---|---|---|")
    for ax, t in zip(axes, times):
        for k, (d, label) in enumerate(runs):
            x, s = profile_at(d, t)
            ax.plot(x, s, "-" if k == 0 else "--", lw=1.0 if k == 0 else 0.9, label=label)
            pk = peaks(x, s, a.peaks)
            print("| %s | %g | %s |" % (label, t, ", ".join("%.4f @ %.2f" % q for q in pk)))
        ax.set_ylabel("stress")
        ax.set_title("t = %g" % t, fontsize=9)
        ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8)
    axes[-1].set_xlabel("x (periodic, length 300)")
    fig.tight_layout()
    fig.savefig(a.out, dpi=110)


if __name__ == "__main__":
    main()
