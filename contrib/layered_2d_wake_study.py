#!/usr/bin/python3
"""Work precision of the 2D layered strip's wake (prm/layered_2d.prm, case (c)):
P2 and P3, without and with subcell blending, on 200 x 20, 400 x 40 and
800 x 80 cells (per [0, 100] x [0, 10]), against a converged reference,
P2 1600 x 160 without a limiter. Error: the L1 of the stress on the slice
y = 5 over the wake x < 15 at t = 20 (contrib/layered_2d_wake.py); work: the
CPU time of the time loop, summed over the ranks.

    contrib/layered_2d_wake_study.py BUILD RUNS OUT [--reference DIR ...] [--ranks N]

RUNS: where the runs go (a run whose summary.json says completed is reused);
OUT: wake-work-precision.{csv,png}, a panel per reference. --reference (may
repeat): reference runs (default: RUNS/p2_1600_none). A reference named
RUNS/pD_N_none or RUNS/pD_N_blend is run if it is missing (P2 1600 x 160:
6.5 min of wall time on two cores; P3 1600 x 160: 13.5 min, blended 21 min). Every run is on [0, 32] x [0, 10] with the cells of [0, 100] per unit
length: up to t = 20 the waves reach x ~ 25, so the strip's far end never
matters (the slices of [0, 32] and [0, 100] agree to 1e-15, measured).
"""
import csv
import json
import os
import re
import subprocess
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from layered_2d_wake import differences, slices, total_variation  # noqa: E402

LENGTH, T = 32, 20.0
CFL = {2: 0.15, 3: 0.1}  # the prm's 0.15 for P2; 0.1 for P3 (its stable CFL)


def run(build, runs, name, degree, cells, blending, ranks):
    """runs RUNS/name unless it completed before; returns its summary"""
    out = os.path.join(runs, name)
    summary = os.path.join(out, "summary.json")
    if os.path.exists(summary):
        with open(summary) as f:
            done = json.load(f)
        if done["status"] == "completed":
            return done
    here = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
    cmd = ["mpirun", "--allow-run-as-root", "--oversubscribe", "-np", str(ranks),
           os.path.join(build, "granular_dg"), os.path.join(here, "prm/layered_2d.prm"),
           "--set", "Discretization/degree=%d" % degree,
           "--set", "Time stepping/CFL number=%g" % CFL[degree],
           "--set", "Time stepping/final time=%g" % T,
           "--set", "Mesh/x max=%d" % LENGTH,
           "--set", "Mesh/cells x=%d" % (cells * LENGTH // 100),
           "--set", "Mesh/cells y=%d" % (cells // 10),
           "--set", "Output/directory=" + out]
    if blending:
        cmd += ["--set", "Limiter/scheme=none", "--set", "Limiter/subcell blending=true"]
    print("running", name, flush=True)
    with open(out + ".log", "w") as log:
        subprocess.run(cmd, stdout=log, stderr=subprocess.STDOUT, check=True)
    with open(summary) as f:
        return json.load(f)


def main():
    args, references, ranks = sys.argv[1:], [], 2
    while "--reference" in args or "--ranks" in args:
        i = args.index("--reference") if "--reference" in args else args.index("--ranks")
        if args[i] == "--reference":
            references.append(args[i + 1])
        else:
            ranks = int(args[i + 1])
        del args[i:i + 2]
    if len(args) != 3:
        raise SystemExit(__doc__)
    build, runs, out = args
    os.makedirs(runs, exist_ok=True)
    os.makedirs(out, exist_ok=True)
    references = references or [os.path.join(runs, "p2_1600_none")]
    for r in references:
        name = os.path.basename(r.rstrip("/"))
        match = re.fullmatch(r"p(\d)_(\d+)_(none|blend)", name)
        if match and os.path.samefile(os.path.dirname(os.path.abspath(r)), runs):
            run(build, runs, name, int(match[1]), int(match[2]), match[3] == "blend", ranks)
    names = [os.path.basename(r.rstrip("/")) for r in references]
    refs = [slices(r)[T] for r in references]
    rows = []
    for degree in (2, 3):
        for blending in (False, True):
            for cells in (200, 400, 800):
                name = "p%d_%d_%s" % (degree, cells, "blend" if blending else "none")
                s = run(build, runs, name, degree, cells, blending, ranks)
                x, stress = slices(os.path.join(runs, name))[T]
                l1 = [differences((x, stress), ref)[0] for ref in refs]
                cpu = s["time_loop_cpu_s"] * s["n_mpi_ranks"]
                rows.append([degree, "blending" if blending else "none", cells,
                             total_variation(x, stress), cpu, s["diagnostics"]["energy"], *l1])
                print("P%d %-8s %4d x %3d  TV %.3f  CPU %.1f s  energy %.4f  L1 wake vs %s"
                      % (degree, rows[-1][1], cells, cells // 10, *rows[-1][3:6],
                         ", ".join("%s %.4f" % nl for nl in zip(names, l1))), flush=True)
    with open(os.path.join(out, "wake-work-precision.csv"), "w") as f:
        w = csv.writer(f)
        w.writerow(["degree", "method", "cells_x_per_100", "tv_wake", "cpu_s", "energy"]
                   + ["l1_wake_vs_" + n for n in names])
        w.writerows(rows)
    plot(rows, names, os.path.join(out, "wake-work-precision.png"))


def plot(rows, names, path):
    """error against CPU time, a panel per reference"""
    fig, axes = plt.subplots(1, len(names), figsize=(5.2 * len(names), 4.2), squeeze=False)
    for k, (ax, name) in enumerate(zip(axes[0], names)):
        for degree, colour in ((2, "tab:blue"), (3, "tab:red")):
            for method, style in (("none", "o-"), ("blending", "s--")):
                r = [row for row in rows if row[0] == degree and row[1] == method]
                ax.loglog([row[4] for row in r], [row[6 + k] for row in r], style, color=colour,
                          label="P%d, %s" % (degree, "no limiter" if method == "none"
                                             else "subcell blending"))
                for row in r:
                    ax.annotate("%d" % row[2], (row[4], row[6 + k]), fontsize=7, xytext=(3, 3),
                                textcoords="offset points")
        ax.set_xlabel("CPU time of the time loop, all ranks [s]")
        ax.set_ylabel("L1 of the stress on y = 5, x < 15, t = 20")
        ax.set_title("the wake vs %s (labels: cells in x per 100)" % name, fontsize=9)
        ax.grid(alpha=0.3, which="both")
        ax.legend(fontsize=8)
    fig.tight_layout()
    fig.savefig(path, dpi=120)


if __name__ == "__main__":
    main()
