#!/usr/bin/python3
"""Profiles of layered_strip runs against a reference, like Figs 2.2-2.4
(naive flux) and 4.1-4.3 (interface-aware flux) of the central-upwind paper
on layered elasticity.

    contrib/plot_layered.py OUT.png --time 240 --xlim 160,220 REF_DIR:label RUN_DIR:label [...]

Strain (left) and stress (right) of the profile at the given time (the first
directory is drawn as the solid reference line, the others as markers at the
sample points)."""
from granular_dg import outputs, parser, plot

p = parser(__doc__)
p.add_argument("output")
p.add_argument("runs", nargs="+")
p.add_argument("--time", type=float, required=True)
p.add_argument("--xlim", default="")
p.add_argument("--title", default="")
a = p.parse_args()
lo, hi = [float(v) for v in a.xlim.split(",")] if a.xlim else (-float("inf"), float("inf"))
fig, ax = plot.subplots(1, 2, figsize=(12, 4))
for i, run in enumerate(a.runs):
    d, name = plot.split_run(run)
    t = outputs.profile_at(d, a.time)
    keep = (t["x"] >= lo) & (t["x"] <= hi)
    style = dict(color="k", lw=1) if i == 0 else dict(ls="none", marker="ox+s^"[(i - 1) % 5], ms=3, mfc="none")
    for k, column in enumerate(("strain", "stress")):
        ax[k].plot(t["x"][keep], t[column][keep], label=name, **style)
for k, column in enumerate(("strain", "stress")):
    plot.label(ax[k], "x", column, legend=7)
    if a.xlim:
        ax[k].set_xlim(lo, hi)
fig.suptitle(a.title or "t = %g" % a.time)
plot.save(fig, a.output)
