#!/usr/bin/python3
"""Work-precision chart of the column scene: the L1 error (strain + velocity)
against the exact solution of the linear case (m = 1, t = 4, after the first
stop, with the frozen region) versus the CPU time of the time loop, for DG
degrees 0-3 on 25-1600 cells of (0, 5), CFL 0.9/(2p+1) (the paper: 0.2 for P2).

    contrib/column_work_precision.py BUILD_DIR OUT_DIR [--engine line|matrix_free] [--cells 25,50,...]

Writes OUT_DIR/work-precision.csv (the convergence.csv of each degree) and
doc-ready OUT_DIR/work-precision.png. One run of granular_dg per degree (its
convergence-study mode).
"""
import csv
import os

from granular_dg import outputs, parser, plot
from granular_dg.run import run_case

p = parser(__doc__)
p.add_argument("build")
p.add_argument("out")
p.add_argument("--engine", default="auto")
p.add_argument("--cells", default="25,50,100,200,400,800,1600")
a = p.parse_args()
fig, ax = plot.subplots(figsize=(6.5, 4.5))
rows = []
for degree in range(4):
    r = run_case(a.build, "tests/column/m1_base.prm", os.path.join(a.out, "p%d" % degree), [
        "Output/output times=", "Convergence/enabled=true", "Convergence/degrees=%d" % degree,
        "Convergence/cells=" + a.cells, "Time stepping/CFL number=%g" % (0.9 / (2 * degree + 1)),
        "Discretization/engine=" + a.engine], check=True)
    t = outputs.convergence(r.directory)
    ax.loglog(t["time_loop_cpu_s"], t["l1_error"], "o-", label="P%d" % degree)
    with open(t.path, newline="") as f:  # the rows as the program wrote them
        rows += list(csv.reader(l for l in f if not l.startswith("#")))[0 if degree == 0 else 1:]
with open(os.path.join(a.out, "work-precision.csv"), "w", newline="") as f:
    csv.writer(f).writerows(rows)
plot.label(ax, "CPU time of the time loop [s]", "L1 error (u and v) at t = 4",
           "column, m = 1: error against the exact solution", legend=10)
plot.save(fig, os.path.join(a.out, "work-precision.png"))
