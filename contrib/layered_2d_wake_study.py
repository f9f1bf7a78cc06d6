#!/usr/bin/python3
"""Work precision of the 2D layered strip's wake (prm/layered_2d.prm, case (c)):
P2 and P3, without and with subcell blending, on 200 x 20, 400 x 40 and
800 x 80 cells (per [0, 100] x [0, 10]), against a converged reference,
P2 1600 x 160 without a limiter. Error: the L1 of the stress on the slice
y = 5 over the wake x < 15 at t = 20 (contrib/layered_2d_wake.py); work: the
CPU time of the time loop, summed over the ranks.

    contrib/layered_2d_wake_study.py BUILD RUNS OUT [--reference DIR ...] [--ranks N]

RUNS: where the runs go (a run that completed is reused); OUT:
wake-work-precision.{csv,png}, a panel per reference. --reference (may
repeat): reference runs (default: RUNS/p2_1600_none). A reference named
RUNS/pD_N_none or RUNS/pD_N_blend is run if it is missing (P2 1600 x 160:
6.5 min of wall time on two cores; P3 1600 x 160: 13.5 min, blended 21 min).
Every run is on [0, 32] x [0, 10] with the cells of [0, 100] per unit
length: up to t = 20 the waves reach x ~ 25, so the strip's far end never
matters (the slices of [0, 32] and [0, 100] agree to 1e-15, measured).
"""
import os
import re

from granular_dg import outputs, parser, plot
from granular_dg.compare import slice_l1, total_variation
from granular_dg.run import finished, run_case

LENGTH, T, WAKE = 32, 20.0, 15.0
CFL = {2: 0.15, 3: 0.1}  # the prm's 0.15 for P2; 0.1 for P3 (its stable CFL)


def run(a, name, degree, cells, blending):
    """RUNS/name unless it completed before: its summary and (x, stress) at T."""
    sets = ["Discretization/degree=%d" % degree, "Time stepping/CFL number=%g" % CFL[degree],
            "Time stepping/final time=%g" % T, "Mesh/x max=%d" % LENGTH,
            "Mesh/cells x=%d" % (cells * LENGTH // 100), "Mesh/cells y=%d" % (cells // 10)]
    # blending computes every cell (the prm's skipping of cells at rest refuses it)
    sets += ["Limiter/scheme=none", "Limiter/subcell blending=true",
             "Time stepping/skip cells at rest=false"] if blending else []
    if not finished(os.path.join(a.runs, name)):
        print("running", name, flush=True)
    r = run_case(a.build, "prm/layered_2d.prm", os.path.join(a.runs, name), sets, ranks=a.ranks,
                 reuse=True, check=True, log=True)
    s = outputs.slices(r.directory)[T]
    return r.summary, (s["x"], s["stress"])


def main():
    p = parser(__doc__)
    p.add_argument("build")
    p.add_argument("runs")
    p.add_argument("out")
    p.add_argument("--reference", action="append", default=[])
    p.add_argument("--ranks", type=int, default=2)
    a = p.parse_args()
    os.makedirs(a.runs, exist_ok=True)
    os.makedirs(a.out, exist_ok=True)
    references = a.reference or [os.path.join(a.runs, "p2_1600_none")]
    names = [os.path.basename(r.rstrip("/")) for r in references]
    refs = []
    for path, name in zip(references, names):
        match = re.fullmatch(r"p(\d)_(\d+)_(none|blend)", name)
        if match and os.path.samefile(os.path.dirname(os.path.abspath(path)), a.runs):
            refs.append(run(a, name, int(match[1]), int(match[2]), match[3] == "blend")[1])
        else:
            s = outputs.slices(path)[T]
            refs.append((s["x"], s["stress"]))
    rows = []
    for degree, blending, cells in ((d, b, n) for d in (2, 3) for b in (False, True) for n in (200, 400, 800)):
        name = "p%d_%d_%s" % (degree, cells, "blend" if blending else "none")
        s, (x, stress) = run(a, name, degree, cells, blending)
        rows.append(dict(degree=degree, method="blending" if blending else "none", cells_x_per_100=cells,
                         tv_wake=total_variation(x, stress, WAKE), cpu_s=s["time_loop_cpu_s"] * s["n_mpi_ranks"],
                         energy=s["diagnostics"]["energy"],
                         **{"l1_wake_vs_" + n: slice_l1((x, stress), ref, WAKE)[0] for n, ref in zip(names, refs)}))
        print("P%d %-8s %4d x %3d  TV %.3f  CPU %.1f s  energy %.4f  L1 wake vs %s" % (
            degree, rows[-1]["method"], cells, cells // 10, rows[-1]["tv_wake"], rows[-1]["cpu_s"],
            rows[-1]["energy"], ", ".join("%s %.4f" % (n, rows[-1]["l1_wake_vs_" + n]) for n in names)), flush=True)
    outputs.write_csv(os.path.join(a.out, "wake-work-precision.csv"), rows)
    chart(rows, names, os.path.join(a.out, "wake-work-precision.png"))


def chart(rows, names, path):
    """Error against CPU time, a panel per reference."""
    fig, axes = plot.subplots(1, len(names), figsize=(5.2 * len(names), 4.2), squeeze=False)
    for ax, name in zip(axes[0], names):
        for degree, colour in ((2, "tab:blue"), (3, "tab:red")):
            for method, style in (("none", "o-"), ("blending", "s--")):
                r = [row for row in rows if row["degree"] == degree and row["method"] == method]
                x, y = [row["cpu_s"] for row in r], [row["l1_wake_vs_" + name] for row in r]
                ax.loglog(x, y, style, color=colour, label="P%d, %s" % (
                    degree, "no limiter" if method == "none" else "subcell blending"))
                for row, xi, yi in zip(r, x, y):
                    ax.annotate("%d" % row["cells_x_per_100"], (xi, yi), fontsize=7, xytext=(3, 3),
                                textcoords="offset points")
        plot.label(ax, "CPU time of the time loop, all ranks [s]", "L1 of the stress on y = 5, x < 15, t = 20",
                   "the wake vs %s (labels: cells in x per 100)" % name, legend=8, size=9)
    plot.save(fig, path, dpi=120)


if __name__ == "__main__":
    main()
