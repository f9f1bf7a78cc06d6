#!/usr/bin/python3
"""Case (c) of the layered strip: stress and strain along the slice y = 5
(slice-NNNN.csv of prm/layered_2d.prm) at every output time, one panel per
time.

    contrib/plot_layered_slice.py OUT.png RUN_DIR[:label] [...]
"""
import sys

from granular_dg import outputs, plot

if len(sys.argv) < 3:
    raise SystemExit(__doc__)
runs = [plot.split_run(r) for r in sys.argv[2:]]
first = outputs.slices(runs[0][0])
fig, axes = plot.subplots(len(first), 1, figsize=(10, 2.3 * len(first)), sharex=True, squeeze=False)
for k, (d, name) in enumerate(runs):
    for ax, (t, s) in zip(axes[:, 0], sorted(outputs.slices(d).items())):
        ax.plot(s["x"], s["stress"], "-" if k == 0 else "--", lw=1, label="%s stress" % name)
        ax.plot(s["x"], s["strain"], ":", lw=1, label="%s strain" % name)
        plot.label(ax, title="y = 5, t = %g" % t, size=9)
axes[0, 0].legend(fontsize=8, ncol=2)
axes[-1, 0].set_xlabel("x")
plot.save(fig, sys.argv[1])
