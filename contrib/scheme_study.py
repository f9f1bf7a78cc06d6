#!/usr/bin/python3
"""Work precision of the time integrators (Time stepping/scheme): error
against CPU time for SSP-RK3 and deal.II's low-storage schemes, each at 0.95
of its CFL limit for the degree (the table of dg::cfl_limit in
source/dg/parameters.cc, read from there), on the smooth linear wave of the
layered-strip scene with its exact solution, in 1D (prm/elasticity_linear_wave.prm,
line engine, to t = 10) and 2D (tests/hardening/linear_wave_2d.prm, MatrixFree,
to t = 2), P2 and P3, meshes refined by 2.

    /usr/bin/python3 contrib/scheme_study.py BUILD_DIR OUT_DIR

writes OUT_DIR/schemes.csv (one row per run), schemes-1d.png, schemes-2d.png
and schemes.md (the cheapest scheme and degree per target error). About
3 min on one core; runs one process at a time.
"""
import argparse
import csv
import os
import re
import subprocess
import sys
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
SCHEMES = ["ssp_rk3", "lsrk_5_4", "lsrk_7_4", "lsrk_9_5"]
CASES = {"1d": ("prm/elasticity_linear_wave.prm", 10., [16, 32, 64, 128, 256, 512]),
         "2d": ("tests/hardening/linear_wave_2d.prm", 2., [8, 16, 32, 64])}
TARGETS = [1e-4, 1e-6, 1e-8]


def cfl_limits():
    """{scheme: [limit for p = 0..4]} from the program's table."""
    text = open(os.path.join(ROOT, "source/dg/parameters.cc")).read()
    rows = re.findall(r"\{([\d.,\s]+)\},?\}?;?\s*// (\w+)", text)
    return {name: [float(x) for x in values.split(",")] for values, name in rows}


def run(build, out, case, scheme, degree, cfl):
    prm, final_time, cells = CASES[case]
    d = os.path.join(out, "%s-%s-p%d" % (case, scheme, degree))
    cmd = [os.path.join(build, "granular_dg"), os.path.join(ROOT, prm),
           "--set", "Output/directory=" + d, "--set", "Output/overwrite=true",
           "--set", "Output/progress interval=0", "--set", "Output/write vtu=false",
           "--set", "Convergence/enabled=true", "--set", "Convergence/degrees=%d" % degree,
           "--set", "Convergence/cells=" + ",".join(map(str, cells)),
           "--set", "Convergence/CFL numbers=%.4f" % cfl,
           "--set", "Time stepping/final time=%g" % final_time,
           "--set", "Time stepping/scheme=" + scheme]
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit("failed: %s\n%s" % (" ".join(cmd), p.stderr[-500:]))
    with open(os.path.join(d, "convergence.csv")) as f:
        rows = [r for r in csv.DictReader(l for l in f if not l.startswith("#"))]
    return [{"case": case, "scheme": scheme, "degree": degree, "cfl": cfl,
             "cells": int(r["cells"]), "dofs": int(r["dofs"]),
             "l2_error": float(r["l2_error"]), "cpu_s": float(r["time_loop_cpu_s"]),
             "steps": int(r["time_steps"])} for r in rows]


def chart(rows, case, path):
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=(6.4, 4.6))
    for scheme in SCHEMES:
        for degree, style in ((2, "-o"), (3, "--s")):
            r = [x for x in rows if x["case"] == case and x["scheme"] == scheme and x["degree"] == degree]
            ax.loglog([x["cpu_s"] for x in r], [x["l2_error"] for x in r], style, ms=4,
                      label="%s P%d" % (scheme, degree))
    ax.set_xlabel("CPU time of the time loop [s]")
    ax.set_ylabel("L2 error at the final time")
    ax.set_title("linear wave %s: schemes at 0.95 of their CFL limit" % case.upper())
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=7, ncol=2)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


def cheapest(rows):
    """Per case and target error: the run of least CPU reaching it."""
    lines = ["| case | target L2 error | cheapest (scheme, degree, cells) | CPU s | next best scheme | CPU s |",
             "|---|---|---|---|---|---|"]
    for case in CASES:
        for target in TARGETS:
            ok = sorted((x for x in rows if x["case"] == case and x["l2_error"] <= target),
                        key=lambda x: x["cpu_s"])
            if not ok:
                lines.append("| %s | %g | none reaches it | | | |" % (case, target))
                continue
            best = ok[0]
            other = next((x for x in ok if x["scheme"] != best["scheme"]), None)
            lines.append("| %s | %g | %s P%d, %d cells | %.3g | %s | %s |" % (
                case, target, best["scheme"], best["degree"], best["cells"], best["cpu_s"],
                "%s P%d, %d cells" % (other["scheme"], other["degree"], other["cells"]) if other else "",
                "%.3g" % other["cpu_s"] if other else ""))
    return "\n".join(lines) + "\n"


def main():
    a = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    a.add_argument("build")
    a.add_argument("out")
    args = a.parse_args()
    os.makedirs(args.out, exist_ok=True)
    limits = cfl_limits()
    rows = []
    with tempfile.TemporaryDirectory() as runs:  # the runs' own files are not kept
        for case in CASES:
            for degree in (2, 3):
                for scheme in SCHEMES:
                    rows += run(args.build, runs, case, scheme, degree,
                                0.95 * limits[scheme][degree])
    with open(os.path.join(args.out, "schemes.csv"), "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=list(rows[0].keys()))
        w.writeheader()
        w.writerows(rows)
    for case in CASES:
        chart(rows, case, os.path.join(args.out, "schemes-%s.png" % case))
    with open(os.path.join(args.out, "schemes.md"), "w") as f:
        f.write(cheapest(rows))
    print(cheapest(rows))


if __name__ == "__main__":
    main()
