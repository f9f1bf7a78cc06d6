"""Where the methods fail, reproduced and charted for contrib/study.py, which
runs it (doc/study/README.md, "Where the methods fail"). Each mode writes
OUT/failure-NAME.{png,svg,csv} and its numbers into OUT/failures.md:
interfaces (the naive LLF flux at material interfaces against the impedance
flux), friction (explicit friction in the column against the projection),
rk3 (SSP-RK3 beyond its CFL limit, from OUT/layered_1d-stability.csv), shock
(the unlimited scheme at shocks) and hopper (loss of hyperbolicity of
steep-to-shallow transitions)."""
import math
import os
from pathlib import Path

import numpy as np

from granular_dg import outputs, plot
from granular_dg.outputs import select
from granular_dg.run import tag

# SSP-RK3 with upwind DG of degree p on u_t + u_x = 0: the linear stability
# limit of nu = a dt/h (Fourier analysis: tests/unit/rk_stability_limits.cc computes them)
LINEAR_RK3 = {0: 1.256373, 1: 0.409590, 2: 0.209754, 3: 0.130094, 4: 0.089687}
LAYERS = 60            # layers of width 1 on [0, 60]
LAYERED_T = 50         # the front is at x ~ 45 then: the outflow end is not reached
# the limiters of these studies act in every cell (prm/layered_1d.prm and
# prm/elasticity_shock.prm ship the modal-energy indicator)
EVERYWHERE = ["Limiter/indicator=everywhere"]
LAYERED_SHORT = ["Mesh/x max=%d" % LAYERS, "Time stepping/final time=%g" % LAYERED_T] + EVERYWHERE


def fmt(x, digits=3):
    return ("%." + str(digits) + "g") % x if isinstance(x, (int, float)) and math.isfinite(x) else "-"


def strain_l1(s, d=None):
    """L1 error of the strain (component 0) against the reference."""
    return s.get("errors", {}).get("component_0_l1_l2_linf", [math.nan])[0]


def diagnostics(s, *keys):
    """The named entries of summary.json's diagnostics (NaN where missing)."""
    dg = s.get("diagnostics", {})
    return {k: dg.get(k, math.nan) for k in keys}


def layered_reference_sets(ctx):
    """The reference of the shortened layered case: P3, impedance flux, no
    limiter, 32 cells per layer (8 with --quick), CFL 0.1; returns the
    --set that makes a run compute its errors against it."""
    per_layer = 8 if ctx.quick else 32
    run = ctx.run("layered_reference/p3-n%d" % per_layer, "prm/layered_1d.prm", LAYERED_SHORT + [
        "Mesh/cells x=%d" % (LAYERS * per_layer), "Discretization/degree=3", "Discretization/numerical flux=impedance",
        "Limiter/scheme=none", "Time stepping/CFL number=0.1", "Output/write modes=true"])
    if run.code != 0:
        raise RuntimeError("the layered reference run failed: " + run.stderr)
    return ["Exact solution/reference file=" + outputs.latest(run.directory, "modes")]


# ---------------------------------------------------------------- interfaces
INTERFACE_CONFIGS = [("LLF on (eps, m) + componentwise", "local_lax_friedrichs", "componentwise", "tab:red"),
                     ("LLF on (eps, m), no limiter", "local_lax_friedrichs", "none", "tab:orange"),
                     ("impedance + flux_variables", "impedance", "flux_variables", "tab:blue"),
                     ("impedance, no limiter", "impedance", "none", "tab:green")]


def interfaces(ctx):
    ref = layered_reference_sets(ctx)
    degrees, per_layer = ([2], [2, 4]) if ctx.quick else ([1, 2], [2, 4, 8, 16])

    def one(label, flux, limiter, _, p, n):
        run = ctx.run("interfaces/%s-%s-p%d-n%d" % (flux, limiter, p, n), "prm/layered_1d.prm", LAYERED_SHORT + ref + [
            "Mesh/cells x=%d" % (LAYERS * n), "Discretization/degree=%d" % p, "Discretization/numerical flux=" + flux,
            "Limiter/scheme=" + limiter, "Time stepping/CFL number=%.12g" % (0.8 / (2 * p + 1))])
        s = run.summary
        return dict(config=label, flux=flux, limiter=limiter, degree=p, cells_per_layer=n, exit=run.code,
                    l1_strain_error=strain_l1(s) if run.code == 0 else math.nan,
                    **diagnostics(s, "interface_stress_jump_max", "interface_stress_jump_mean", "min_strain",
                                  "max_strain"),
                    time_loop_cpu_s=s.get("time_loop_cpu_s", math.nan), final_time=s.get("final_time", ""),
                    message=run.stderr[:160])

    rows = ctx.pmap(one, [(*c, p, n) for c in INTERFACE_CONFIGS for p in degrees for n in per_layer])
    ctx.csv("failure-interfaces", rows)
    fig, ax = plot.subplots(1, 2, figsize=(11, 4.2))
    notes = ["**interfaces** (layered strip [0, %d] to t = %g, L1 strain error against P3 "
             "impedance at %d cells per layer; CFL 0.8/(2p+1)):" % (LAYERS, LAYERED_T, 8 if ctx.quick else 32)]
    for label, _, _, color in INTERFACE_CONFIGS:
        for p in degrees:
            sel = select(rows, config=label, degree=p)
            ok = [r for r in sel if r["exit"] == 0]
            style = dict(marker={1: "o", 2: "s", 3: "^"}[p], color=color, ms=5, ls="--" if "LLF" in label else "-")
            if ok:
                x = [r["cells_per_layer"] for r in ok]
                ax[0].loglog(x, [r["l1_strain_error"] for r in ok], label="%s, P%d" % (label, p), **style)
                ax[1].loglog(x, [r["interface_stress_jump_max"] for r in ok], **style)
            for r in (r for r in sel if r["exit"] != 0):  # stopped: mark at the top of the left panel
                ax[0].annotate("exit %d" % r["exit"], (r["cells_per_layer"], 1), fontsize=6, color=color, rotation=90)
            cells = ", ".join("%d: %s (jump %s)" % (r["cells_per_layer"], fmt(r["l1_strain_error"]),
                                                    fmt(r["interface_stress_jump_max"]))
                              if r["exit"] == 0 else "%d: exit %d at t = %s" % (
                                  r["cells_per_layer"], r["exit"], fmt(r["final_time"], 4)) for r in sel)
            ok = [r for r in ok if r["l1_strain_error"] > 0]
            e, n = [r["l1_strain_error"] for r in ok[-2:]], [r["cells_per_layer"] for r in ok[-2:]]
            eoc = "; EOC finest pair %.2f" % math.log(e[0] / e[1], n[1] / n[0]) if len(ok) >= 2 else ""
            notes.append("  - %s, P%d, cells per layer %s%s" % (label, p, cells, eoc))
    for a, y in zip(ax, ("L1 error of the strain", "largest stress jump across an interface")):
        plot.label(a, "cells per layer", y + " at t = %g" % LAYERED_T)
        plot.log_ticks(a, per_layer)
    ax[0].legend(fontsize=6, ncol=2)
    fig.suptitle("Naive LLF on (eps, m) against the interface-aware impedance flux at material "
                 "interfaces (layered strip, [0, %d], t = %g)" % (LAYERS, LAYERED_T), fontsize=9)
    ctx.save(fig, "failure-interfaces")
    return notes


# ------------------------------------------------------------------ friction
FRICTION = [("projection", ["Physics/friction=projection"]),
            ("explicit sgn(v)", ["Physics/friction=explicit_sign"]),
            ("explicit smooth, delta = 1e-2", ["Physics/friction=explicit_smooth", "Physics/smoothing=0.01"]),
            ("explicit smooth, delta = 1e-3", ["Physics/friction=explicit_smooth", "Physics/smoothing=0.001"])]


def friction(ctx):
    cells, cfls = ([100, 400], [0.05, 0.2]) if ctx.quick else ([100, 200, 400, 800], [0.025, 0.05, 0.1, 0.2])
    variants = FRICTION[:2] if ctx.quick else FRICTION
    items = sorted({(v, n, 0.2) for v in range(len(variants)) for n in cells} |
                   {(v, 400, c) for v in range(len(variants)) for c in cfls})

    def one(v, n, cfl):
        label, sets = variants[v]
        run = ctx.run("friction/v%d-n%d-cfl%s" % (v, n, tag(cfl)), "tests/column/m1_stuck.prm", sets + [
            "Mesh/cells=%d" % n, "Time stepping/CFL number=%.12g" % cfl])
        s, steps = run.summary, run.summary.get("n_time_steps", 0)
        return dict(friction=label, cells=n, cfl=cfl, exit=run.code,
                    dt=s.get("final_time", 8.) / steps if steps else math.nan,
                    **diagnostics(s, "velocity_sign_flips", "probe_strain_drift", "max_velocity"),
                    time_loop_cpu_s=s.get("time_loop_cpu_s", math.nan), message=run.stderr[:160])

    rows = ctx.pmap(one, items)
    ctx.csv("failure-friction", rows)
    fig, ax = plot.subplots(2, 2, figsize=(11, 7))
    floor = {"velocity_sign_flips": 0.5, "probe_strain_drift": 1e-17}
    notes = ["**friction** (column m = 1 on (0, 10), P2, characteristic limiter, t = 8; the probe "
             "z = 0.5 is at rest from t = 3.3 in the exact solution):"]
    for v, (label, _) in enumerate(variants):
        by_cells, by_dt = select(rows, friction=label, cfl=0.2), select(rows, friction=label, cells=400)
        for row, (key, sel) in enumerate((("cells", by_cells), ("dt", by_dt))):
            sel = sorted([r for r in sel if r["exit"] == 0], key=lambda r: r[key])
            for col, q in enumerate(floor):
                y = [max(abs(r[q]), floor[q]) for r in sel]
                ax[row, col].loglog([r[key] for r in sel], y, ["o-", "s--", "^:", "v-."][v], ms=5, label=label)
        joined = lambda sel, key, digits: "/".join(fmt(r[key], digits) for r in sel)
        notes.append("  - %s, CFL 0.2, cells %s: sign flips %s; probe drift %s" % (
            label, "/".join(str(r["cells"]) for r in by_cells),
            "/".join(fmt(r["velocity_sign_flips"], 6) if r["exit"] == 0 else "exit %d" % r["exit"]
                     for r in by_cells), joined(by_cells, "probe_strain_drift", 2)))
        notes.append("    400 cells, dt %s: sign flips %s; probe drift %s; max v at t = 8 %s" % (
            joined(by_dt, "dt", 3), joined(by_dt, "velocity_sign_flips", 6),
            joined(by_dt, "probe_strain_drift", 2), joined(by_dt, "max_velocity", 2)))
    for row, (xl, key) in enumerate((("cells on (0, 10) (CFL 0.2, dt ~ dx)", "cells"),
                                     ("time step dt (400 cells)", "dt"))):
        for col, y in enumerate(("velocity sign flips", "|strain drift| of the probe, t = 4..8")):
            plot.label(ax[row, col], xl, y, legend=7 if row == col == 0 else None)
            plot.log_ticks(ax[row, col], [r[key] for r in rows if r["exit"] == 0 and math.isfinite(r[key])])
    fig.suptitle("Coulomb friction in the column (m = 1, t = 8): chatter (velocity sign flips) and creep "
                 "of stuck material (strain drift)\nof the explicit treatments against the projection "
                 "(an exact 0 is drawn at 0.5 flips and 1e-17 drift)", fontsize=9)
    ctx.save(fig, "failure-friction")
    return notes


# ----------------------------------------------------------------------- rk3
def rk3(ctx):
    path = os.path.join(ctx.out, "layered_1d-stability.csv")
    if not os.path.exists(path):
        return ["**rk3**: no layered_1d-stability.csv (stability maps skipped)"]
    rows = outputs.read_table(path, numbers=False).rows()
    degrees = sorted({int(r["degree"]) for r in rows})
    fig, ax = plot.subplots(figsize=(7, 4.2))
    out = []
    notes = ["**rk3** (smooth wave, 32 cells, t = 1, LLF, no limiter; from layered_1d-stability.csv):"]
    for p in degrees:
        sel = sorted([r for r in rows if int(r["degree"]) == p], key=lambda r: float(r["cfl"]))
        x = [float(r["cfl"]) / LINEAR_RK3[p] for r in sel]
        y = [float(r["error"]) for r in sel]
        line, = ax.loglog(x, y, "-", lw=0.8, label="P%d" % p)
        for xi, yi, r in zip(x, y, sel):
            marker = {"stable": "o", "oscillatory": "s", "blown up": "x", "inadmissible": "D"}.get(r["state"], "+")
            ax.scatter([xi], [yi], marker=marker, color=line.get_color(), s=18)
            out.append(dict(degree=p, cfl=r["cfl"], cfl_over_linear_limit=xi, error=yi, state=r["state"]))
        good = [r for r in out[-len(sel):] if r["state"] == "stable"]
        bad = [r for r in out[-len(sel):] if r["state"] != "stable" and good and
               r["cfl_over_linear_limit"] > good[-1]["cfl_over_linear_limit"]]
        if good and bad:
            notes.append("  - P%d: error %s at %s x the linear limit (stable), %s (%s) at %s x" % (
                p, fmt(good[-1]["error"]), fmt(good[-1]["cfl_over_linear_limit"]), fmt(bad[0]["error"]),
                bad[0]["state"], fmt(bad[0]["cfl_over_linear_limit"])))
    ax.axvline(1, color="k", lw=0.8, ls=":")
    plot.log_ticks(ax, [0.25, 0.5, 0.75, 1, 1.25, 1.5, 2])
    plot.label(ax, "CFL / linear SSP-RK3 DG limit of the degree (1.256, 0.410, 0.210, 0.130, 0.0897)",
               "L1 error at t = 1 (smooth wave, 32 cells)", "SSP-RK3 DG beyond its linear CFL limit (smooth wave, "
               "LLF, no limiter)\n(o stable, s energy grew, x blown up)", legend=7, size=9)
    ctx.save(fig, "failure-rk3")
    ctx.csv("failure-rk3", out)
    return notes


# --------------------------------------------------------------------- shock
def wall_strain_bound(rho=2., K=2., beta=0.3, speed=0.4):
    """The strain eps_w of the simple wave at the wall moving with the largest
    speed of its data: phi(eps_w) = speed for phi(eps) = int_0^eps c de =
    ((K + 2 beta K^2 eps)^1.5 - K^1.5) / (3 beta K^2 sqrt(rho)), c =
    sqrt(sigma'/rho), sigma = K eps + beta K^2 eps^2 (law (1.4)); the range
    [0, eps_w] holds the simple wave the wall drives (prm/elasticity_shock.prm:
    rho = K = 2, beta = 0.3, u(0, t) = -0.2 (1 + cos(...)), |u| <= 0.4)."""
    return ((K ** 1.5 + 3 * beta * K * K * math.sqrt(rho) * speed) ** (2 / 3) - K) / (2 * beta * K * K)


def shock(ctx):
    eps_w, t_end = wall_strain_bound(), 240  # the case as shipped (at t = 120 no degree overshoots yet)
    degrees = [1] if ctx.quick else [1, 2, 3, 4]
    limiters = [("characteristic minmod (M = 0)", "characteristic"), ("no limiter", "none")]

    def one(p, label, lim):
        cfl = 0.07 if p == 4 else 0.75 / (2 * p + 1)
        run = ctx.run("shock/%s-p%d" % (lim, p), "prm/elasticity_shock.prm", EVERYWHERE + [
            "Discretization/degree=%d" % p, "Limiter/scheme=" + lim, "Time stepping/CFL number=%.12g" % cfl])
        r = dict(limiter=label, degree=p, cfl=cfl, exit=run.code, message=run.stderr[:160],
                 time_loop_cpu_s=run.summary.get("time_loop_cpu_s", math.nan))
        if run.code == 0:
            prof = outputs.read_table(outputs.latest(run.directory, "profile"))
            strain = prof["strain"]
            r.update(final_max_strain=strain.max(), final_min_strain=strain.min(),
                     overshoot_pct=100 * max(0., strain.max() - eps_w) / eps_w,
                     undershoot_pct=100 * max(0., -strain.min()) / eps_w, profile=prof)
        return r

    rows = ctx.pmap(one, [(p, *l) for l in limiters for p in degrees])
    ctx.csv("failure-shock", [{k: v for k, v in r.items() if k != "profile"} for r in rows])
    done = [r for r in rows if r["exit"] == 0]
    fig, ax = plot.subplots(1, 2, figsize=(11, 4.2))
    for (label, lim), c in zip(limiters, ("tab:blue", "tab:red")):
        sel = select(done, limiter=label)
        for key, style, what in (("overshoot", "o-", "above eps_w"), ("undershoot", "s--", "below 0")):
            ax[0].plot([r["degree"] for r in sel], [r[key + "_pct"] for r in sel], style, color=c,
                       label="%s %s, %s" % (key, what, label))
    top = max([r.get("overshoot_pct", 0) for r in rows] + [r.get("undershoot_pct", 0) for r in rows] + [1])
    ax[0].set(ylim=(-0.05 * top, 1.6 * top), xticks=degrees)  # room for the legend above the curves
    plot.label(ax[0], "degree", "%% of eps_w = %.4f at t = %g" % (eps_w, t_end), legend=7, which="major")
    # the profiles at the shock: the steepest drop of the last limited run's
    limited = select(done, limiter=limiters[0][0])
    if limited:
        t = limited[-1]["profile"]
        xs = t["x"][np.argmin(np.diff(t["strain"])) if len(t) > 1 else 0]
        for r in done:
            x, e = r["profile"]["x"], r["profile"]["strain"]
            w = (x > xs - 10) & (x < xs + 5)
            unlimited = r["limiter"] == limiters[1][0]
            ax[1].plot(x[w], e[w], "-" if unlimited else ":", lw=1,
                       label="P%d, %s" % (r["degree"], "no limiter" if unlimited else "limited"))
        ax[1].axhline(eps_w, color="gray", lw=0.6, ls="--")
        ax[1].axhline(0, color="gray", lw=0.6, ls="--")
        plot.label(ax[1], "x", "strain at t = %g" % t_end, legend=(6, 2))
    fig.suptitle("The unlimited scheme at a shock (prm/elasticity_shock.prm, dx = 0.25): over- and "
                 "undershoots; the characteristic minmod limiter removes them", fontsize=9)
    ctx.save(fig, "failure-shock")
    return ["**shock** (prm/elasticity_shock.prm, 1200 cells, t = %g; simple-wave range [0, eps_w], "
            "eps_w = %.4f; strain at p + 1 equidistant points per cell):" % (t_end, eps_w)] + [
        "  - P%d, %s: strain in [%.4f, %.4f]: overshoot %.1f %%, undershoot %.1f %%" % (
            r["degree"], r["limiter"], r["final_min_strain"], r["final_max_strain"], r["overshoot_pct"],
            r["undershoot_pct"]) if r["exit"] == 0 else
        "  - P%d, %s: exit %d: %s" % (r["degree"], r["limiter"], r["exit"], r["message"]) for r in rows]


# -------------------------------------------------------------------- hopper
HOPPER_TAU = 0.3


def hopper(ctx):
    cases = [("cone", 31), ("cone", 35)] if ctx.quick else \
        [("cone", 25), ("cone", 31), ("cone", 32), ("cone", 33), ("cone", 35), ("wedge", 35)]
    meshes = [100, 200] if ctx.quick else [100, 200, 400, 800]
    # N = 1600 (16x the work of N = 400) only where it changes the outcome
    finest = [] if ctx.quick else [("cone", 31, 1600)]

    def one(g, a, n):
        run = ctx.run("hopper/%s-30-%g-n%d" % (g, a, n), "prm/hopper_cone_30_25.prm", [
            "Hopper/geometry=" + g, "Hopper/lower half-angle=%g" % a, "Hopper/cells=%d" % n,
            "Time stepping/final time=%g" % HOPPER_TAU, "Hopper output/step series interval=0"])
        code, s = run.code, run.summary
        return dict(geometry=g, upper=30, lower=a, cells=n, exit=code,
                    outcome="completes" if code == 0 else ("hyperbolicity lost" if code == 3 else "exit %d" % code),
                    tau_reached=s.get("final_time", math.nan),
                    **diagnostics(s, "min_hyperbolicity_margin", "tau_of_min_margin", "theta_of_min_margin_deg"),
                    time_loop_cpu_s=s.get("time_loop_cpu_s", math.nan), message=run.stderr[:200])

    rows = ctx.pmap(one, [(g, a, n) for g, a in cases for n in meshes] + finest)
    ctx.csv("failure-hopper", rows)
    fig, ax = plot.subplots(1, 2, figsize=(11, 4.2))
    labels = ["%s 30 -> %g" % c for c in cases]
    notes = ["**hopper** (P1, CFL 1/3, characteristic limiter, marched to tau = %g):" % HOPPER_TAU]
    for i, (g, a) in enumerate(cases):
        sel = select(rows, geometry=g, lower=a)
        for r in sel:
            ok = r["exit"] == 0
            ax[0].scatter([r["cells"]], [i], marker="o" if ok else "x", s=40, color="tab:green" if ok else "tab:red")
            ax[0].annotate(("m %.2g" % r["min_hyperbolicity_margin"]) if ok else ("tau %.4g" % r["tau_reached"]),
                           (r["cells"], i), xytext=(4, 5), textcoords="offset points", fontsize=6.5)
        fail = sorted(select(sel, exit=3), key=lambda r: r["cells"])
        if fail:
            ax[1].semilogx([r["cells"] for r in fail], [r["tau_reached"] for r in fail], "x-", label=labels[i])
        notes.append("  - %s 30 -> %g: %s" % (g, a, "; ".join(
            "N %d %s" % (r["cells"], ("completes, min margin %s at tau %s" % (
                fmt(r["min_hyperbolicity_margin"], 2), fmt(r["tau_of_min_margin"], 3))) if r["exit"] == 0 else
                "fails at tau %s (theta %s deg)" % (fmt(r["tau_reached"], 4), fmt(r["theta_of_min_margin_deg"], 2)))
            for r in sel)))
    for a in ax:
        plot.log_ticks(a, [r["cells"] for r in rows])
    ax[0].set_yticks(range(len(cases)), labels, fontsize=7)
    ax[0].set_ylim(-0.5, len(cases) - 0.3)
    plot.label(ax[0], "cells N (P1)", title="o completes to tau = %g (m: min hyperbolicity margin), x loses "
               "hyperbolicity (tau)" % HOPPER_TAU, size=8)
    plot.label(ax[1], "cells N (P1)", "tau at which hyperbolicity is lost",
               legend=7 if ax[1].get_legend_handles_labels()[0] else None)
    fig.suptitle("Hopper: steep-to-shallow transitions (30 deg -> shallower lower hopper) lose "
                 "hyperbolicity where the corner shock focuses on the axis", fontsize=9)
    ctx.save(fig, "failure-hopper")
    return notes


MODES = [(interfaces, "layered_1d"), (friction, "column"), (rk3, "layered_1d"), (shock, "layered_1d"),
         (hopper, "hopper")]


def run_all(ctx, scenes):
    notes = []
    for f, scene in MODES:
        if scene in scenes:
            print("failure mode %s" % f.__name__, flush=True)
            notes += f(ctx) + [""]
    Path(ctx.out, "failures.md").write_text("# Where the methods fail: the numbers behind failure-*.png\n\n"
                                            "Written by contrib/study.py (contrib/study_failures.py)%s.\n\n%s\n" % (
                                                " --quick" if ctx.quick else "", "\n".join(notes)))
