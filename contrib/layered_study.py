#!/usr/bin/python3
"""The layered 1D strip (prm/layered_1d.prm, case (b)) at t = 240: the naive
flux against the interface-aware one (CONFIGS), and the work-precision chart
(doc/layered_strip.md, "Work precision").

    contrib/layered_study.py BUILD_DIR OUT_DIR REFERENCE_MODES_CSV [--quick]
        [--only aware-indicator --rows-from doc/figures/layered_study.csv]

Degrees 1-3 on 2-32 cells per layer (p x cells per layer <= 32, the
reference's resolution), CFL 0.8/(2p+1). Per run: the L1 strain error against
the reference (a modes-NNNN.csv of a finer run), the largest interface stress
jump, the shift of the leading stress peak against the reference's, the CPU
time of the time loop: OUT_DIR/layered-study.csv, layered-work-precision.png.
Runs whose directory has a summary.json are reused; --only runs some
configurations and takes the others' rows from an earlier study (--rows-from)."""
import os

import numpy as np

from granular_dg import outputs, parser, plot
from granular_dg.run import NO_SNAPSHOTS, run_case

# name: (numerical flux, limiter, troubled-cell indicator)
CONFIGS = {
    "aware": ("impedance", "flux_variables", "everywhere"),
    "aware-indicator": ("impedance", "flux_variables", "modal_energy"),
    "aware-nolim": ("impedance", "none", "everywhere"),
    "naive": ("local_lax_friedrichs", "componentwise", "everywhere"),
}
STYLES = {"naive": "s--", "aware": "o-", "aware-indicator": "D-.", "aware-nolim": "^:"}


def leading_peak(directory):
    """x of the largest stress maximum in the leading 40 length units of the last profile."""
    t = outputs.read_table(outputs.latest(directory, "profile"))
    x, s = t["x"], t["stress"]
    front = x[np.nonzero(np.abs(s) > 1e-3 * np.max(np.abs(s)))[0][-1]]
    return x[x > front - 40][np.argmax(s[x > front - 40])]


def study_row(a, name, degree, per_layer, x_ref):
    flux, limiter, indicator = CONFIGS[name]
    r = run_case(a.build, "prm/layered_1d.prm", os.path.join(a.out, "%s-p%d-%d" % (name, degree, per_layer)),
                 NO_SNAPSHOTS + ("Mesh/cells x=%d" % (300 * per_layer), "Discretization/degree=%d" % degree,
                                 "Discretization/numerical flux=" + flux, "Limiter/scheme=" + limiter,
                                 "Limiter/indicator=" + indicator,
                                 "Time stepping/CFL number=%g" % (0.8 / (2 * degree + 1)),
                                 "Exact solution/reference file=" + os.path.abspath(a.reference)),
                 reuse=True, check=True)
    s = r.summary
    return {"config": name, "flux": flux, "limiter": limiter, "indicator": indicator, "degree": degree,
            "cells_per_layer": per_layer, "n_dofs": s["n_dofs"],
            "l1_strain_error": s["errors"]["component_0_l1_l2_linf"][0],
            "interface_stress_jump_max": s["diagnostics"]["interface_stress_jump_max"],
            "min_strain": s["diagnostics"]["min_strain"], "leading_peak_shift": leading_peak(r.directory) - x_ref,
            "time_loop_cpu_s": s["time_loop_cpu_s"], "dof_updates_per_cpu_s": s["dof_updates_per_cpu_s_per_rank"]}


def earlier_rows(path, rerun):
    """The rows of an earlier study for the configurations not rerun."""
    rows = [r for r in outputs.read_table(path, numbers=False).rows() if r["config"] not in rerun]
    for r in rows:
        r.update({k: int(r[k]) for k in ("degree", "cells_per_layer", "n_dofs")})
        r.setdefault("indicator", "everywhere")
    return rows


def chart(rows, degrees, path):
    fig, ax = plot.subplots(figsize=(7, 5))
    for name in CONFIGS:
        for degree in degrees:
            sel = [r for r in rows if r["config"] == name and r["degree"] == degree and r["l1_strain_error"] > 0]
            if sel:
                ax.loglog([r["time_loop_cpu_s"] for r in sel], [r["l1_strain_error"] for r in sel],
                          STYLES[name], label="%s P%d" % (name, degree))
    # Clawpack's second-order f-wave finite volumes on the same case (doc/layered_strip.md)
    ax.loglog([1, 5], [0.09, 0.04], "k*", ms=12, label="Clawpack f-wave")
    plot.label(ax, "CPU time of the time loop [s]", "L1 error of the strain at t = 240",
               "layered 1D strip: error against the reference vs CPU time")
    ax.legend(fontsize=7, ncol=2)
    plot.save(fig, path)


def main():
    p = parser(__doc__)
    p.add_argument("build")
    p.add_argument("out")
    p.add_argument("reference")
    p.add_argument("--quick", action="store_true", help="degree 2, 4 and 8 cells per layer only")
    p.add_argument("--only", help="comma-separated configurations to run (default: all)")
    p.add_argument("--rows-from", help="an earlier layered-study.csv: the rows of the configurations not run")
    a = p.parse_args()
    run = a.only.split(",") if a.only else list(CONFIGS)
    for name in run:
        if name not in CONFIGS:
            p.error("--only: unknown configuration '%s' (allowed: %s)" % (name, ", ".join(CONFIGS)))
    x_ref = leading_peak(os.path.dirname(os.path.abspath(a.reference)))
    degrees = (2,) if a.quick else (1, 2, 3)
    rows = earlier_rows(a.rows_from, run) if a.rows_from else []
    resolutions = (4, 8) if a.quick else (2, 4, 8, 16, 32)
    for name, degree, per_layer in ((n, d, c) for n in run for d in degrees for c in resolutions):
        if degree * per_layer <= 32:  # finer: as fine as the reference (P3 at 32 cells per layer)
            rows.append(study_row(a, name, degree, per_layer, x_ref))
            print(rows[-1], flush=True)
    outputs.write_csv(os.path.join(a.out, "layered-study.csv"), rows)
    chart(rows, degrees, os.path.join(a.out, "layered-work-precision.png"))


if __name__ == "__main__":
    main()
