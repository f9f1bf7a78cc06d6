#!/usr/bin/python3
"""Shock capturing in the 1D scenes (doc/study/README.md, "Subcell blending,
and all five choices in work-precision charts"): error against the CPU time
of the time loop for the CONFIGS (no limiter; the TVB minmod limiter in
every cell; on the cells the modal-energy indicator flags; subcell
blending; both) on the CASES, P2, on a ladder of meshes, each against its
reference run REF_DIR/CASE_ref (run when missing: 10-30 min in all).

    contrib/shock_capturing_study.py BUILD_DIR OUT_DIR REF_DIR [--quick] [--cases layered,...]

Writes OUT_DIR/shock-capturing.csv and .png (a work-precision panel per
case); runs that completed before are reused.
"""
import os

from granular_dg import arguments, outputs, plot
from granular_dg.compare import stress_l1, value_at
from granular_dg.run import HOPPER_SAMPLED, Runs

# name: (limiter on, indicator, subcell blending, line style)
CONFIGS = {
    "none": (False, "everywhere", False, "k^:"),
    "everywhere": (True, "everywhere", False, "o-"),
    "indicator": (True, "modal_energy", False, "D-."),
    "blending": (False, "everywhere", True, "s--"),
    "both": (True, "modal_energy", True, "v-"),
}
HOPPER = ["Time stepping/final time=0.5", "Output/output times="] + HOPPER_SAMPLED
# the limiter, the meshes (the one of --quick) and the reference: its file and its --set overrides
CASES = {
    # (b) at t = 240: L1 strain error against P3, 32 cells per layer, no limiter
    "layered": dict(prm="prm/layered_1d.prm", limiter="flux_variables", mesh="Mesh/cells x",
                    cells=[600, 1200, 2400], quick=[1200], title="layered 1D (b), t = 240: L1 strain",
                    ref="modes-0003.csv", reference=["Mesh/cells x=9600", "Discretization/degree=3",
                                                     "Limiter/scheme=none", "Time stepping/CFL number=0.1",
                                                     "Output/write modes=true"]),
    # (a) at t = 240: L1 strain error against 9600 cells with the limiter everywhere; the strain range
    "shock": dict(prm="prm/elasticity_shock.prm", limiter="characteristic", mesh="Mesh/cells x",
                  cells=[300, 600, 1200, 2400], quick=[600], title="shock (a), t = 240: L1 strain",
                  ref="modes-0003.csv", reference=["Mesh/cells x=9600", "Limiter/indicator=everywhere",
                                                   "Output/write modes=true"]),
    # m = 1 on (0, 5) at t = 4: L1 error of strain + velocity against the closed form, and
    # |strain(3, 4) - reference| against 3200 cells
    "column": dict(prm="tests/column/m1_base.prm", limiter="characteristic", mesh="Mesh/cells",
                   cells=[50, 100, 200, 400], quick=[200], title="column m = 1, t = 4: L1 (strain + velocity)",
                   ref="profile-0003.csv", reference=["Mesh/cells=3200", "Output/profile points per cell=3"]),
    # the cone 30 -> 25 marched to tau = 0.5 (CFL 0.2): relative L1 of (T_rr, T_rtheta)/r at 2001
    # theta against P3 on 800 cells
    "hopper": dict(prm="prm/hopper_cone_30_25.prm", limiter="characteristic", mesh="Hopper/cells",
                   cells=[25, 50, 100, 200], quick=[50],
                   title="hopper cone 30 -> 25, tau = 0.5, P2: rel. L1 (T_rr, T_rtheta)", ref="stress-0001.csv",
                   reference=["Discretization/degree=3", "Hopper/cells=800", "Time stepping/CFL number=0.12",
                              "Output/write vtu=false"] + HOPPER),
}


def case_row(runs, ref, case, cells, config):
    c = CASES[case]
    limiter_on, indicator, blending, _ = CONFIGS[config]
    sets = ["Output/write vtu=false", "%s=%d" % (c["mesh"], cells),
            "Limiter/scheme=" + (c["limiter"] if limiter_on else "none"), "Limiter/indicator=" + indicator,
            "Limiter/subcell blending=%s" % ("true" if blending else "false")]
    # (layered and shock: the shipped output times, on which the step lands as in the shipped runs)
    sets += {"column": ["Output/profile points per cell=3"],
             "hopper": ["Discretization/degree=2", "Time stepping/CFL number=0.2"] + HOPPER}.get(
        case, ["Exact solution/reference file=" + ref])
    r = runs.run("%s-%s-%d" % (case, config, cells), c["prm"], sets)
    s, last = r.summary, outputs.timeseries(r.directory).rows()[-1]
    own = lambda name: outputs.read_table(os.path.join(r.directory, name))
    row = {"case": case, "config": config, "cells": cells, "n_dofs": s["n_dofs"],
           "time_loop_cpu_s": s["time_loop_cpu_s"]}
    if case == "column":
        row["error"] = float(last["l1_error_strain"] + last["l1_error_velocity"])
        row["error_at_3_4"] = abs(value_at(own("profile-0003.csv"), "strain", 3.)
                                  - value_at(outputs.read_table(ref), "strain", 3.))
    elif case == "hopper":
        row["error"] = stress_l1(own("stress-0001.csv"), outputs.read_table(ref))
    else:
        row.update(error=s["errors"]["component_0_l1_l2_linf"][0], min_strain=s["diagnostics"]["min_strain"],
                   max_strain=s["diagnostics"]["max_strain"])
    row["blended_cells_end"] = int(last.get("blended_cells", 0))
    row["flagged_cells_end"] = int(last.get("flagged_cells", 0))
    return row


def chart(rows, cases, runs):
    nrows = 1 if len(cases) <= 2 else 2
    ncols = (len(cases) + nrows - 1) // nrows
    fig, axes = plot.subplots(nrows, ncols, figsize=(5.5 * ncols, 4.3 * nrows), squeeze=False)
    for ax in axes.flat[len(cases):]:
        ax.set_visible(False)
    for ax, case in zip(axes.flat, cases):
        for config, (*_, style) in CONFIGS.items():
            sel = outputs.select(rows, case=case, config=config)
            ax.loglog([r["time_loop_cpu_s"] for r in sel], [r["error"] for r in sel], style, label=config)
        plot.label(ax, "CPU time of the time loop [s]", title=CASES[case]["title"], size=9)
    for row in axes:
        row[0].set_ylabel("error against the reference")
    axes[0][0].legend(fontsize=8)
    runs.save(fig, "shock-capturing")


if __name__ == "__main__":
    a = arguments(__doc__, ["build", "out", "ref_dir", ("--quick", dict(action="store_true", help="one mesh per case")),
                            ("--cases", dict(default=",".join(CASES)))])
    cases, rows = a.cases.split(","), []
    runs, references = Runs(a.build, a.out, check=True), Runs(a.build, a.ref_dir, check=True)
    for case in cases:
        c = CASES[case]
        if not os.path.exists(os.path.join(references.out, case + "_ref", c["ref"])):
            print("running the reference %s_ref" % case, flush=True)
        ref = os.path.join(references.run(case + "_ref", c["prm"], c["reference"]).directory, c["ref"])
        for config in CONFIGS:
            for cells in c["quick" if a.quick else "cells"]:
                rows.append(case_row(runs, ref, case, cells, config))
                print(rows[-1], flush=True)
    runs.csv("shock-capturing", rows)
    chart(rows, cases, runs)
