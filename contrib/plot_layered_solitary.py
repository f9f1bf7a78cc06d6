#!/usr/bin/python3
"""Case (b'): the layered strip periodic from t = 60 on; the wave train breaks
into solitary waves. Stress profiles at the given times for several runs, and
a table of the highest peaks (height, position) per run and time.

    contrib/plot_layered_solitary.py OUT.png --times 840,1500,2850 RUN_DIR:label [...]

Peaks are local maxima of the sampled stress that exceed 5% of the largest;
positions are on the periodic domain [0, 300)."""
import numpy as np

from granular_dg import outputs, parser, plot


def peaks(x, s, n):
    """The n highest local maxima (height, position), highest first, one per
    5 length units periodically (a solitary wave spans several layers; the
    layering modulates the stress within it)."""
    i = np.nonzero((s[1:-1] > s[:-2]) & (s[1:-1] >= s[2:]) & (s[1:-1] > 0.05 * s.max()))[0] + 1
    kept = []
    for k in i[np.argsort(-s[i])]:
        if len(kept) < n and all(min(abs(x[k] - x[j]), 300 - abs(x[k] - x[j])) > 5 for j in kept):
            kept.append(k)
    return [(s[k], x[k]) for k in kept]


p = parser(__doc__)
p.add_argument("out")
p.add_argument("runs", nargs="+", help="DIR:label")
p.add_argument("--times", default="840,1500,2850")
p.add_argument("--peaks", type=int, default=4)
a = p.parse_args()
times = [float(t) for t in a.times.split(",")]
fig, axes = plot.subplots(len(times), 1, figsize=(10, 2.6 * len(times)), sharex=True, squeeze=False)
print("| run | t | peaks: stress height @ x |\n|---|---|---|")
for ax, t in zip(axes[:, 0], times):
    for k, (d, name) in enumerate(map(plot.split_run, a.runs)):
        x, s = (outputs.profile_at(d, t, rtol=1e-6)[c] for c in ("x", "stress"))
        ax.plot(x, s, "-" if k == 0 else "--", lw=1.0 if k == 0 else 0.9, label=name)
        print("| %s | %g | %s |" % (name, t, ", ".join("%.4f @ %.2f" % q for q in peaks(x, s, a.peaks))))
    plot.label(ax, y="stress", title="t = %g" % t, size=9)
axes[0, 0].legend(fontsize=8)
axes[-1, 0].set_xlabel("x (periodic, length 300)")
plot.save(fig, a.out)
