#!/usr/bin/python3
"""Shock capturing in the 1D scenes: error against CPU time for
  none        no limiter, no blending
  everywhere  the TVB minmod limiter in every cell (the scenes' old default)
  indicator   the minmod limiter in the cells the modal-energy indicator flags
  blending    subcell blending (Limiter/subcell blending), no limiter
  both        subcell blending and the minmod limiter on flagged cells
on three cases, P2, on a ladder of meshes:
  layered     prm/layered_1d.prm (b), t = 240, 2-8 cells per layer, flux-variable
              limiter; L1 strain error against REF_DIR/layered_ref/modes-0003.csv
              (P3, 32 cells per layer, no limiter)
  shock       prm/elasticity_shock.prm (a), t = 240, 300-2400 cells, characteristic
              limiter; L1 strain error against REF_DIR/shock_ref/modes-0003.csv
              (9600 cells, limiter everywhere); also the strain range (overshoot)
  column      tests/column/m1_base.prm (m = 1, (0, 5), t = 4), 50-400 cells,
              characteristic limiter; L1 error of strain + velocity against the
              closed form, and |strain(3, 4) - reference| against
              REF_DIR/column_ref/profile-0003.csv (3200 cells, limiter everywhere)
  hopper      prm/hopper_cone_30_25.prm marched to tau = 0.5, P2 (CFL 0.2), 25-200
              cells, characteristic limiter; relative L1 of (T_rr, T_rtheta)/r at
              2001 theta against REF_DIR/hopper_ref/stress-0001.csv (P3, 800 cells)

    contrib/shock_capturing_study.py BUILD_DIR OUT_DIR REF_DIR [--quick] [--cases layered,...]

Writes OUT_DIR/shock-capturing.csv and OUT_DIR/shock-capturing.png (one
work-precision panel per case); runs whose directory has a summary.json are
reused. The references (doc/study/README.md):
    granular_dg prm/layered_1d.prm --set "Mesh/cells x=9600" --set Discretization/degree=3 \\
      --set Limiter/scheme=none --set "Time stepping/CFL number=0.1" \\
      --set "Output/write modes=true" --set Output/directory=REF_DIR/layered_ref
    granular_dg prm/elasticity_shock.prm --set "Mesh/cells x=9600" --set Limiter/indicator=everywhere \\
      --set "Output/write modes=true" --set Output/directory=REF_DIR/shock_ref
    granular_dg tests/column/m1_base.prm --set Mesh/cells=3200 \\
      --set "Output/profile points per cell=3" --set Output/directory=REF_DIR/column_ref
    granular_dg prm/hopper_cone_30_25.prm --set Discretization/degree=3 --set Hopper/cells=800 \\
      --set "Time stepping/CFL number=0.12" --set "Time stepping/final time=0.5" \\
      --set "Output/output times=" --set "Output/write vtu=false" \\
      --set "Hopper output/step series interval=0" --set "Hopper output/sample points=2001" \\
      --set Output/directory=REF_DIR/hopper_ref
"""
import os

from granular_dg import outputs, parser, plot
from granular_dg.compare import stress_l1, value_at
from granular_dg.run import run_case

# name: (limiter on, indicator, subcell blending)
CONFIGS = {
    "none": (False, "everywhere", False),
    "everywhere": (True, "everywhere", False),
    "indicator": (True, "modal_energy", False),
    "blending": (False, "everywhere", True),
    "both": (True, "modal_energy", True),
}
STYLES = {"none": "k^:", "everywhere": "o-", "indicator": "D-.", "blending": "s--", "both": "v-"}
CASES = {
    "layered": dict(prm="prm/layered_1d.prm", limiter="flux_variables", mesh="Mesh/cells x",
                    cells=[600, 1200, 2400], quick=[1200], ref="layered_ref/modes-0003.csv",
                    title="layered 1D (b), t = 240: L1 strain"),
    "shock": dict(prm="prm/elasticity_shock.prm", limiter="characteristic", mesh="Mesh/cells x",
                  cells=[300, 600, 1200, 2400], quick=[600], ref="shock_ref/modes-0003.csv",
                  title="shock (a), t = 240: L1 strain"),
    "column": dict(prm="tests/column/m1_base.prm", limiter="characteristic", mesh="Mesh/cells",
                   cells=[50, 100, 200, 400], quick=[200], ref="column_ref/profile-0003.csv",
                   title="column m = 1, t = 4: L1 (strain + velocity)"),
    "hopper": dict(prm="prm/hopper_cone_30_25.prm", limiter="characteristic", mesh="Hopper/cells",
                   cells=[25, 50, 100, 200], quick=[50], ref="hopper_ref/stress-0001.csv",
                   title="hopper cone 30 -> 25, tau = 0.5, P2: rel. L1 (T_rr, T_rtheta)"),
}
HOPPER_SETS = ["Discretization/degree=2", "Time stepping/CFL number=0.2", "Time stepping/final time=0.5",
               "Output/output times=", "Hopper output/step series interval=0", "Hopper output/sample points=2001"]


def case_row(a, case, cells, config):
    c = CASES[case]
    limiter_on, indicator, blending = CONFIGS[config]
    ref = os.path.join(a.ref_dir, c["ref"])
    sets = ["Output/write vtu=false", "%s=%d" % (c["mesh"], cells),
            "Limiter/scheme=" + (c["limiter"] if limiter_on else "none"), "Limiter/indicator=" + indicator,
            "Limiter/subcell blending=%s" % ("true" if blending else "false")]
    # (layered and shock: the shipped output times, on which the step lands as in the shipped runs)
    sets += {"column": ["Output/profile points per cell=3"], "hopper": HOPPER_SETS}.get(
        case, ["Exact solution/reference file=" + ref])
    r = run_case(a.build, c["prm"], os.path.join(a.out, "%s-%s-%d" % (case, config, cells)), sets,
                 reuse=True, check=True)
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


def chart(rows, cases, path):
    nrows = 1 if len(cases) <= 2 else 2
    ncols = (len(cases) + nrows - 1) // nrows
    fig, axes = plot.subplots(nrows, ncols, figsize=(5.5 * ncols, 4.3 * nrows), squeeze=False)
    for ax in axes.flat[len(cases):]:
        ax.set_visible(False)
    for ax, case in zip(axes.flat, cases):
        for config in CONFIGS:
            sel = [r for r in rows if r["case"] == case and r["config"] == config]
            ax.loglog([r["time_loop_cpu_s"] for r in sel], [r["error"] for r in sel], STYLES[config], label=config)
        plot.label(ax, "CPU time of the time loop [s]", title=CASES[case]["title"], size=9)
    for row in axes:
        row[0].set_ylabel("error against the reference")
    axes[0][0].legend(fontsize=8)
    plot.save(fig, path)


def main():
    p = parser(__doc__)
    p.add_argument("build")
    p.add_argument("out")
    p.add_argument("ref_dir")
    p.add_argument("--quick", action="store_true", help="one mesh per case")
    p.add_argument("--cases", default=",".join(CASES))
    a = p.parse_args()
    cases, rows = a.cases.split(","), []
    for case, config in ((case, config) for case in cases for config in CONFIGS):
        for cells in CASES[case]["quick" if a.quick else "cells"]:
            rows.append(case_row(a, case, cells, config))
            print(rows[-1], flush=True)
    outputs.write_csv(os.path.join(a.out, "shock-capturing.csv"), rows)
    chart(rows, cases, os.path.join(a.out, "shock-capturing.png"))


if __name__ == "__main__":
    main()
