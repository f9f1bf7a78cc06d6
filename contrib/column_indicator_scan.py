#!/usr/bin/python3
"""The column's shock capturing against the exact solution of the linear case
(doc/column.md, "Shock capturing"): for each choice of limiting (CHOICES),
tests/column/m1_base.prm (m = 1, P2, t = 4) on 100, 200 and 400 cells (the
strain error at (3, 4), the L1 error of (strain, velocity), the cells flagged
at t = 4, the largest velocity in a stuck cell) and prm/column_m1.prm to
t = 40 (velocity sign flips, final strain against the stationary profile,
scatter of the frozen sgn(v) on 4 < z < 13.6 about a degree-6 fit).

    contrib/column_indicator_scan.py BUILD_DIR OUT_DIR

Prints a markdown table and writes OUT_DIR/column-indicator-scan.csv; runs
whose directory has a summary.json are reused (about 2 minutes in all)."""
import os

import numpy as np

from granular_dg import outputs, parser
from granular_dg.compare import value_at
from granular_dg.run import run_case

# u(3, 4) of the closed form (include/granular_dg/equations/column/
# closed_form.h, u_b = -1): z = 3 slides until t_s(3) = 4.7196
EXACT_STRAIN_3_4 = -0.147769340095

# name: extra parameters (the limiter is the characteristic one of the prm)
CHOICES = {
    "everywhere": ["Limiter/indicator=everywhere"],
    "modal_energy (automatic threshold 2.1e-3)": ["Limiter/indicator=modal_energy"],
    **{"modal_energy, threshold %g" % t: ["Limiter/indicator=modal_energy",
                                           "Limiter/indicator threshold=%g" % t]
       for t in (0.01, 0.05, 0.1, 0.2, 0.3, 0.5)},
    "subcell blending, no limiter": ["Limiter/scheme=none", "Limiter/subcell blending=true"],
    "no limiter": ["Limiter/scheme=none"],
}
CELLS = (100, 200, 400)


def multiplier_scatter(directory):
    d = outputs.read_table(os.path.join(directory, "final-profile.csv"))
    frozen = (d["z"] > 4) & (d["z"] < 13.6)
    z, s = d["z"][frozen], d["sgn_v"][frozen]
    return float(np.sqrt(np.mean((s - np.polyval(np.polyfit(z, s, 6), z)) ** 2)))


def choice_row(a, i, name, settings):
    row = {"choice": name}
    run = lambda prm, d, sets: run_case(a.build, prm, os.path.join(a.out, d), ["Output/write vtu=false"] + sets,
                                        reuse=True, check=True)
    for cells in CELLS:
        r = run("tests/column/m1_base.prm", "base-%d-%d" % (i, cells),
                settings + ["Mesh/cells=%d" % cells, "Output/profile points per cell=3"])
        row["error_3_4_%d" % cells] = abs(value_at(outputs.profile_at(r.directory, 4), "strain", 3.)
                                          - EXACT_STRAIN_3_4)
        if cells == 200:
            errors, last = r.summary["errors"], outputs.timeseries(r.directory).rows()[-1]
            row["l1"] = errors["component_0_l1_l2_linf"][0] + errors["component_1_l1_l2_linf"][0]
            row["max_stuck_velocity"] = r.summary["diagnostics"]["max_stuck_velocity"]
            row["flagged_t4"] = next(("%d" % last[k] for k in ("flagged_cells", "blended_cells") if k in last), "-")
    r = run("prm/column_m1.prm", "m1-%d" % i, settings)
    row["multiplier_scatter"] = multiplier_scatter(r.directory)
    row["sign_flips_t40"] = r.summary["diagnostics"]["velocity_sign_flips"]
    row["final_vs_stationary"] = r.summary["diagnostics"]["auxiliary_max_difference"]
    return row


def main():
    p = parser(__doc__)
    p.add_argument("build")
    p.add_argument("out")
    a = p.parse_args()
    rows = [choice_row(a, i, name, settings) for i, (name, settings) in enumerate(CHOICES.items())]
    outputs.write_csv(os.path.join(a.out, "column-indicator-scan.csv"), rows)
    print(outputs.markdown(
        ["choice", "error of u at (3, 4), 100 / 200 / 400 cells", "L1 (u, v), 200 cells", "flagged at t = 4",
         "max v in stuck cells", "sign flips to t = 40", "final u vs stationary", "scatter of frozen sgn(v)"],
        [[r["choice"], " / ".join("%.2g" % r["error_3_4_%d" % c] for c in CELLS), "%.3g" % r["l1"], r["flagged_t4"],
          "%.3g" % r["max_stuck_velocity"], "%d" % r["sign_flips_t40"], "%.2g" % r["final_vs_stationary"],
          "%.3f" % r["multiplier_scatter"]] for r in rows]), end="")


if __name__ == "__main__":
    main()
