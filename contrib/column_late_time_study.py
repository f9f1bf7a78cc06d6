#!/usr/bin/python3
"""Late-time study of the column (m = 3/2, the paper's 400 P2 cells on (0, 10)):
does material at rest keep its strain, and is the paper's late critical
loading (t ~ 1520) physical or numerical?

    contrib/column_late_time_study.py BUILD_DIR OUT_DIR [--final-time 1000]

Runs 200, 400 and 800 cells with the characteristic and the componentwise
limiter and the consistent friction stage weights (dt, dt/4, 2dt/3), and the
same resolutions with the weights printed in the paper (dt, dt/2, dt). For
each run: the strain at z = 0.5 (stuck since t ~ 3) at t = 100 and at the
final time, its drift, the number of critical loadings (stuck cells forced to
slide again) after t = 100 and the first such time. Writes
OUT_DIR/late-time.csv; runs whose directory has a summary.json are reused.
"""
import os

import numpy as np

from granular_dg import outputs, parser
from granular_dg.run import run_case


def late_time_row(a, weights, limiter, cells):
    r = run_case(a.build, "prm/column_m1.5.prm", os.path.join(a.out, "%s-%s-%d" % (weights, limiter, cells)), [
        "Mesh/length=10", "Mesh/cells=%d" % cells, "Time stepping/final time=%g" % a.final_time,
        "Output/output interval=0", "Output/write vtu=false",
        "Time stepping/skip tolerance=0",  # the full computation: the study measures drifts
        "Diagnostics/write sgn map=false", "Diagnostics/sample interval=1", "Limiter/scheme=" + limiter,
        "Physics/friction stage weights=" + weights], reuse=True, check=True)
    h = outputs.history(r.directory)
    i100, crit, strain = int(np.argmin(abs(h["time"] - 100))), h["critical_loadings"], h["probe_strain"]
    late = np.nonzero(crit > crit[i100])[0]
    return {"weights": weights, "limiter": limiter, "cells": cells, "probe_strain_t100": strain[i100],
            "probe_strain_final": strain[-1], "drift": strain[-1] - strain[i100],
            "critical_loadings_after_t100": int(crit[-1] - crit[i100]),
            "first_late_critical_time": h["time"][late[0]] if len(late) else -1,
            "max_velocity_final": h["max_velocity"][-1]}


def main():
    p = parser(__doc__)
    p.add_argument("build")
    p.add_argument("out")
    p.add_argument("--final-time", type=float, default=1000)
    a = p.parse_args()
    rows = []
    for weights, limiters in (("consistent", ("characteristic", "componentwise")), ("printed", ("characteristic",))):
        for limiter, cells in ((l, c) for l in limiters for c in (200, 400, 800)):
            rows.append(late_time_row(a, weights, limiter, cells))
            print(rows[-1], flush=True)
    outputs.write_csv(os.path.join(a.out, "late-time.csv"), rows)


if __name__ == "__main__":
    main()
