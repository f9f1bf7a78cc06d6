#!/usr/bin/python3
"""The wake of the 2D layered strip (prm/layered_2d.prm, case (c)): the stress
on the slice y = 5 (slice-NNNN.csv) of several runs against a reference run,
in the wake x < 15 and on the whole slice, at every output time the runs
share; draws the wake at the last of them.

    contrib/layered_2d_wake.py [--xlim A,B] [--time T] OUT.png REF_DIR RUN_DIR[:label] [...]

Prints, per run and time, the L1 norm of the stress difference on the slice
(each run linear between its sample points, by two-point Gauss on the union
of both runs' sample intervals) over x < 15
and over the whole strip, the largest difference in x < 15, and the run's
total variation of the stress over x < 15 (a measure of ringing). OUT.csv gets
the same rows. --xlim: the part of the wake the figure shows (default 0,15);
--time: the output time it shows (default the last one the reference has).
The commands of doc/study/README.md ("The 2D strip's wake")
make the runs.
"""
import csv
import glob
import os
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt
import numpy as np

WAKE = 15.0


def slices(directory):
    """{time: (x, stress)} of a run's slice files"""
    out = {}
    for path in sorted(glob.glob(os.path.join(directory, "slice-*.csv"))):
        with open(path) as f:
            t = float(f.readline().split(",")[0].split("=")[1])
            header = f.readline().strip().split(",")
        s = np.loadtxt(path, delimiter=",", skiprows=2, ndmin=2)
        out[t] = (s[:, 0], s[:, header.index("stress")])
    return out


def total_variation(x, stress):
    """the total variation of the stress over x < 15 (the slice's samples,
    with the jumps between cells): ringing raises it, a resolved wave train
    keeps it under refinement"""
    return np.sum(np.abs(np.diff(stress[x < WAKE])))


def differences(run, ref):
    """(L1 over x < 15, L1 over the slice, max over x < 15) of run - ref,
    each sampled run linear between its samples and discontinuous where a
    sample point repeats (a cell's end): two-point Gauss on every interval of
    the union of both runs' sample points, so no point sits on a jump and a
    run against itself gives 0"""
    edges = np.unique(np.concatenate([run[0], ref[0]]))
    edges = edges[edges <= run[0].max()]
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    x = np.concatenate([mid - half / np.sqrt(3.0), mid + half / np.sqrt(3.0)])
    w = np.concatenate([half, half])
    e = np.abs(np.interp(x, *run) - np.interp(x, *ref))
    wake = x < WAKE
    return np.sum((e * w)[wake]), np.sum(e * w), e[wake].max()


def main():
    args = sys.argv[1:]
    xlim, shown = (0.0, WAKE), None
    while args and args[0] in ("--xlim", "--time"):
        if args[0] == "--xlim":
            xlim = tuple(float(v) for v in args[1].split(","))
        else:
            shown = float(args[1])
        args = args[2:]
    if len(args) < 3:
        raise SystemExit(__doc__)
    out, ref_dir = args[0], args[1]
    runs = [(r.split(":", 1) + [os.path.basename(r.rstrip("/"))])[:2] for r in args[2:]]
    ref = slices(ref_dir)
    rows = []
    for d, label in runs:
        for t, s in sorted(slices(d).items()):
            if t > 0 and t in ref:
                rows.append([label, t, *differences(s, ref[t]), total_variation(*s)])
                print("%-24s t = %-5g L1 wake %.4f  L1 slice %.4f  max wake %.4f  TV wake %.3f"
                      % tuple(rows[-1]))
    with open(os.path.splitext(out)[0] + ".csv", "w") as f:
        w = csv.writer(f)
        w.writerow(["run", "time", "l1_wake", "l1_slice", "max_wake", "tv_wake"])
        w.writerows(rows)
    t = max(ref) if shown is None else shown
    fig, ax = plt.subplots(figsize=(10, 3.8))
    x, s = ref[t]
    ax.plot(x[x < WAKE], s[x < WAKE], "k-", lw=2.2, alpha=0.35,
            label="reference: " + os.path.basename(ref_dir.rstrip("/")))
    for d, label in runs:
        x, s = slices(d)[t]
        ax.plot(x[x < WAKE], s[x < WAKE], lw=0.9, label=label)
    for j in range(int(WAKE)):
        ax.axvspan(2 * j, 2 * j + 1, color="0.93", lw=0) if 2 * j < WAKE else None
    ax.set_xlabel("x (shaded: the stiff layers, rho = K = 4)")
    ax.set_ylabel("stress on y = 5")
    ax.set_title("2D layered strip, the wake at t = %g" % t)
    ax.set_xlim(*xlim)
    ax.legend(fontsize=8, ncol=2)
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(out, dpi=120)


if __name__ == "__main__":
    main()
