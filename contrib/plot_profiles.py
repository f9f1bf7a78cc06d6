#!/usr/bin/python3
"""Plot 1D profile-NNNN.csv files of one or more runs.

    contrib/plot_profiles.py OUT.png --column stress RUNDIR[:label] [RUNDIR[:label] ...]
        [--times 80,160,240] [--xlim 0,300] [--title TEXT]

Every profile of a run but t = 0 (or those at --times) is drawn; several runs
are overlaid with their labels."""
from granular_dg import outputs, parser, plot

p = parser(__doc__)
p.add_argument("output")
p.add_argument("runs", nargs="+", help="RUNDIR or RUNDIR:label")
p.add_argument("--column", default="stress")
p.add_argument("--times", default="")
p.add_argument("--xlim", default="")
p.add_argument("--title", default="")
a = p.parse_args()
times = [float(t) for t in a.times.split(",")] if a.times else None
fig, ax = plot.subplots(figsize=(10, 4))
for i, run in enumerate(a.runs):
    d, name = plot.split_run(run)
    for t in outputs.profiles(d):
        if t.time != 0 and (not times or any(abs(t.time - s) < 1e-9 for s in times)):
            ax.plot(t["x"], t[a.column], ["-", "--", ":", "-."][i % 4], lw=1, label="%s t=%g" % (name, t.time))
if a.xlim:
    ax.set_xlim(*[float(v) for v in a.xlim.split(",")])
plot.label(ax, "x", a.column, a.title, legend=7)
plot.save(fig, a.output, dpi=120)
