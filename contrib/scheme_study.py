#!/usr/bin/python3
"""Work precision of the time integrators (doc/study/README.md, "Time
integrators"): the L2 error against CPU time of SSP-RK3 and deal.II's
low-storage schemes, each at 0.95 of its CFL limit for the degree (the
program's table, dg::cfl_limit), P2 and P3, on the smooth linear wave of the
layered strip in 1D and 2D (CASES: case, final time, meshes):

    /usr/bin/python3 contrib/scheme_study.py BUILD_DIR OUT_DIR

writes OUT_DIR/schemes.csv (a row per run), schemes-1d.png, schemes-2d.png and
schemes.md (the cheapest scheme and degree per target error); one process at a time.
"""
import os
import tempfile
from pathlib import Path

from granular_dg import arguments, outputs, plot
from granular_dg.run import cfl_limits, run_case

SCHEMES = ["ssp_rk3", "lsrk_5_4", "lsrk_7_4", "lsrk_9_5"]
CASES = {"1d": ("prm/elasticity_linear_wave.prm", 10., [16, 32, 64, 128, 256, 512]),
         "2d": ("tests/hardening/linear_wave_2d.prm", 2., [8, 16, 32, 64])}
TARGETS = [1e-4, 1e-6, 1e-8]


def scheme_rows(build, runs, case, scheme, degree, cfl):
    prm, final_time, cells = CASES[case]
    run = run_case(build, prm, os.path.join(runs, "%s-%s-p%d" % (case, scheme, degree)), [
        "Output/write vtu=false", "Convergence/enabled=true", "Convergence/degrees=%d" % degree,
        "Convergence/cells=" + ",".join(map(str, cells)), "Convergence/CFL numbers=%.4f" % cfl,
        "Time stepping/final time=%g" % final_time, "Time stepping/scheme=" + scheme], check=True)
    return [{"case": case, "scheme": scheme, "degree": degree, "cfl": cfl, "cells": int(r["cells"]),
             "dofs": int(r["dofs"]), "l2_error": float(r["l2_error"]), "cpu_s": float(r["time_loop_cpu_s"]),
             "steps": int(r["time_steps"])} for r in outputs.convergence(run.directory).rows()]


def chart(rows, case, path):
    fig, ax = plot.subplots(figsize=(6.4, 4.6))
    for scheme in SCHEMES:
        for degree, style in ((2, "-o"), (3, "--s")):
            r = outputs.select(rows, case=case, scheme=scheme, degree=degree)
            ax.loglog([x["cpu_s"] for x in r], [x["l2_error"] for x in r], style, ms=4,
                      label="%s P%d" % (scheme, degree))
    plot.label(ax, "CPU time of the time loop [s]", "L2 error at the final time",
               "linear wave %s: schemes at 0.95 of their CFL limit" % case.upper(), legend=(7, 2))
    plot.save(fig, path, dpi=120)


def cheapest(rows):
    """Per case and target error: the run of least CPU reaching it."""
    table = []
    for case, target in ((c, t) for c in CASES for t in TARGETS):
        ok = sorted((x for x in rows if x["case"] == case and x["l2_error"] <= target), key=lambda x: x["cpu_s"])
        other = next((x for x in ok if x["scheme"] != ok[0]["scheme"]), None)
        describe = lambda x: ["%s P%d, %d cells" % (x["scheme"], x["degree"], x["cells"]), "%.3g" % x["cpu_s"]] \
            if x else ["", ""]
        table.append([case, "%g" % target] + (describe(ok[0]) if ok else ["none reaches it", ""]) + describe(other))
    return outputs.markdown(["case", "target L2 error", "cheapest (scheme, degree, cells)", "CPU s",
                             "next best scheme", "CPU s"], table)


if __name__ == "__main__":
    a = arguments(__doc__, ["build", "out"])
    os.makedirs(a.out, exist_ok=True)
    limits = cfl_limits()
    with tempfile.TemporaryDirectory() as runs:  # the runs' own files are not kept
        rows = [r for case in CASES for degree in (2, 3) for scheme in SCHEMES
                for r in scheme_rows(a.build, runs, case, scheme, degree, 0.95 * limits[scheme][degree])]
    outputs.write_csv(os.path.join(a.out, "schemes.csv"), rows)
    for case in CASES:
        chart(rows, case, os.path.join(a.out, "schemes-%s.png" % case))
    table = cheapest(rows)
    Path(a.out, "schemes.md").write_text(table)
    print(table)
