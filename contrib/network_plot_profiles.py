#!/usr/bin/python3
"""Plots the edge profiles of a network run (profile-NNNN-edge-K.csv, with
the exact solution when the run had one): one panel per edge, numerical
solution against exact, the vertex value marked at the vertex end.

  /usr/bin/python3 contrib/network_plot_profiles.py OUTPUT_DIR PNG [--snapshot N] [--title T]
"""
from granular_dg import outputs, parser, plot

p = parser(__doc__)
p.add_argument("directory")
p.add_argument("png")
p.add_argument("--snapshot", type=int, default=-1, help="index (default: the last)")
p.add_argument("--title", default="")
a = p.parse_args()
edges = outputs.edge_profiles(a.directory, a.snapshot)
fig, axes = plot.subplots(1, len(edges), figsize=(3.1 * len(edges), 2.9), sharey=True, squeeze=False)
for ax, t in zip(axes[0], edges):
    name, direction = t.comments[1].split(":", 1)[0], t.comments[1].split(":", 1)[1].split(",")[0].strip()
    if "exact" in t:
        ax.plot(t["x"], t["exact"], "k-", lw=1.0, label="exact")
    ax.plot(t["x"], t["u"], "-", color="tab:blue", lw=1.2, label="numerical")
    # the vertex value at the vertex end(s) of the edge
    ends = [max(t["x"])] * (direction in ("in", "loop")) + [min(t["x"])] * (direction in ("out", "loop"))
    for e in ends:
        ax.plot([e], [t.value("vertex value")], "o", color="tab:red", ms=5, label="vertex $u_0$")
    plot.label(ax, "x", title="%s (%s)" % (name.strip(), direction), size=9)
axes[0, 0].set_ylabel("u")
axes[0, 0].legend(fontsize=7, loc="best")
fig.suptitle((a.title + ", " if a.title else "") + "t = %g" % edges[0].time, fontsize=10)
plot.save(fig, a.png, dpi=130, say=True)
