#!/usr/bin/python3
"""Where the naive friction fails: the strain of material at rest (the probe
at z = 0.5) and max_z v over time, for the implicit projection and the naive
explicit variants (history.csv of each run).

    contrib/plot_column_naive.py OUT.png RUNDIR:label [RUNDIR:label ...]
"""
import sys

import numpy as np

from granular_dg import outputs, plot

fig, ax = plot.subplots(1, 2, figsize=(11, 4))
for i, (d, name) in enumerate(map(plot.split_run, sys.argv[2:])):
    h = outputs.history(d)
    style = ["-", "--", ":", "-."][i % 4]
    ax[0].plot(h["time"], h["probe_strain"], style, lw=1.2, label=name)
    ax[1].semilogy(h["time"], np.where(h["max_velocity"] > 0, h["max_velocity"], np.nan), style, lw=1.2, label=name)
plot.label(ax[0], "t", "strain at z = 0.5", "material at rest must keep its strain", legend=8)
plot.label(ax[1], "t", "max_z v", legend=8, which="major")
plot.save(fig, sys.argv[1])
