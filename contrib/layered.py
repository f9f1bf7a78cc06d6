#!/usr/bin/python3
"""Studies of the layered strip (RUN: a run's output directory, RUN:label
names it; runs that completed before are reused):

  layered.py study BUILD OUT REFERENCE_MODES_CSV [--quick] [--only CONFIG,... --rows-from CSV]
      doc/layered_strip.md, "Work precision": case (b) to t = 240, the naive flux against
      the interface-aware one (CONFIGS), P1-P3 on 2-32 cells per layer against a finer
      run's modes-NNNN.csv: OUT/layered-study.csv, layered-work-precision.png; --only
      runs some configurations, the others' rows come from CSV;
  layered.py wake [--xlim 0,15] [--time T] OUT.png REF RUN ...
      doc/study/README.md, "The 2D strip's wake": the stress on y = 5 of case (c)'s runs
      against REF at the output times they share (L1 over the wake x < 15 and the slice,
      largest difference, total variation): printed, OUT.csv and the wake at --time;
  layered.py wake-study BUILD RUNS OUT [--reference DIR ...] [--ranks 2]
      the wake's work precision at t = 20 (wake_study): OUT/wake-work-precision.{csv,png}.
"""
import os
import re

import numpy as np

from granular_dg import main, outputs, plot
from granular_dg.compare import slice_l1, total_variation
from granular_dg.run import NO_SNAPSHOTS, Runs

# name: (numerical flux, limiter, troubled-cell indicator, line style)
CONFIGS = {
    "aware": ("impedance", "flux_variables", "everywhere", "o-"),
    "aware-indicator": ("impedance", "flux_variables", "modal_energy", "D-."),
    "aware-nolim": ("impedance", "none", "everywhere", "^:"),
    "naive": ("local_lax_friedrichs", "componentwise", "everywhere", "s--"),
}


def leading_peak(directory):
    """x of the largest stress maximum in the leading 40 length units of the last profile."""
    t = outputs.read_table(outputs.latest(directory, "profile"))
    x, s = t["x"], t["stress"]
    front = x[np.nonzero(np.abs(s) > 1e-3 * np.max(np.abs(s)))[0][-1]]
    return x[x > front - 40][np.argmax(s[x > front - 40])]


def study(a):
    configs = a.only.split(",") if a.only else list(CONFIGS)
    if not set(configs) <= set(CONFIGS):
        raise SystemExit("--only: an unknown configuration in '%s' (allowed: %s)" % (a.only, ", ".join(CONFIGS)))
    runs = Runs(a.build, a.out, sets=NO_SNAPSHOTS, check=True)
    x_ref = leading_peak(os.path.dirname(os.path.abspath(a.reference)))
    degrees = (2,) if a.quick else (1, 2, 3)
    rows = []
    if a.rows_from:  # the rows of an earlier study for the configurations not rerun
        rows = [dict(r, **{k: int(r[k]) for k in ("degree", "cells_per_layer", "n_dofs")})
                for r in outputs.read_table(a.rows_from, numbers=False).rows() if r["config"] not in configs]
    # not finer than the reference (P3 at 32 cells per layer)
    for name, degree, per_layer in ((n, d, c) for n in configs for d in degrees
                                    for c in ((4, 8) if a.quick else (2, 4, 8, 16, 32)) if d * c <= 32):
        flux, limiter, indicator, _ = CONFIGS[name]
        r = runs.run("%s-p%d-%d" % (name, degree, per_layer), "prm/layered_1d.prm", [
            "Mesh/cells x=%d" % (300 * per_layer), "Discretization/degree=%d" % degree,
            "Discretization/numerical flux=" + flux, "Limiter/scheme=" + limiter, "Limiter/indicator=" + indicator,
            "Time stepping/CFL number=%g" % (0.8 / (2 * degree + 1)),
            "Exact solution/reference file=" + os.path.abspath(a.reference)])
        s = r.summary
        rows.append({"config": name, "flux": flux, "limiter": limiter, "indicator": indicator, "degree": degree,
                     "cells_per_layer": per_layer, "n_dofs": s["n_dofs"],
                     "l1_strain_error": s["errors"]["component_0_l1_l2_linf"][0],
                     "interface_stress_jump_max": s["diagnostics"]["interface_stress_jump_max"],
                     "min_strain": s["diagnostics"]["min_strain"],
                     "leading_peak_shift": leading_peak(r.directory) - x_ref,
                     "time_loop_cpu_s": s["time_loop_cpu_s"],
                     "dof_updates_per_cpu_s": s["dof_updates_per_cpu_s_per_rank"]})
        print(rows[-1], flush=True)
    runs.csv("layered-study", rows)
    fig, ax = plot.subplots(figsize=(7, 5))
    for name, (*_, style) in CONFIGS.items():
        for degree in degrees:
            sel = [r for r in outputs.select(rows, config=name, degree=degree) if r["l1_strain_error"] > 0]
            if sel:
                ax.loglog([r["time_loop_cpu_s"] for r in sel], [r["l1_strain_error"] for r in sel], style,
                          label="%s P%d" % (name, degree))
    # Clawpack's second-order f-wave finite volumes on the same case (doc/layered_strip.md)
    ax.loglog([1, 5], [0.09, 0.04], "k*", ms=12, label="Clawpack f-wave")
    plot.label(ax, "CPU time of the time loop [s]", "L1 error of the strain at t = 240",
               "layered 1D strip: error against the reference vs CPU time", legend=(7, 2))
    runs.save(fig, "layered-work-precision")


WAKE, T = 15.0, 20.0  # the wake x < WAKE; the wake study's time


def stress(directory):
    """{time: (x, stress)} of a run's slices."""
    return {t: (s["x"], s["stress"]) for t, s in outputs.slices(directory).items()}


def wake(a):
    ref, rows = stress(a.reference[0]), []
    for d, name in a.runs:
        for t, s in sorted(stress(d).items()):
            if t > 0 and t in ref:
                l1_wake, l1_slice, max_wake = slice_l1(s, ref[t], WAKE)
                rows.append(dict(run=name, time=t, l1_wake=l1_wake, l1_slice=l1_slice, max_wake=max_wake,
                                 tv_wake=total_variation(*s, WAKE)))
                print("%-24s t = %-5g L1 wake %.4f  L1 slice %.4f  max wake %.4f  TV wake %.3f"
                      % tuple(rows[-1].values()))
    outputs.write_csv(os.path.splitext(a.out)[0] + ".csv", rows)
    t = max(ref) if a.time is None else a.time
    fig, ax = plot.subplots(figsize=(10, 3.8))
    x, s = ref[t]
    ax.plot(x[x < WAKE], s[x < WAKE], "k-", lw=2.2, alpha=0.35, label="reference: " + a.reference[1])
    for d, name in a.runs:
        x, s = stress(d)[t]
        ax.plot(x[x < WAKE], s[x < WAKE], lw=0.9, label=name)
    for j in range(0, int(WAKE), 2):
        ax.axvspan(j, j + 1, color="0.93", lw=0)
    ax.set_xlim(*(float(v) for v in a.xlim.split(",")))
    plot.label(ax, "x (shaded: the stiff layers, rho = K = 4)", "stress on y = 5",
               "2D layered strip, the wake at t = %g" % t, legend=(8, 2))
    plot.save(fig, a.out, dpi=120)


def wake_study(a):
    """P2 and P3, with and without subcell blending, 200 x 20 to 800 x 80 cells
    per [0, 100] x [0, 10] (run on [0, 32], which the waves do not leave),
    against the references (default RUNS/p2_1600_none; RUNS/pD_N_none or
    _blend is run when missing)."""
    runs = Runs(a.build, a.runs, check=True)
    cfl = {2: 0.15, 3: 0.1}  # the prm's 0.15 for P2; 0.1 for P3 (its stable CFL)

    def run(name, degree, cells, blending):
        """RUNS/name (run unless it completed before): its summary and (x, stress) at T."""
        sets = ["Discretization/degree=%d" % degree, "Time stepping/CFL number=%g" % cfl[degree],
                "Time stepping/final time=%g" % T, "Mesh/x max=32", "Mesh/cells x=%d" % (cells * 32 // 100),
                "Mesh/cells y=%d" % (cells // 10)]
        # blending computes every cell (the prm's skipping of cells at rest refuses it)
        sets += ["Limiter/scheme=none", "Limiter/subcell blending=true",
                 "Time stepping/skip cells at rest=false"] if blending else []
        r = runs.run(name, "prm/layered_2d.prm", sets, ranks=a.ranks, log=True)
        return r.summary, stress(r.directory)[T]

    references = a.reference or [os.path.join(a.runs, "p2_1600_none")]
    names = [os.path.basename(r.rstrip("/")) for r in references]
    refs = []
    for path, name in zip(references, names):
        match = re.fullmatch(r"p(\d)_(\d+)_(none|blend)", name)
        if match and os.path.samefile(os.path.dirname(os.path.abspath(path)), a.runs):
            refs.append(run(name, int(match[1]), int(match[2]), match[3] == "blend")[1])
        else:
            refs.append(stress(path)[T])
    rows = []
    for degree, blending, cells in ((d, b, n) for d in (2, 3) for b in (False, True) for n in (200, 400, 800)):
        s, (x, y) = run("p%d_%d_%s" % (degree, cells, "blend" if blending else "none"), degree, cells, blending)
        rows.append(dict(degree=degree, method="blending" if blending else "none", cells_x_per_100=cells,
                         tv_wake=total_variation(x, y, WAKE), cpu_s=s["time_loop_cpu_s"] * s["n_mpi_ranks"],
                         energy=s["diagnostics"]["energy"],
                         **{"l1_wake_vs_" + n: slice_l1((x, y), ref, WAKE)[0] for n, ref in zip(names, refs)}))
        print("P%d %-8s %4d x %3d  TV %.3f  CPU %.1f s  energy %.4f  L1 wake vs %s" % (
            degree, rows[-1]["method"], cells, cells // 10, rows[-1]["tv_wake"], rows[-1]["cpu_s"],
            rows[-1]["energy"], ", ".join("%s %.4f" % (n, rows[-1]["l1_wake_vs_" + n]) for n in names)), flush=True)
    os.makedirs(a.out, exist_ok=True)
    outputs.write_csv(os.path.join(a.out, "wake-work-precision.csv"), rows)
    fig, axes = plot.subplots(1, len(names), figsize=(5.2 * len(names), 4.2), squeeze=False)
    for ax, name in zip(axes[0], names):
        for degree, colour in ((2, "tab:blue"), (3, "tab:red")):
            for method, style in (("none", "o-"), ("blending", "s--")):
                r = outputs.select(rows, degree=degree, method=method)
                x, y = [row["cpu_s"] for row in r], [row["l1_wake_vs_" + name] for row in r]
                ax.loglog(x, y, style, color=colour, label="P%d, %s" % (
                    degree, "no limiter" if method == "none" else "subcell blending"))
                for row, xi, yi in zip(r, x, y):
                    ax.annotate("%d" % row["cells_x_per_100"], (xi, yi), fontsize=7, xytext=(3, 3),
                                textcoords="offset points")
        plot.label(ax, "CPU time of the time loop, all ranks [s]", "L1 of the stress on y = 5, x < 15, t = 20",
                   "the wake vs %s (labels: cells in x per 100)" % name, legend=8, size=9)
    plot.save(fig, os.path.join(a.out, "wake-work-precision.png"), dpi=120)


if __name__ == "__main__":
    main(__doc__, {
        "study": (study, ["build", "out", "reference", ("--quick", dict(action="store_true")),
                          ("--only", dict(help="comma-separated configurations to run (default: all)")),
                          ("--rows-from", dict(help="an earlier layered-study.csv: the rows of the others"))]),
        "wake": (wake, [("--xlim", dict(default="0,%g" % WAKE)), ("--time", dict(type=float)), "out",
                        ("reference", dict(type=plot.split_run)), ("runs", dict(nargs="+", type=plot.split_run))]),
        "wake-study": (wake_study, ["build", "runs", "out", ("--reference", dict(action="append", default=[])),
                                    ("--ranks", dict(type=int, default=2))])})
