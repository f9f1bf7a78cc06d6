#!/usr/bin/python3
"""Profiles of runs along x (RUN: a run's output directory, RUN:label names it):

  plot_profiles.py runs OUT.png RUN... [--column stress] [--times 80,160] [--xlim 0,300] [--title T]
      a column of the 1D profiles of the runs, all but t = 0 (or those at --times);
  plot_profiles.py layered OUT.png --time 240 [--xlim 160,220] [--title T] REF RUN...
      strain and stress of the layered strip at one time (doc/layered_strip.md):
      the first run as the solid reference line, the others as markers;
  plot_profiles.py slice OUT.png RUN...
      case (c) of the layered strip: stress and strain on y = 5, a panel per time;
  plot_profiles.py solitary OUT.png [--times 840,1500,2850] RUN...
      case (b'): the stress at the times, a panel per time; a markdown table of the 4 highest peaks;
  plot_profiles.py edges OUT.png RUN [--title T]
      a network run's edge profiles (the last snapshot), a panel per edge,
      against the exact solution if the run has it, the vertex value at its end.
"""
import numpy as np

from granular_dg import main, outputs, plot


def numbers(text):
    return [float(v) for v in text.split(",")] if text else []


def runs(a):
    fig, ax = plot.subplots(figsize=(10, 4))
    for i, (d, name) in enumerate(a.runs):
        shown = [t for t in outputs.profiles(d)
                 if t.time != 0 and (not a.times or any(abs(t.time - s) < 1e-9 for s in numbers(a.times)))]
        if not shown:
            raise outputs.OutputError("%s has no profile-NNNN.csv %s" % (
                d, "at t = " + a.times if a.times else "after t = 0 (a 1D run's profiles)"))
        for t in shown:
            ax.plot(t["x"], t[a.column], plot.STYLES[i % 4], lw=1, label="%s t=%g" % (name, t.time))
    if a.xlim:
        ax.set_xlim(*numbers(a.xlim))
    plot.label(ax, "x", a.column, a.title, legend=7)
    plot.save(fig, a.out, dpi=120)


def layered(a):
    lo, hi = numbers(a.xlim) or (-np.inf, np.inf)
    fig, ax = plot.subplots(1, 2, figsize=(12, 4))
    for i, (d, name) in enumerate(a.runs):
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
    plot.save(fig, a.out)


def slices(a):
    for d, _ in a.runs:
        if not outputs.slices(d):
            raise outputs.OutputError("%s has no slice-NNNN.csv (a 2D layered run with Output/slice y)" % d)
    n = len(outputs.slices(a.runs[0][0]))
    fig, axes = plot.subplots(n, 1, figsize=(10, 2.3 * n), sharex=True, squeeze=False)
    for k, (d, name) in enumerate(a.runs):
        for ax, (t, s) in zip(axes[:, 0], sorted(outputs.slices(d).items())):
            ax.plot(s["x"], s["stress"], "-" if k == 0 else "--", lw=1, label="%s stress" % name)
            ax.plot(s["x"], s["strain"], ":", lw=1, label="%s strain" % name)
            plot.label(ax, title="y = 5, t = %g" % t, size=9)
    axes[0, 0].legend(fontsize=8, ncol=2)
    axes[-1, 0].set_xlabel("x")
    plot.save(fig, a.out)


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


def solitary(a):
    times = numbers(a.times)
    fig, axes = plot.subplots(len(times), 1, figsize=(10, 2.6 * len(times)), sharex=True, squeeze=False)
    print("| run | t | peaks: stress height @ x |\n|---|---|---|")
    for ax, t in zip(axes[:, 0], times):
        for k, (d, name) in enumerate(a.runs):
            x, s = (outputs.profile_at(d, t, rtol=1e-6)[c] for c in ("x", "stress"))
            ax.plot(x, s, "-" if k == 0 else "--", lw=1.0 if k == 0 else 0.9, label=name)
            print("| %s | %g | %s |" % (name, t, ", ".join("%.4f @ %.2f" % q for q in peaks(x, s, 4))))
        plot.label(ax, y="stress", title="t = %g" % t, size=9)
    axes[0, 0].legend(fontsize=8)
    axes[-1, 0].set_xlabel("x (periodic, length 300)")
    plot.save(fig, a.out)


def edges(a):
    found = outputs.edge_profiles(a.run)
    fig, axes = plot.subplots(1, len(found), figsize=(3.1 * len(found), 2.9), sharey=True, squeeze=False)
    for ax, t in zip(axes[0], found):
        name, rest = t.comments[1].split(":", 1)  # "Edge 2: loop, ..."
        direction = rest.split(",")[0].strip()
        if "exact" in t:
            ax.plot(t["x"], t["exact"], "k-", lw=1.0, label="exact")
        ax.plot(t["x"], t["u"], "-", color="tab:blue", lw=1.2, label="numerical")
        # the vertex value at the vertex end(s) of the edge
        ends = [max(t["x"])] * (direction in ("in", "loop")) + [min(t["x"])] * (direction in ("out", "loop"))
        for e in ends:
            ax.plot([e], [t.value("vertex value")], "o", color="tab:red", ms=5, label="vertex $u_0$")
        plot.label(ax, "x", title="%s (%s)" % (name.strip(), direction), size=9)
    plot.label(axes[0, 0], y="u", legend=7, grid=0)
    fig.suptitle((a.title + ", " if a.title else "") + "t = %g" % found[0].time, fontsize=10)
    plot.save(fig, a.out, dpi=130, say=True)


if __name__ == "__main__":
    title, xlim = ("--title", dict(default="")), ("--xlim", dict(default=""))
    many = ("runs", dict(nargs="+", type=plot.split_run))
    main(__doc__, {
        "runs": (runs, ["out", many, ("--column", dict(default="stress")), ("--times", dict(default="")), xlim, title]),
        "layered": (layered, ["out", many, ("--time", dict(type=float, required=True)), xlim, title]),
        "slice": (slices, ["out", many]),
        "solitary": (solitary, ["out", many, ("--times", dict(default="840,1500,2850"))]),
        "edges": (edges, ["out", "run", title])})
