#!/usr/bin/python3
"""Work-precision chart of the column scene: the L1 error (strain + velocity)
against the exact solution of the linear case (m = 1, t = 4, after the first
stop, with the frozen region) versus the CPU time of the time loop, for DG
degrees 0-3 on 25-1600 cells of (0, 5), CFL 0.9/(2p+1) (the paper: 0.2 for P2).

    contrib/column_work_precision.py BUILD_DIR OUT_DIR [--engine line|matrix_free]

Writes OUT_DIR/work-precision.csv and doc-ready OUT_DIR/work-precision.png.
One run of granular_dg per degree (its convergence-study mode).
"""
import argparse
import csv
import os
import subprocess

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt


def main():
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    p.add_argument("build")
    p.add_argument("out")
    p.add_argument("--engine", default="auto")
    p.add_argument("--cells", default="25,50,100,200,400,800,1600")
    a = p.parse_args()
    here = os.path.dirname(os.path.abspath(__file__))
    prm = os.path.join(here, "..", "tests", "column", "m1_base.prm")
    rows = []
    for degree in range(4):
        d = os.path.join(a.out, "p%d" % degree)
        subprocess.run([os.path.join(a.build, "granular_dg"), prm,
                        "--set", "Output/directory=" + d, "--set", "Output/overwrite=true",
                        "--set", "Output/output times=", "--set", "Convergence/enabled=true",
                        "--set", "Convergence/degrees=%d" % degree,
                        "--set", "Convergence/cells=" + a.cells,
                        "--set", "Time stepping/CFL number=%g" % (0.9 / (2 * degree + 1)),
                        "--set", "Discretization/engine=" + a.engine],
                       check=True, stdout=subprocess.DEVNULL)
        with open(os.path.join(d, "convergence.csv")) as f:
            for r in csv.DictReader(f):
                rows.append(r)
    os.makedirs(a.out, exist_ok=True)
    with open(os.path.join(a.out, "work-precision.csv"), "w") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)

    fig, ax = plt.subplots(figsize=(6.5, 4.5))
    for degree in range(4):
        sel = [r for r in rows if int(float(r["degree"])) == degree]
        ax.loglog([float(r["time_loop_cpu_s"]) for r in sel], [float(r["l1_error"]) for r in sel],
                  "o-", label="P%d" % degree)
    ax.set_xlabel("CPU time of the time loop [s]")
    ax.set_ylabel("L1 error (u and v) at t = 4")
    ax.set_title("column, m = 1: error against the exact solution")
    ax.grid(alpha=0.3, which="both")
    ax.legend()
    fig.tight_layout()
    fig.savefig(os.path.join(a.out, "work-precision.png"), dpi=110)


if __name__ == "__main__":
    main()
