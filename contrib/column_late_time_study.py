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
slide again) after t = 100 and the first such time. Writes OUT_DIR/late-time.csv.
"""
import argparse
import csv
import os
import subprocess

import numpy as np


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("build")
    p.add_argument("out")
    p.add_argument("--final-time", type=float, default=1000)
    a = p.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    prm = os.path.join(here, "..", "prm", "column_m1.5.prm")
    rows = []
    for weights, limiters in (("consistent", ("characteristic", "componentwise")),
                              ("printed", ("characteristic",))):
        for limiter in limiters:
            for cells in (200, 400, 800):
                d = os.path.join(a.out, "%s-%s-%d" % (weights, limiter, cells))
                if not os.path.exists(os.path.join(d, "summary.json")):
                    subprocess.run([os.path.join(a.build, "granular_dg"), prm,
                                    "--set", "Output/directory=" + d, "--set", "Output/overwrite=true",
                                    "--set", "Mesh/length=10", "--set", "Mesh/cells=%d" % cells,
                                    "--set", "Time stepping/final time=%g" % a.final_time,
                                    "--set", "Output/output interval=0",
                                    # the full computation: the study measures drifts
                                    "--set", "Time stepping/skip tolerance=0",
                                    "--set", "Output/write vtu=false",
                                    "--set", "Diagnostics/write sgn map=false",
                                    "--set", "Diagnostics/sample interval=1",
                                    "--set", "Limiter/scheme=" + limiter,
                                    "--set", "Physics/friction stage weights=" + weights],
                                   check=True, stdout=subprocess.DEVNULL)
                h = np.genfromtxt(os.path.join(d, "history.csv"), delimiter=",", names=True)
                i100 = int(np.argmin(abs(h["time"] - 100)))
                crit = h["critical_loadings"]
                late = np.nonzero(crit > crit[i100])[0]
                rows.append({"weights": weights, "limiter": limiter, "cells": cells,
                             "probe_strain_t100": h["probe_strain"][i100],
                             "probe_strain_final": h["probe_strain"][-1],
                             "drift": h["probe_strain"][-1] - h["probe_strain"][i100],
                             "critical_loadings_after_t100": int(crit[-1] - crit[i100]),
                             "first_late_critical_time": h["time"][late[0]] if len(late) else -1,
                             "max_velocity_final": h["max_velocity"][-1]})
                print(rows[-1], flush=True)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "late-time.csv"), "w") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)


if __name__ == "__main__":
    main()
