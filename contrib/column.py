#!/usr/bin/python3
"""Figures and studies of the column scene; what they draw and measure is in
doc/column.md (RUN: a run's output directory, RUN:label names it):

  column.py figure RUN OUT.png [--title T] [--zmax Z] [--tmax T] [--compare RUN:label ...]
      Figs 4.1-4.3 of Coffey & Gremaud: sgn(v) over (z, t) (up to --tmax) and at the
      final time, the final strain against Janssen's and the stationary profile, max_z v;
  column.py naive OUT.png RUN:label ...           the probe strain and max_z v of each run;
  column.py indicators BUILD OUT                  "Shock capturing": OUT/column-indicator-scan.csv
                                                  and a markdown table;
  column.py late-time BUILD OUT [--final-time T]  "Late times": OUT/late-time.csv.

The studies reuse the runs that completed before.
"""
import os

import numpy as np

from granular_dg import main, outputs, plot
from granular_dg.compare import value_at
from granular_dg.plot import STYLES
from granular_dg.run import Runs


def figure(a):
    final, history = outputs.read_table(os.path.join(a.run, "final-profile.csv")), outputs.history(a.run)
    front = np.max(history["front_position"])
    zmax = a.zmax or max(1.2 * front, 1.0)
    fig, ax = plot.subplots(2, 2, figsize=(11, 8))
    if os.path.exists(os.path.join(a.run, "sgn-map.csv")):
        sgn_map(ax[0, 0], fig, a.run, history, zmax, a.tmax)
    plot.label(ax[0, 0], "z", "t", grid=0)
    ax[0, 1].plot(final["z"], np.where(final["z"] > front + 1e-9, 0., final["sgn_v"]), "k-", lw=1)
    ax[0, 1].set(xlim=(0, zmax), ylim=(-1.1, 1.1))
    plot.label(ax[0, 1], "z", title="sgn(v) at the final time t = %g" % history["time"][-1], grid=0)
    disturbed, z = final["z"] <= front, final["z"]
    every = max(1, int(np.sum(disturbed) / 40))
    ax[1, 0].plot(z, final["strain"], "k-", lw=1.5, label="final strain u_h")
    ax[1, 0].plot(z, final["strain_janssen"], "k--", lw=1, label="Janssen")
    ax[1, 0].plot(z[disturbed][::every], final["strain_auxiliary"][disturbed][::every], "o", mfc="none", ms=4,
                  color="C0", label="stationary (4.1)-(4.2) with final sgn(v)")
    ax[1, 0].set_xlim(0, zmax)
    plot.label(ax[1, 0], "z", "u", legend=8, grid=0)
    for i, (d, name) in enumerate([plot.split_run(a.run)] + a.compare):
        h = outputs.history(d)
        ax[1, 1].semilogy(h["time"], np.ma.masked_less_equal(h["max_velocity"], 0), STYLES[i % 4], color="k", lw=1,
                          label=name)
    plot.label(ax[1, 1], "t", "max_z v(z, t)", legend=8, which="major")
    if a.title:
        fig.suptitle(a.title)
    plot.save(fig, a.out)


def sgn_map(ax, fig, run, history, zmax, tmax):
    """sgn(v) in the (z, t) plane: black -1 or 0, white 1, as in the paper."""
    t, z, s = outputs.sgn_map(run)
    # ahead of the pressure front (the running maximum of front_position, the
    # leading edge of |u| > 1e-3 |u_b|) the scheme leaves round-off-sized
    # precursor values whose multiplier means nothing: drawn as 0 (undisturbed)
    extent = np.maximum.accumulate(history["front_position"])
    s = np.where(z[None, :] > np.interp(t, history["time"], extent)[:, None] + 1e-9, 0., s)
    rows, keep = (t <= tmax) if tmax > 0 else np.ones(len(t), bool), z <= zmax
    t, s = t[rows], s[rows][:, keep]
    vmin = -1 if np.min(s) < 0 else 0
    im = ax.imshow(s, origin="lower", aspect="auto", cmap="gray", vmin=vmin, vmax=1,
                   extent=[z[keep][0], z[keep][-1], t[0], t[-1]], interpolation="nearest")
    fig.colorbar(im, ax=ax, label="sgn(v)")
    ax.set_title("sgn(v): black %d, white 1 (0: undisturbed)" % vmin)


def naive(a):
    fig, ax = plot.subplots(1, 2, figsize=(11, 4))
    for i, (d, name) in enumerate(a.runs):
        h = outputs.history(d)
        ax[0].plot(h["time"], h["probe_strain"], STYLES[i % 4], lw=1.2, label=name)
        ax[1].semilogy(h["time"], np.ma.masked_less_equal(h["max_velocity"], 0), STYLES[i % 4], lw=1.2, label=name)
    plot.label(ax[0], "t", "strain at z = 0.5", "material at rest must keep its strain", legend=8)
    plot.label(ax[1], "t", "max_z v", legend=8, which="major")
    plot.save(fig, a.out)


# u(3, 4) of the closed form (include/granular_dg/equations/column/
# closed_form.h, u_b = -1): z = 3 slides until t_s(3) = 4.7196
EXACT_STRAIN_3_4 = -0.147769340095
# name: extra parameters (the limiter is the characteristic one of the prm)
CHOICES = {
    "everywhere": ["Limiter/indicator=everywhere"],
    "modal_energy (automatic threshold 2.1e-3)": ["Limiter/indicator=modal_energy"],
    **{"modal_energy, threshold %g" % t: ["Limiter/indicator=modal_energy", "Limiter/indicator threshold=%g" % t]
       for t in (0.01, 0.05, 0.1, 0.2, 0.3, 0.5)},
    "subcell blending, no limiter": ["Limiter/scheme=none", "Limiter/subcell blending=true"],
    "no limiter": ["Limiter/scheme=none"],
}
CELLS = (100, 200, 400)


def indicators(a):
    runs, rows = Runs(a.build, a.out, sets=["Output/write vtu=false"], check=True), []
    for i, (name, settings) in enumerate(CHOICES.items()):
        row = {"choice": name}
        for cells in CELLS:
            r = runs.run("base-%d-%d" % (i, cells), "tests/column/m1_base.prm",
                         settings + ["Mesh/cells=%d" % cells, "Output/profile points per cell=3"])
            row["error_3_4_%d" % cells] = abs(value_at(outputs.profile_at(r.directory, 4), "strain", 3.)
                                              - EXACT_STRAIN_3_4)
            if cells == 200:
                errors, last = r.summary["errors"], outputs.timeseries(r.directory).rows()[-1]
                row["l1"] = errors["component_0_l1_l2_linf"][0] + errors["component_1_l1_l2_linf"][0]
                row["max_stuck_velocity"] = r.summary["diagnostics"]["max_stuck_velocity"]
                row["flagged_t4"] = next(("%d" % last[k] for k in ("flagged_cells", "blended_cells") if k in last),
                                         "-")
        r = runs.run("m1-%d" % i, "prm/column_m1.prm", settings)
        # the scatter of the frozen sgn(v) on 4 < z < 13.6 about a degree-6 fit
        d = outputs.read_table(os.path.join(r.directory, "final-profile.csv"))
        frozen = (d["z"] > 4) & (d["z"] < 13.6)
        z, s = d["z"][frozen], d["sgn_v"][frozen]
        row["multiplier_scatter"] = float(np.sqrt(np.mean((s - np.polyval(np.polyfit(z, s, 6), z)) ** 2)))
        row["sign_flips_t40"] = r.summary["diagnostics"]["velocity_sign_flips"]
        row["final_vs_stationary"] = r.summary["diagnostics"]["auxiliary_max_difference"]
        rows.append(row)
    runs.csv("column-indicator-scan", rows)
    print(outputs.markdown(
        ["choice", "error of u at (3, 4), 100 / 200 / 400 cells", "L1 (u, v), 200 cells", "flagged at t = 4",
         "max v in stuck cells", "sign flips to t = 40", "final u vs stationary", "scatter of frozen sgn(v)"],
        [[r["choice"], " / ".join("%.2g" % r["error_3_4_%d" % c] for c in CELLS), "%.3g" % r["l1"], r["flagged_t4"],
          "%.3g" % r["max_stuck_velocity"], "%d" % r["sign_flips_t40"], "%.2g" % r["final_vs_stationary"],
          "%.3f" % r["multiplier_scatter"]] for r in rows]), end="")


def late_time(a):
    runs, rows = Runs(a.build, a.out, check=True), []
    for weights, limiters in (("consistent", ("characteristic", "componentwise")), ("printed", ("characteristic",))):
        for limiter, cells in ((l, c) for l in limiters for c in (200, 400, 800)):
            r = runs.run("%s-%s-%d" % (weights, limiter, cells), "prm/column_m1.5.prm", [
                "Mesh/length=10", "Mesh/cells=%d" % cells, "Time stepping/final time=%g" % a.final_time,
                "Output/output interval=0", "Output/write vtu=false",
                "Time stepping/skip tolerance=0",  # the full computation: the study measures drifts
                "Diagnostics/write sgn map=false", "Diagnostics/sample interval=1", "Limiter/scheme=" + limiter,
                "Physics/friction stage weights=" + weights])
            h = outputs.history(r.directory)
            i100, crit, strain = int(np.argmin(abs(h["time"] - 100))), h["critical_loadings"], h["probe_strain"]
            late = np.nonzero(crit > crit[i100])[0]
            rows.append({"weights": weights, "limiter": limiter, "cells": cells, "probe_strain_t100": strain[i100],
                         "probe_strain_final": strain[-1], "drift": strain[-1] - strain[i100],
                         "critical_loadings_after_t100": int(crit[-1] - crit[i100]),
                         "first_late_critical_time": h["time"][late[0]] if len(late) else -1,
                         "max_velocity_final": h["max_velocity"][-1]})
            print(rows[-1], flush=True)
    runs.csv("late-time", rows)


if __name__ == "__main__":
    main(__doc__, {
        "figure": (figure, ["run", "out", ("--title", dict(default="")), ("--zmax", dict(type=float, default=0)),
                            ("--tmax", dict(type=float, default=0, help="time range of the sgn(v) map (0: all)")),
                            ("--compare", dict(nargs="*", default=[], type=plot.split_run))]),
        "naive": (naive, ["out", ("runs", dict(nargs="+", type=plot.split_run))]),
        "indicators": (indicators, ["build", "out"]),
        "late-time": (late_time, ["build", "out", ("--final-time", dict(type=float, default=1000))])})
