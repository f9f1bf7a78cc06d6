#!/usr/bin/python3
"""The column's shock capturing against the exact solution of the linear case
(doc/column.md, "Shock capturing"): for each choice of limiting,
  - tests/column/m1_base.prm (m = 1 on (0, 5), P2, t = 4) on 100, 200 (the
    paper's dx = 0.025) and 400 cells: the strain error at (z, t) = (3, 4)
    against the closed form, the L1 error of (strain, velocity), the cells
    flagged at t = 4 and the largest velocity in a stuck cell;
  - prm/column_m1.prm (to t = 40): the velocity sign flips at the fronts, the
    largest difference of the final strain from the stationary profile, and
    the cell-to-cell scatter of the frozen friction multiplier sgn(v) on
    4 < z < 13.6 (rms of its difference from a degree-6 fit; the exact
    multiplier is smooth there).

    contrib/column_indicator_scan.py BUILD_DIR OUT_DIR

Prints a markdown table and writes OUT_DIR/column-indicator-scan.csv; runs
whose directory has a summary.json are reused (about 2 minutes in all).
"""
import argparse
import csv
import json
import os
import subprocess

import numpy as np

from shock_capturing_study import profile_value

HERE = os.path.dirname(os.path.abspath(__file__))
# u(3, 4) of the closed form (include/granular_dg/equations/friction_column/
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


def run(build, prm, out, settings):
    if not os.path.exists(os.path.join(out, "summary.json")):
        args = [os.path.join(build, "granular_dg"), os.path.join(HERE, "..", prm),
                "--set", "Output/directory=" + out, "--set", "Output/overwrite=true",
                "--set", "Output/write vtu=false", "--set", "Output/progress interval=0"]
        for s in settings:
            args += ["--set", s]
        subprocess.run(args, check=True, stdout=subprocess.DEVNULL)
    with open(os.path.join(out, "summary.json")) as f:
        return json.load(f)


def multiplier_scatter(directory):
    d = np.genfromtxt(os.path.join(directory, "final-profile.csv"), delimiter=",", names=True)
    frozen = (d["z"] > 4) & (d["z"] < 13.6)
    z, s = d["z"][frozen], d["sgn_v"][frozen]
    return float(np.sqrt(np.mean((s - np.polyval(np.polyfit(z, s, 6), z)) ** 2)))


def flagged_at_end(directory):
    with open(os.path.join(directory, "timeseries.csv")) as f:
        rows = list(csv.DictReader(f))
    return rows[-1].get("flagged_cells", rows[-1].get("blended_cells", "-"))


def main():
    parser = argparse.ArgumentParser(description=__doc__,
                                     formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument("build")
    parser.add_argument("out")
    a = parser.parse_args()
    os.makedirs(a.out, exist_ok=True)
    rows = []
    for i, (name, settings) in enumerate(CHOICES.items()):
        row = {"choice": name}
        for cells in CELLS:
            d = os.path.join(a.out, "base-%d-%d" % (i, cells))
            diag = run(a.build, "tests/column/m1_base.prm", d,
                       settings + ["Mesh/cells=%d" % cells, "Output/profile points per cell=3"])
            # the prm writes t = 1, 2 and the final t = 4
            row["error_3_4_%d" % cells] = abs(profile_value(os.path.join(d, "profile-0003.csv"), "strain", 3.)
                                              - EXACT_STRAIN_3_4)
            if cells == 200:
                errors = diag["errors"]
                row["l1"] = errors["component_0_l1_l2_linf"][0] + errors["component_1_l1_l2_linf"][0]
                row["max_stuck_velocity"] = diag["diagnostics"]["max_stuck_velocity"]
                row["flagged_t4"] = flagged_at_end(d)
        d = os.path.join(a.out, "m1-%d" % i)
        diag = run(a.build, "prm/column_m1.prm", d, settings)["diagnostics"]
        row["multiplier_scatter"] = multiplier_scatter(d)
        row["sign_flips_t40"] = diag["velocity_sign_flips"]
        row["final_vs_stationary"] = diag["auxiliary_max_difference"]
        rows.append(row)
    with open(os.path.join(a.out, "column-indicator-scan.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0]))
        w.writeheader()
        w.writerows(rows)
    print("| choice | error of u at (3, 4), 100 / 200 / 400 cells | L1 (u, v), 200 cells "
          "| flagged at t = 4 | max v in stuck cells | sign flips to t = 40 | final u vs stationary "
          "| scatter of frozen sgn(v) |")
    print("|---|---|---|---|---|---|---|---|")
    for r in rows:
        print("| %s | %s | %.3g | %s | %.3g | %d | %.2g | %.3f |" % (
            r["choice"], " / ".join("%.2g" % r["error_3_4_%d" % c] for c in CELLS), r["l1"],
            r["flagged_t4"], r["max_stuck_velocity"], r["sign_flips_t40"], r["final_vs_stationary"],
            r["multiplier_scatter"]))


if __name__ == "__main__":
    main()
