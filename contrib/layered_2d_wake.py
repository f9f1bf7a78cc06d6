#!/usr/bin/python3
"""The wake of the 2D layered strip (prm/layered_2d.prm, case (c)): the stress
on the slice y = 5 (slice-NNNN.csv) of several runs against a reference run,
in the wake x < 15 and on the whole slice, at every output time the runs
share; draws the wake at the last of them.

    contrib/layered_2d_wake.py [--xlim A,B] [--time T] OUT.png REF_DIR RUN_DIR[:label] [...]

Prints, per run and time, the L1 norm of the stress difference on the slice
(each run linear between its sample points, by two-point Gauss on the union
of both runs' sample intervals) over x < 15 and over the whole strip, the
largest difference in x < 15, and the run's total variation of the stress
over x < 15 (a measure of ringing). OUT.csv gets the same rows. --xlim: the
part of the wake the figure shows (default 0,15); --time: the output time it
shows (default the last one the reference has). The commands of
doc/study/README.md ("The 2D strip's wake") make the runs.
"""
import os
import sys

from granular_dg import outputs, plot
from granular_dg.compare import slice_l1, total_variation

WAKE = 15.0


def stress(directory):
    """{time: (x, stress)} of a run's slices."""
    return {t: (s["x"], s["stress"]) for t, s in outputs.slices(directory).items()}


def main():
    args, xlim, shown = sys.argv[1:], (0.0, WAKE), None
    while args and args[0] in ("--xlim", "--time"):
        if args[0] == "--xlim":
            xlim = tuple(float(v) for v in args[1].split(","))
        else:
            shown = float(args[1])
        args = args[2:]
    if len(args) < 3:
        raise SystemExit(__doc__)
    out, ref_dir, runs = args[0], args[1], [plot.split_run(r) for r in args[2:]]
    ref, rows = stress(ref_dir), []
    for d, name in runs:
        for t, s in sorted(stress(d).items()):
            if t > 0 and t in ref:
                l1_wake, l1_slice, max_wake = slice_l1(s, ref[t], WAKE)
                rows.append(dict(run=name, time=t, l1_wake=l1_wake, l1_slice=l1_slice, max_wake=max_wake,
                                 tv_wake=total_variation(*s, WAKE)))
                print("%-24s t = %-5g L1 wake %.4f  L1 slice %.4f  max wake %.4f  TV wake %.3f"
                      % tuple(rows[-1].values()))
    outputs.write_csv(os.path.splitext(out)[0] + ".csv", rows)
    t = max(ref) if shown is None else shown
    fig, ax = plot.subplots(figsize=(10, 3.8))
    x, s = ref[t]
    ax.plot(x[x < WAKE], s[x < WAKE], "k-", lw=2.2, alpha=0.35, label="reference: " + plot.split_run(ref_dir)[1])
    for d, name in runs:
        x, s = stress(d)[t]
        ax.plot(x[x < WAKE], s[x < WAKE], lw=0.9, label=name)
    for j in range(0, int(WAKE), 2):
        ax.axvspan(j, j + 1, color="0.93", lw=0)
    ax.set_xlim(*xlim)
    plot.label(ax, "x (shaded: the stiff layers, rho = K = 4)", "stress on y = 5",
               "2D layered strip, the wake at t = %g" % t)
    ax.legend(fontsize=8, ncol=2)
    plot.save(fig, out, dpi=120)


if __name__ == "__main__":
    main()
