#!/usr/bin/python3
"""Case (c) of the layered strip: stress and strain along the slice y = 5
(slice-NNNN.csv of prm/layered_2d.prm) at every output time, one panel per
time.

    contrib/plot_layered_slice.py OUT.png RUN_DIR[:label] [...]
"""
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np


def slices(directory):
    out = []
    for path in sorted(glob.glob(os.path.join(directory, "slice-*.csv"))):
        with open(path) as f:
            t = float(f.readline().split(",")[0].split("=")[1])
            header = f.readline().strip().split(",")
        out.append((t, header, np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)))
    return out


def main():
    if len(sys.argv) < 3:
        raise SystemExit(__doc__)
    runs = [(r.split(":", 1) + [os.path.basename(r)])[:2] for r in sys.argv[2:]]
    first = slices(runs[0][0])
    fig, axes = plt.subplots(len(first), 1, figsize=(10, 2.3 * len(first)), sharex=True)
    axes = np.atleast_1d(axes)
    for k, (d, label) in enumerate(runs):
        for ax, (t, header, s) in zip(axes, slices(d)):
            ax.plot(s[:, 0], s[:, header.index("stress")], "-" if k == 0 else "--", lw=1,
                    label="%s stress" % label)
            ax.plot(s[:, 0], s[:, header.index("strain")], ":", lw=1, label="%s strain" % label)
            ax.set_title("y = 5, t = %g" % t, fontsize=9)
            ax.grid(alpha=0.3)
    axes[0].legend(fontsize=8, ncol=2)
    axes[-1].set_xlabel("x")
    fig.tight_layout()
    fig.savefig(sys.argv[1], dpi=110)


if __name__ == "__main__":
    main()
