#!/usr/bin/python3
"""Speed against accuracy across the scenes (doc/study/README.md lists the
files): work-precision charts (SCENES), stability maps CFL x degree x (flux,
limiter) with the limits found by bisection (STABILITY), the cheapest
configuration reaching two target errors per scene, and where the methods
fail (study_failures.py).

    /usr/bin/python3 contrib/study.py BUILD_DIR OUT_DIR [--quick] [--jobs N]
        [--only scene,...] [--skip-work-precision] [--skip-stability] [--skip-failures]

Runs go to OUT_DIR/runs/, --jobs at a time (default 2), and are reused when
they are there (delete them to rerun); the charted CPU times are those of
each process. stability() says how a map finds the limits, classify() names
the states.
"""
import math
import os
import textwrap
import time
from pathlib import Path

from granular_dg import arguments, outputs, plot
from granular_dg.compare import stress_l1
from granular_dg.run import HOPPER_SAMPLED, NO_SNAPSHOTS, Runs, load, tag

import study_failures
from study_failures import LINEAR_RK3, strain_l1


def sum_l1(s, d):
    """Sum over the components of the L1 error against the exact solution."""
    vals = [v[0] for k, v in s.get("errors", {}).items() if k.endswith("_l1_l2_linf")]
    return sum(vals) if vals else math.nan


def network_l1(s, d):
    return s.get("diagnostics", {}).get("l1_error", math.nan)


def hopper_radial(s, d):
    """Relative L1 error of (T_rr, T_rtheta)/r against the exact radial field
    at 2001 equidistant theta (doc/hopper.md 4.7, contrib/hopper.py precision)."""
    return stress_l1(outputs.read_table(os.path.join(d, "stress-0001.csv")))


def cpu_loop(s):
    """The CPU time of the time loop (the network's own loop's)."""
    return s.get("diagnostics", {}).get("cpu_time_loop_s", s.get("time_loop_cpu_s", math.nan))


SCENES = {
    # m = 1, t = 4 against the closed form (the frozen region included)
    "column": dict(
        prm="tests/column/m1_base.prm", mesh="Mesh/cells", cells=[25, 50, 100, 200, 400, 800, 1600, 3200],
        quick_cells=[50, 200], degrees=[0, 1, 2, 3], quick_degrees=[1, 2], cfl=lambda p: 0.9 / (2 * p + 1),
        max_cells={3: 800},  # P3 is the most expensive per accuracy here
        error=sum_l1, error_name="L1 error (strain + velocity) at t = 4", targets=[1e-2, 1e-3]),
    # the smooth periodic linear wave of the layered_strip scene (1D)
    "layered_1d": dict(
        prm="prm/elasticity_linear_wave.prm", mesh="Mesh/cells x", cells=[8, 16, 32, 64, 128, 256],
        quick_cells=[8, 32], degrees=[0, 1, 2, 3, 4], quick_degrees=[1, 2],
        # 0.9/(2p+1), but P4 blows up there (its limit is ~0.09): 0.07
        cfl=lambda p: 0.07 if p == 4 else 0.9 / (2 * p + 1),
        error=sum_l1, error_name="L1 error (strain + velocity) at t = 1", targets=[1e-4, 1e-7]),
    # the 2D strip scene on the same wave, 2 cells across in y (periodic)
    "layered_2d": dict(
        prm="prm/elasticity_linear_wave.prm", mesh="Mesh/cells x", cells=[8, 16, 32, 64], quick_cells=[8, 16],
        degrees=[1, 2, 3], quick_degrees=[2], cfl=lambda p: 0.9 / (2 * p + 1),
        error=sum_l1, error_name="L1 error (strain + velocity) at t = 1", targets=[1e-4, 1e-6],
        extra=["Mesh/dimension=2", "Mesh/cells y=2", "Mesh/y min=0", "Mesh/y max=0.25",
               "Boundary conditions/bottom=periodic", "Boundary conditions/top=periodic",
               "Initial condition/velocity=-0.1*sin(2*pi*x); 0",
               "Exact solution/velocity=-0.1*sin(2*pi*(x-t)); 0"]),
    # the smooth network case (exact solution by characteristics), the vertex
    # without volume (the paper's vertex cell caps every degree at order 1,
    # doc/network.md)
    "network": dict(
        prm="prm/network_smooth.prm", mesh="Network/cells per unit length", cells=[8, 16, 32, 64, 128, 256, 512],
        quick_cells=[8, 32], degrees=[0, 1, 2, 3], quick_degrees=[1, 2],
        cfl=lambda p: {0: 0.5, 1: 0.3, 2: 0.18, 3: 0.03}[p],
        max_cells={3: 256},  # P3 at 512 cells: 1e-11, the round-off floor, 22 s CPU
        error=network_l1, error_name="L1 error (edges + vertex) at t = 0.5",
        targets=[1e-3, 1e-5], extra=["Network/vertex width factor=0"]),
    # the 30 deg cone marched to tau = 1 against the exact radial field,
    # without the limiter (with it P2 and P3 are capped at 3rd order, doc/hopper.md)
    "hopper": dict(
        prm="prm/hopper_radial_cone.prm", mesh="Hopper/cells", cells=[25, 50, 100, 200, 400], quick_cells=[25, 100],
        degrees=[1, 2, 3], quick_degrees=[1, 2], cfl=lambda p: {1: 1 / 3., 2: 1 / 5., 3: 0.12}[p],
        max_cells={2: 200, 3: 200},
        error=hopper_radial, error_name="relative difference to the radial field at tau = 1", targets=[1e-3, 1e-5],
        extra=["Time stepping/final time=1", "Limiter/scheme=none"] + HOPPER_SAMPLED),
}


def flux_limiter(flux, limiter):
    return ["Discretization/numerical flux=" + flux, "Limiter/scheme=" + limiter]


# the limiter only in the cells the modal-energy indicator flags
FLAGGED = ["Limiter/indicator=modal_energy"]
# subcell blending, alone (no limiter)
BLENDING = ["Limiter/subcell blending=true"]


# Stability maps. choices: (label, --set overrides); quick_choices: indices used with --quick
# (default none); p0_choices: the choices run at degree 0 (default all; degree 0 has no slopes
# to limit, so choices that differ only in the limiter are one scheme there); factors: see
# stability(); extra: the --set overrides of every run (default none); blowup: see classify() (default 1).
STABILITY = {
    # the smooth linear wave in one material: LLF = impedance = upwind flux here
    "layered_1d": dict(
        scene="layered_1d", prm="prm/elasticity_linear_wave.prm", mesh="Mesh/cells x", cells=32,
        case="smooth linear wave, one material, 32 cells, t = 1 (exact solution)",
        error=sum_l1, energy=True, degrees=[0, 1, 2, 3, 4], quick_degrees=[1, 2],
        factors=[0.25, 0.5, 0.8, 1.0, 1.2, 1.5, 2.0, 3.0],
        choices=[("LLF, no limiter", flux_limiter("local_lax_friedrichs", "none"))], quick_choices=[0]),
    # case (b) of doc/layered_strip.md shortened (layers of width 1, rho = K = 3 | 1,
    # 4 cells per layer, t = 50) against a P3 impedance run at 32 cells per layer
    "layered_interfaces": dict(
        scene="layered_1d", prm="prm/layered_1d.prm", mesh="Mesh/cells x",
        cells=4 * study_failures.LAYERS,
        case="layered strip (rho = K = 3 | 1, layers of width 1), 4 cells per layer, t = %g "
             "(reference: P3 impedance, 32 cells per layer; 8 with --quick)" % study_failures.LAYERED_T,
        extra=study_failures.LAYERED_SHORT, setup=study_failures.layered_reference_sets,
        error=strain_l1, blowup=100.0, degrees=[1, 2, 3], quick_degrees=[2],
        choices=[("LLF on (eps, m), no limiter", flux_limiter("local_lax_friedrichs", "none")),
                 ("LLF + componentwise", flux_limiter("local_lax_friedrichs", "componentwise")),
                 ("LLF + characteristic", flux_limiter("local_lax_friedrichs", "characteristic")),
                 ("impedance, no limiter", flux_limiter("impedance", "none")),
                 ("impedance + flux_variables", flux_limiter("impedance", "flux_variables")),
                 ("impedance + flux_variables, flagged cells", flux_limiter("impedance", "flux_variables") + FLAGGED),
                 ("impedance, subcell blending", flux_limiter("impedance", "none") + BLENDING)], quick_choices=[1, 3]),
    # the column m = 1 (friction projection) against the closed form
    "column": dict(
        scene="column", prm="tests/column/m1_base.prm", mesh="Mesh/cells", cells=200,
        case="column m = 1, 200 cells, t = 4 (closed form), friction projection",
        error=sum_l1, p0_choices=[0], degrees=[0, 1, 2, 3], quick_degrees=[1],
        choices=[("characteristic", ["Limiter/scheme=characteristic"]),
                 ("componentwise", ["Limiter/scheme=componentwise"]),
                 ("no limiter", ["Limiter/scheme=none"]),
                 ("characteristic, flagged cells", ["Limiter/scheme=characteristic"] + FLAGGED),
                 ("subcell blending", ["Limiter/scheme=none"] + BLENDING)], quick_choices=[0, 1]),
    # Burgers on the star graph with a shock through the vertex (exact solution)
    "network": dict(
        scene="network", prm="prm/network_example_7_5.prm", mesh="Network/cells per unit length",
        cells=64, case="example 7.5 (Burgers, shock through the vertex), 64 cells per edge, "
                       "t = 0.5 (exact solution)",
        error=network_l1, degrees=[0, 1, 2, 3], quick_degrees=[1],
        choices=[("upwind (Godunov) + componentwise", flux_limiter("upwind", "componentwise")),
                 ("LLF + componentwise", flux_limiter("local_lax_friedrichs", "componentwise")),
                 ("upwind (Godunov), no limiter", flux_limiter("upwind", "none")),
                 ("upwind (Godunov) + componentwise, flagged cells",
                  flux_limiter("upwind", "componentwise") + FLAGGED)],
        p0_choices=[0, 1], quick_choices=[0, 1]),
    # the 30 deg cone's radial field marched to tau = 1 (exact)
    "hopper": dict(
        scene="hopper", prm="prm/hopper_radial_cone.prm", mesh="Hopper/cells", cells=50,
        case="30 deg cone, radial field marched to tau = 1 on 50 cells (exact)",
        extra=["Time stepping/final time=1"] + HOPPER_SAMPLED, error=hopper_radial,
        degrees=[1, 2, 3], quick_degrees=[1],
        choices=[("Roe-LF + characteristic (GM)", flux_limiter("roe_lax_friedrichs", "characteristic")),
                 ("Roe-LF, no limiter", flux_limiter("roe_lax_friedrichs", "none")),
                 ("LLF + characteristic", flux_limiter("local_lax_friedrichs", "characteristic")),
                 ("Roe-LF + characteristic, flagged cells",
                  flux_limiter("roe_lax_friedrichs", "characteristic") + FLAGGED)]),
}
DEFAULT_FACTORS = [0.5, 1.0, 1.5, 2.0, 3.0]
QUICK_FACTORS = [0.5, 1.5]
EXTEND_FACTORS = [5.0, 8.0, 12.0]


def work_precision(ctx, name, sc):
    degrees = ctx.pick(sc, "degrees")

    def one(p, n):
        cfl = sc["cfl"](p)
        run = ctx.run(os.path.join(name, "wp-p%d-n%d" % (p, n)), sc["prm"], sc.get("extra", []) + [
            "Discretization/degree=%d" % p, "%s=%d" % (sc["mesh"], n), "Time stepping/CFL number=%.12g" % cfl])
        s = run.summary
        e = sc["error"](s, run.directory) if run.code == 0 else math.nan
        r = dict(scene=name, degree=p, cells=n, cfl=cfl, exit=run.code, error=e, n_dofs=s.get("n_dofs", ""),
                 steps=s.get("n_time_steps", ""), time_loop_cpu_s=cpu_loop(s), run_wall_s=run.wall_s, load=s["_load"])
        print("%s P%d n=%d: exit %d error %.3e cpu %.3g s" % (name, p, n, run.code, e, cpu_loop(s)), flush=True)
        return r

    rows = ctx.pmap(one, [(p, n) for p in degrees for n in ctx.pick(sc, "cells")
                          if n <= sc.get("max_cells", {}).get(p, n)])
    # blown up: exit 3, an error > 1, or an error above the coarser mesh's
    # (an instability growing: e.g. P4 above its CFL limit)
    for p in degrees:
        previous = math.inf
        for r in outputs.select(rows, degree=p):
            r["blown_up"] = int(r["exit"] != 0 or not (r["error"] <= min(1., previous)))
            previous = r["error"] if math.isfinite(r["error"]) else previous
    ctx.csv(name + "-work-precision", rows)
    fig, axes = plot.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    for ax, key, label in ((axes[0], "time_loop_cpu_s", "CPU time of the time loop [s]"),
                           (axes[1], "run_wall_s", "wall time of the run [s]")):
        for p in degrees:
            sel = [r for r in outputs.select(rows, degree=p) if not r["blown_up"] and r["error"] > 0]
            if sel:
                ax.loglog([max(r[key], 1e-4) for r in sel], [r["error"] for r in sel], "o-", ms=4, label="P%d" % p)
        for t in sc["targets"]:
            ax.axhline(t, color="gray", lw=0.6, ls=":")
        plot.label(ax, label)
    plot.label(axes[0], y=sc["error_name"], legend=8, grid=0)
    fig.suptitle("%s: error against the exact solution vs cost (%s, SSP-RK3)" % (name, sc["prm"]), fontsize=10)
    ctx.save(fig, name + "-work-precision")
    return rows


def classify(code, err, e, e0, grew=None, blowup=1.0):
    """The state of a stability run (fixed mesh, to the final time): blown up
    (exit 3 with a non-finite state, or an error above the map's blow-up
    level: 1 for the O(0.1-1) data of the exact-solution cases, 100 for the
    layered case, whose reference strain has L1 norm 11.7, the wall
    displacement at t = 50); inadmissible (exit 3 naming another
    admissibility test: negative sigma', the hopper's loss of hyperbolicity);
    oscillatory (completed, but the discrete energy grew in an energy-stable
    case, energy=True: the linear wave with the LLF flux, no limiter; else
    the error is > 2 e0, e0 the error of the same degree and choice at the
    grid's smallest CFL: a limiter keeps such a run bounded, the instability
    shows as lost accuracy); refused (exit 2: the program refuses the input);
    stable otherwise."""
    if code == 3:  # the run failed: inadmissible or non-finite state
        return "blown up" if any(w in err.lower() for w in ("finite", "nan", "inf")) else "inadmissible"
    if code != 0:
        return "refused" if code == 2 else "failed"
    if not math.isfinite(e) or e > blowup:
        return "blown up"
    if grew is not None:  # energy-stable scheme: growth is the instability
        return "oscillatory" if grew else "stable"
    return "oscillatory" if e0 is not None and e > 2 * e0 else "stable"


def stability(ctx, name, sp):
    """One map: for every (choice, degree) the grid CFL = f/(2p+1), at most 1
    (the program's range), f in DEFAULT_FACTORS or the map's factors (in the
    full study on with EXTEND_FACTORS while every run is stable: limited
    schemes stay bounded far beyond the linear limit), then the bisection of
    the limit, the largest stable CFL, between the largest stable and the
    smallest non-stable value to a relative width of 5 % (15 % with --quick);
    the pairs run --jobs at a time."""
    degrees = ctx.pick(sp, "degrees")
    choices = [sp["choices"][i] for i in sp.get("quick_choices", [])] if ctx.quick else sp["choices"]
    if not choices:
        return []
    factors = QUICK_FACTORS if ctx.quick else sp.get("factors", DEFAULT_FACTORS)
    width = 0.15 if ctx.quick else 0.05
    extra = sp.get("extra", []) + (sp["setup"](ctx) if "setup" in sp else [])
    p0 = [sp["choices"][i] for i in sp.get("p0_choices", range(len(sp["choices"])))]

    def pair(label, sets, p):
        index, rows = sp["choices"].index((label, sets)), []

        def one(cfl, e0):
            run = ctx.run(os.path.join(name, "st-c%d-p%d-cfl%s" % (index, p, tag(cfl))), sp["prm"], extra + sets + [
                "Discretization/degree=%d" % p, "%s=%d" % (sp["mesh"], sp["cells"]),
                "Time stepping/CFL number=%.12g" % cfl, "Time stepping/check stability limit=false"])
            e = sp["error"](run.summary, run.directory) if run.code == 0 else math.nan
            grew = energy_grew(run.directory) if run.code == 0 and sp.get("energy") else None
            c = classify(run.code, run.stderr, e, e0, grew, sp.get("blowup", 1.0))
            rows.append(dict(map=name, scene=sp["scene"], choice=label, degree=p, cfl=cfl, exit=run.code,
                             error=e, state=c, time_loop_cpu_s=cpu_loop(run.summary), message=run.stderr[:200]))
            print("%s [%s] P%d CFL %.4g: %s (error %.3e)" % (name, label, p, cfl, c, e), flush=True)
            return c, e

        # the grid; e0: the error at its first CFL with a finite error
        states, e0 = [], None
        for cfl in sorted({min(1.0, f / (2 * p + 1)) for f in factors}):
            c, e = one(cfl, e0)
            e0 = e if e0 is None and math.isfinite(e) else e0
            states.append((cfl, c))
        for f in ([] if ctx.quick else EXTEND_FACTORS):
            cfl = min(1.0, f / (2 * p + 1))
            if any(c != "stable" for _, c in states) or cfl <= states[-1][0]:
                break
            states.append((cfl, one(cfl, e0)[0]))
        lo = max((cfl for cfl, c in states if c == "stable"), default=None)
        hi = min((cfl for cfl, c in states if c != "stable" and lo is not None and cfl > lo), default=None)
        while hi is not None and (hi - lo) / lo > width:  # a hi is above a lo
            mid = 0.5 * (lo + hi)
            lo, hi = (mid, hi) if one(mid, e0)[0] == "stable" else (lo, mid)
        above = next((c for cfl, c in sorted((r["cfl"], r["state"]) for r in rows) if hi is not None and cfl >= hi),
                     "none up to CFL %.3g" % max(states)[0])
        none = lo is None
        return rows, dict(map=name, scene=sp["scene"], choice=label, degree=p, cfl_limit="" if none else lo,
                          first_unstable_cfl="" if hi is None else hi,
                          limit_times_2p_plus_1="" if none else lo * (2 * p + 1), linear_rk3_limit=LINEAR_RK3[p],
                          limit_over_linear="" if none else lo / LINEAR_RK3[p], state_above=above)

    results = ctx.pmap(pair, [(*c, p) for c in choices for p in degrees if p > 0 or c in p0])
    rows, limits = [r for rr, _ in results for r in rr], [l for _, l in results]
    ctx.csv(name + "-stability", rows)
    stability_chart(ctx, name, sp, choices, degrees, rows, limits)
    return limits


def energy_grew(d):
    """Whether the discrete energy (timeseries.csv) grew from t = 0 to the end."""
    e = outputs.timeseries(d)["energy"]
    return not (e[-1] <= e[0] * (1 + 1e-10))


# state: (colour, marker)
STATES = {"stable": ("tab:green", "o"), "oscillatory": ("tab:orange", "s"), "inadmissible": ("tab:purple", "D"),
          "blown up": ("tab:red", "x"), "refused": ("gray", "_"), "failed": ("black", "+")}


def stability_chart(ctx, name, sp, choices, degrees, rows, limits):
    from matplotlib.ticker import FormatStrFormatter, LogLocator
    n = len(choices)
    panel, top, bottom = 0.28 * len(degrees) + 0.5, 0.55, 0.8  # inches
    height = top + bottom + n * panel
    fig, axes = plot.subplots(n, 1, figsize=(8, height), sharex=True, squeeze=False)
    fig.subplots_adjust(left=0.07, right=0.98, top=1 - top / height, bottom=bottom / height,
                        hspace=0.32 / (panel - 0.32))
    handles = {}
    for ax, (label, _) in zip(axes[:, 0], choices):
        for state, (colour, marker) in STATES.items():
            sel = outputs.select(rows, state=state, choice=label)
            if sel:
                handles[state] = ax.scatter([r["cfl"] for r in sel], [r["degree"] for r in sel],
                                            c=colour, marker=marker, s=24)
        for l in outputs.select(limits, choice=label):
            if l["cfl_limit"] != "":
                bounded = l["first_unstable_cfl"] != ""
                key = "bisected limit" if bounded else "stable to the end of the grid"
                handles[key], = ax.plot([l["cfl_limit"]] * 2, [l["degree"] - 0.38, l["degree"] + 0.38],
                                        "k-" if bounded else "k:", lw=1.6)
                ax.annotate(("%.3g" if bounded else ">= %.3g") % l["cfl_limit"], (l["cfl_limit"], l["degree"]),
                            xytext=(3, 2), textcoords="offset points", fontsize=6.5)
        ran = sorted({r["degree"] for r in outputs.select(rows, choice=label)})
        handles["linear RK3-DG limit"], = ax.plot([LINEAR_RK3[p] for p in ran], ran, "b|", ms=11, mew=1.0)
        ax.set_yticks(degrees, ["P%d" % p for p in degrees], fontsize=7)
        ax.set_ylim(min(degrees) - 0.6, max(degrees) + 0.6)
        ax.set_title(label, fontsize=8, loc="left", pad=2)
        ax.grid(alpha=0.3, which="both")
    ax = axes[-1, 0]
    ax.set_xscale("log")
    ax.xaxis.set(major_locator=LogLocator(subs=(1, 2, 3, 5)), major_formatter=FormatStrFormatter("%g"),
                 minor_formatter=FormatStrFormatter(""))
    ax.tick_params(axis="x", labelsize=7)
    ax.set_xlabel("CFL number", fontsize=8)
    fig.legend(list(handles.values()), list(handles.keys()), fontsize=7, loc="lower center",
               ncol=len(handles), frameon=False)
    fig.suptitle("\n".join(textwrap.wrap("%s: SSP-RK3 stability, %s" % (name, sp["case"]), 120)),
                 fontsize=8.5, y=1 - 0.06 / height, va="top")
    ctx.save(fig, name + "-stability", tight=False)


def limits_table(ctx, limits):
    ctx.csv("stability-limits", limits)
    number = lambda fmt, x: fmt % x if x != "" else ""
    Path(ctx.out, "stability-limits.md").write_text(outputs.markdown(
        ["map", "choice", "degree", "limit (bisected)", "x (2p+1)", "/ linear RK3-DG limit", "above the limit"],
        [[l["map"], l["choice"], "P%d" % l["degree"], number("%.4g", l["cfl_limit"]) or "none stable",
          number("%.3g", l["limit_times_2p_plus_1"]), number("%.3g", l["limit_over_linear"]), l["state_above"]]
         for l in limits]))


def cheapest(ctx, all_rows):
    res = []
    for name, sc in SCENES.items():
        # completed runs that did not blow up (error <= 1)
        rows = [r for r in outputs.select(all_rows, scene=name) if not r["blown_up"]]
        for t in sc["targets"] if rows else []:
            ok = [r for r in rows if r["error"] <= t]
            if ok:
                b = min(ok, key=lambda r: r["time_loop_cpu_s"])
                res.append(dict(scene=name, target_error=t, degree=b["degree"], cells=b["cells"], cfl="%.4g" % b["cfl"],
                                error="%.3e" % b["error"], time_loop_cpu_s="%.4g" % b["time_loop_cpu_s"],
                                run_wall_s="%.3g" % b["run_wall_s"], load=b["load"]))
            else:
                best = min(rows, key=lambda r: r["error"])
                res.append(dict(scene=name, target_error=t, degree="not reached", cells="", cfl="",
                                error="best %.3e (P%d, %d cells)" % (best["error"], best["degree"], best["cells"]),
                                time_loop_cpu_s="", run_wall_s="", load=""))
    ctx.csv("cheapest", res)
    Path(ctx.out, "cheapest.md").write_text(outputs.markdown(
        ["scene", "target error", "degree", "cells", "CFL", "error", "CPU time loop [s]", "wall run [s]", "load"],
        [[r["scene"], "%g" % r["target_error"]] + [r[k] for k in list(r)[2:]] for r in res]))


if __name__ == "__main__":
    a = arguments(__doc__, [
        "build", "out", ("--quick", dict(action="store_true", help="a few meshes, degrees and choices (a smoke run)")),
        ("--jobs", dict(type=int, default=2, help="granular_dg processes at a time")),
        ("--only", dict(default=",".join(SCENES), help="scenes (work precision, stability maps, failure modes)"))]
        + [("--skip-" + part, dict(action="store_true")) for part in ("work-precision", "stability", "failures")])
    ctx = Runs(a.build, a.out, a.quick, a.jobs, subdir="runs", sets=NO_SNAPSHOTS, formats=("svg",))
    only, parts, all_rows, limits = a.only.split(","), [], [], []
    l0, t0, c0 = load(), time.time(), os.times()

    def timed(label, f):
        s = time.time()
        r = f()
        parts.append("%s %.0f s" % (label, time.time() - s))
        return r

    if not a.skip_work_precision:
        for name in only:
            all_rows += timed("work precision " + name, lambda: work_precision(ctx, name, SCENES[name]))
        cheapest(ctx, all_rows)
    if not a.skip_stability:
        for name, sp in STABILITY.items():
            if sp["scene"] in only:
                limits += timed("stability " + name, lambda: stability(ctx, name, sp))
        if limits:
            limits_table(ctx, limits)
    if not a.skip_failures:
        timed("failures", lambda: study_failures.run_all(ctx, only))
    c1 = os.times()
    runtime = ("study %s (%s), %d jobs: wall %.1f s, CPU of the runs %.1f s, load at the start %s, at the end %s; "
               "granular_dg runs executed %d, reused %d\nparts (wall): %s\n" % (
                   "quick" if a.quick else "full", ",".join(only), a.jobs, time.time() - t0,
                   (c1.children_user - c0.children_user) + (c1.children_system - c0.children_system),
                   l0, load(), ctx.count["executed"], ctx.count["reused"], "; ".join(parts)))
    Path(a.out, "runtime.txt").write_text(runtime)
    print(runtime)
