#!/usr/bin/python3
"""Speed against accuracy across the scenes (issue 7): work-precision charts,
CFL x degree stability maps with the limits found by bisection, and the
cheapest configuration reaching two target errors per scene.

    /usr/bin/python3 contrib/study.py BUILD_DIR OUT_DIR [--quick] [--only scene,...]
        [--skip-stability] [--skip-work-precision]

OUT_DIR (doc/study for the committed charts) gets, per scene S,
  S-work-precision.{png,svg,csv}  error against CPU time of the time loop and
                                  against the wall time of the run, one curve
                                  per degree (log-log);
  S-stability.{png,svg,csv}       CFL x degree map and the bisected limits;
and cheapest.{csv,md}, stability-limits.csv, runtime.txt. Runs go to
OUT_DIR/runs/ (reused when their summary.json exists; delete to rerun).
One granular_dg process at a time. doc/study/README.md reads the charts.

The per-scene description (SCENES below): the case file, the mesh parameter
and its values, the degrees, the CFL number used for the work-precision runs
(per degree), how the error against the exact solution is read from
summary.json, the two target errors, and the mesh and CFL grid of the
stability map (None: no map).

Classification of a stability run (fixed mesh, to the final time):
  blown up      exit 2 with a non-finite state, or an error > 1 (the data are O(0.1-1));
  inadmissible  exit 2 naming another admissibility test (e.g. negative strain);
  oscillatory   completed, but: for an energy-stable case (stability energy=True:
                the linear wave with the dissipative LLF flux) the discrete energy
                grew; otherwise (the limited column, whose energy is fed by the
                wall) the error is > 2 e0, e0 = the error of the same degree at the
                smallest CFL of the grid (the limiter holds the run bounded, the
                instability shows as lost accuracy);
  stable        completed, otherwise;
  refused       exit 1: the program's input check refuses the CFL number
                (lead's require_stable_cfl, newer than this study's runs).
The limit is the largest stable CFL, bisected between the largest stable and
the smallest non-stable grid value (relative width 2 % full, 8 % quick).
"""
import argparse
import csv
import json
import math
import os
import subprocess
import sys
import time

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)
QUIET = ["Output/output times=", "Output/write vtu=false", "Output/progress interval=0",
         "Output/overwrite=true"]


def sum_l1(s, d):
    """Sum over the components of the L1 error against the exact solution."""
    e = s.get("errors", {})
    vals = [v[0] for k, v in e.items() if k.endswith("_l1_l2_linf")]
    return sum(vals) if vals else float("nan")


def network_l1(s, d):
    return s.get("diagnostics", {}).get("l1_error", float("nan"))


def hopper_radial(s, d):
    """Relative L1 error of (T_rr, T_rtheta)/r against the exact radial field
    at 2001 equidistant theta (doc/hopper.md 4.7, contrib/hopper_runs.py)."""
    import numpy as np
    path = os.path.join(d, "stress-0001.csv")
    if not os.path.exists(path):
        return float("nan")
    with open(path) as f:
        skip = 1 if f.readline().startswith("#") else 0
    t = np.genfromtxt(path, delimiter=",", names=True, skip_header=skip)
    num = np.abs(t["T_rr_over_r"] - t["radial_T_rr_over_r"]) + \
        np.abs(t["T_rtheta_over_r"] - t["radial_T_rtheta_over_r"])
    den = np.abs(t["radial_T_rr_over_r"]) + np.abs(t["radial_T_rtheta_over_r"])
    return float(np.trapz(num, t["theta"]) / np.trapz(den, t["theta"]))


def cpu_loop(s):
    if "cpu_time_loop_s" in s.get("diagnostics", {}):  # the network's own loop
        return s["diagnostics"]["cpu_time_loop_s"]
    return s.get("time_loop_cpu_s", float("nan"))


SCENES = {
    # m = 1, t = 4 against the closed form (the frozen region included)
    "column": dict(
        prm="tests/column/m1_base.prm", mesh="Mesh/cells",
        cells=[25, 50, 100, 200, 400, 800, 1600], quick_cells=[25, 50, 100, 200],
        degrees=[0, 1, 2, 3], quick_degrees=[1, 2], cfl=lambda p: 0.9 / (2 * p + 1),
        error=sum_l1, error_name="L1 error (strain + velocity) at t = 4",
        targets=[1e-2, 1e-3], stability=dict(cells=200), extra=[]),
    # the smooth periodic linear wave of the layered_strip scene (1D)
    "layered_1d": dict(
        prm="prm/elasticity_linear_wave.prm", mesh="Mesh/cells x",
        cells=[8, 16, 32, 64, 128, 256], quick_cells=[8, 16, 32],
        degrees=[0, 1, 2, 3, 4], quick_degrees=[1, 2],
        # 0.9/(2p+1), but P4 blows up there (its limit is ~0.09): 0.07
        cfl=lambda p: 0.07 if p == 4 else 0.9 / (2 * p + 1),
        error=sum_l1, error_name="L1 error (strain + velocity) at t = 1",
        targets=[1e-4, 1e-7], stability=dict(cells=32, energy=True), extra=[]),
    # the 2D strip scene on the same wave, 2 cells across in y (periodic)
    "layered_2d": dict(
        prm="prm/elasticity_linear_wave.prm", mesh="Mesh/cells x",
        cells=[8, 16, 32, 64], quick_cells=[8, 16],
        degrees=[1, 2, 3], quick_degrees=[2], cfl=lambda p: 0.9 / (2 * p + 1),
        error=sum_l1, error_name="L1 error (strain + velocity) at t = 1",
        targets=[1e-4, 1e-6], stability=None,
        extra=["Mesh/dimension=2", "Mesh/cells y=2", "Mesh/y min=0", "Mesh/y max=0.25",
               "Boundary conditions/bottom=periodic", "Boundary conditions/top=periodic",
               "Initial condition/velocity=-0.1*sin(2*pi*x); 0",
               "Exact solution/velocity=-0.1*sin(2*pi*(x-t)); 0"]),
    # the smooth network case (exact solution by characteristics), the vertex
    # without volume (the paper's vertex cell caps every degree at order 1,
    # doc/network.md)
    "network": dict(
        prm="prm/network_smooth.prm", mesh="Network/cells per unit length",
        cells=[8, 16, 32, 64, 128, 256, 512], quick_cells=[8, 16, 32],
        degrees=[0, 1, 2, 3], quick_degrees=[1, 2],
        cfl=lambda p: {0: 0.5, 1: 0.3, 2: 0.18, 3: 0.03}[p],
        error=network_l1, error_name="L1 error (edges + vertex) at t = 0.5",
        targets=[1e-3, 1e-5], stability=None, extra=["Network/vertex width factor=0"]),
    # the 30 deg cone marched to tau = 1 against the exact radial field,
    # without the limiter (with it P2 and P3 are capped at 3rd order, doc/hopper.md)
    "hopper": dict(
        prm="prm/hopper_radial_cone.prm", mesh="Hopper/cells",
        cells=[25, 50, 100, 200, 400], quick_cells=[25, 50, 100],
        degrees=[1, 2, 3], quick_degrees=[1, 2],
        cfl=lambda p: {1: 1 / 3., 2: 1 / 5., 3: 0.12}[p],
        error=hopper_radial, error_name="relative difference to the radial field at tau = 1",
        targets=[1e-3, 1e-5], stability=None,
        extra=["Time stepping/final time=1", "Hopper output/step series interval=0",
               "Hopper output/sample points=2001", "Limiter/scheme=none"]),
}


def load():
    with open("/proc/loadavg") as f:
        return f.read().split()[0]


def run(build, d, prm, sets):
    """granular_dg PRM with --set overrides into directory d; reused when
    d/summary.json and d/exit.txt exist. Returns (exit code, summary, stderr)."""
    done = os.path.join(d, "exit.txt")
    if os.path.exists(done) and os.path.exists(os.path.join(d, "summary.json")):
        with open(done) as f:
            code, err = f.read().split("\n", 1)
        with open(os.path.join(d, "summary.json")) as f:
            return int(code), json.load(f), err
    os.makedirs(d, exist_ok=True)
    cmd = [os.path.join(build, "granular_dg"), os.path.join(ROOT, prm), "--set", "Output/directory=" + d]
    for s in QUIET + sets:
        cmd += ["--set", s]
    l0 = load()
    t0 = time.time()
    p = subprocess.run(cmd, capture_output=True, text=True)
    wall = time.time() - t0
    err = p.stderr.strip().replace("\n", " ")
    s = {}
    if os.path.exists(os.path.join(d, "summary.json")):
        with open(os.path.join(d, "summary.json")) as f:
            s = json.load(f)
    s["_run_wall_s"] = wall
    s["_load"] = l0
    with open(os.path.join(d, "summary.json"), "w") as f:
        json.dump(s, f)
    with open(done, "w") as f:
        f.write("%d\n%s" % (p.returncode, err))
    return p.returncode, s, err


def tag(v):
    return ("%.6g" % v).replace(".", "_")


def work_precision(build, out, name, sc, quick):
    degrees = sc["quick_degrees"] if quick else sc["degrees"]
    cells = sc["quick_cells"] if quick else sc["cells"]
    rows = []
    for p in degrees:
        for n in cells:
            cfl = sc["cfl"](p)
            d = os.path.join(out, "runs", name, "wp-p%d-n%d" % (p, n))
            code, s, err = run(build, d, sc["prm"], sc["extra"] + [
                "Discretization/degree=%d" % p, "%s=%d" % (sc["mesh"], n),
                "Time stepping/CFL number=%.12g" % cfl])
            e = sc["error"](s, d) if code == 0 else float("nan")
            rows.append(dict(scene=name, degree=p, cells=n, cfl=cfl, exit=code, error=e,
                             n_dofs=s.get("n_dofs", ""), steps=s.get("n_time_steps", ""),
                             time_loop_cpu_s=cpu_loop(s), run_wall_s=s["_run_wall_s"],
                             load=s["_load"]))
            print("%s P%d n=%d: exit %d error %.3e cpu %.3g s" % (
                name, p, n, code, e, rows[-1]["time_loop_cpu_s"]), flush=True)
    # blown up: exit 2, an error > 1, or an error above the coarser mesh's
    # (an instability growing: e.g. P4 above its CFL limit)
    for p in degrees:
        previous = float("inf")
        for r in [r for r in rows if r["degree"] == p]:
            r["blown_up"] = int(r["exit"] != 0 or not (r["error"] <= min(1., previous)))
            previous = r["error"] if math.isfinite(r["error"]) else previous
    write_csv(os.path.join(out, name + "-work-precision.csv"), rows)
    fig, axes = plt.subplots(1, 2, figsize=(10, 4.2), sharey=True)
    for ax, key, label in ((axes[0], "time_loop_cpu_s", "CPU time of the time loop [s]"),
                           (axes[1], "run_wall_s", "wall time of the run [s]")):
        for p in degrees:
            sel = [r for r in rows if r["degree"] == p and not r["blown_up"] and r["error"] > 0]
            if sel:
                ax.loglog([max(r[key], 1e-4) for r in sel], [r["error"] for r in sel], "o-",
                          ms=4, label="P%d" % p)
        for t in sc["targets"]:
            ax.axhline(t, color="gray", lw=0.6, ls=":")
        ax.set_xlabel(label)
        ax.grid(alpha=0.3, which="both")
    axes[0].set_ylabel(sc["error_name"])
    axes[0].legend(fontsize=8)
    fig.suptitle("%s: error against the exact solution vs cost (%s, SSP-RK3)" % (name, sc["prm"]),
                 fontsize=10)
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, "%s-work-precision.%s" % (name, ext)), dpi=110)
    plt.close(fig)
    return rows


def energy_grew(d):
    """Whether the discrete energy (timeseries.csv) grew from t = 0 to the end."""
    with open(os.path.join(d, "timeseries.csv")) as f:
        rows = list(csv.DictReader(l for l in f if not l.startswith("#")))
    e_first, e_last = float(rows[0]["energy"]), float(rows[-1]["energy"])
    return not (e_last <= e_first * (1 + 1e-10))


def classify(code, err, e, e0, grew=None):
    if code == 2:
        low = err.lower()
        if "finite" in low or "nan" in low or "inf" in low:
            return "blown up"
        return "inadmissible"
    if code == 1:  # bad input: the program refuses a CFL above its built-in limit
        return "refused"
    if code != 0:
        return "failed"
    if not math.isfinite(e) or e > 1:
        return "blown up"
    if grew is not None:  # energy-stable scheme: growth is the instability
        return "oscillatory" if grew else "stable"
    if e0 is not None and e > 2 * e0:
        return "oscillatory"
    return "stable"


def stability(build, out, name, sc, quick):
    degrees = sc["quick_degrees"] if quick else sc["degrees"]
    factors = [0.25, 0.5, 0.8, 1.0, 1.2, 1.5, 2.0, 3.0]
    rows, limits = [], []

    def one(p, cfl, e0):
        d = os.path.join(out, "runs", name, "st-p%d-cfl%s" % (p, tag(cfl)))
        code, s, err = run(build, d, sc["prm"], sc["extra"] + [
            "Discretization/degree=%d" % p, "%s=%d" % (sc["mesh"], sc["stability"]["cells"]),
            "Time stepping/CFL number=%.12g" % cfl, "Time stepping/check stability limit=false"])
        e = sc["error"](s, d) if code == 0 else float("nan")
        grew = energy_grew(d) if code == 0 and sc["stability"].get("energy") else None
        c = classify(code, err, e, e0, grew)
        rows.append(dict(scene=name, degree=p, cfl=cfl, exit=code, error=e, state=c,
                         time_loop_cpu_s=cpu_loop(s), message=err[:200]))
        print("%s stability P%d CFL %.4g: %s (error %.3e)" % (name, p, cfl, c, e), flush=True)
        return c, e

    for p in degrees:
        grid = sorted({min(1.0, f / (2 * p + 1)) for f in factors})
        e0 = None
        states = []
        for cfl in grid:
            c, e = one(p, cfl, e0)
            if e0 is None:
                e0 = e if c == "stable" or math.isfinite(e) else None
            states.append((cfl, c))
        stable = [cfl for cfl, c in states if c == "stable"]
        lo = max(stable) if stable else None
        above = [cfl for cfl, c in states if c != "stable" and lo is not None and cfl > lo]
        hi = min(above) if above else None
        if lo is not None and hi is not None:
            while (hi - lo) / lo > (0.08 if quick else 0.02):
                mid = 0.5 * (lo + hi)
                c, _ = one(p, mid, e0)
                if c == "stable":
                    lo = mid
                else:
                    hi = mid
        first_bad = [c for cfl, c in sorted((r["cfl"], r["state"]) for r in rows
                                             if r["degree"] == p) if hi is not None and cfl >= hi]
        limits.append(dict(scene=name, degree=p, cfl_limit=lo if lo is not None else "",
                           first_unstable_cfl=hi if hi is not None else "",
                           limit_times_2p_plus_1=lo * (2 * p + 1) if lo is not None else "",
                           state_above=first_bad[0] if first_bad else "none up to CFL 1"))
    write_csv(os.path.join(out, name + "-stability.csv"), rows)
    colors = {"stable": "tab:green", "oscillatory": "tab:orange", "inadmissible": "tab:purple",
              "blown up": "tab:red", "refused": "gray", "failed": "black"}
    markers = {"stable": "o", "oscillatory": "s", "inadmissible": "D", "blown up": "x", "refused": "_", "failed": "+"}
    fig, ax = plt.subplots(figsize=(7, 4))
    for state in colors:
        sel = [r for r in rows if r["state"] == state]
        if sel:
            ax.scatter([r["cfl"] for r in sel], [r["degree"] for r in sel], c=colors[state],
                       marker=markers[state], label=state, s=30)
    for l in limits:
        if l["cfl_limit"] != "":
            ax.plot([l["cfl_limit"]] * 2, [l["degree"] - 0.3, l["degree"] + 0.3], "k-", lw=1.5)
    ps = [l["degree"] for l in limits]
    ax.plot([1 / (2 * p + 1) for p in ps], ps, "k:", lw=0.8, label="1/(2p+1)")
    ax.set_xscale("log")
    ax.set_xlabel("CFL number (bar: bisected limit)")
    ax.set_ylabel("degree")
    ax.set_yticks(ps)
    ax.set_title("%s: SSP-RK3 stability on %d cells" % (name, sc["stability"]["cells"]), fontsize=10)
    ax.grid(alpha=0.3, which="both")
    ax.legend(fontsize=7, loc="upper right")
    fig.tight_layout()
    for ext in ("png", "svg"):
        fig.savefig(os.path.join(out, "%s-stability.%s" % (name, ext)), dpi=110)
    plt.close(fig)
    return limits


def write_csv(path, rows):
    if not rows:
        return
    keys = []
    for r in rows:
        keys += [k for k in r if k not in keys]
    with open(path, "w") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def cheapest(out, all_rows):
    res = []
    for name, sc in SCENES.items():
        # completed runs that did not blow up (error <= 1)
        rows = [r for r in all_rows if r["scene"] == name and not r["blown_up"]]
        if not rows:
            continue
        for t in sc["targets"]:
            ok = [r for r in rows if r["error"] <= t]
            if ok:
                b = min(ok, key=lambda r: r["time_loop_cpu_s"])
                res.append(dict(scene=name, target_error=t, degree=b["degree"], cells=b["cells"],
                                cfl="%.4g" % b["cfl"], error="%.3e" % b["error"],
                                time_loop_cpu_s="%.4g" % b["time_loop_cpu_s"],
                                run_wall_s="%.3g" % b["run_wall_s"], load=b["load"]))
            else:
                best = min(rows, key=lambda r: r["error"])
                res.append(dict(scene=name, target_error=t, degree="not reached",
                                cells="", cfl="", error="best %.3e (P%d, %d cells)" % (
                                    best["error"], best["degree"], best["cells"]),
                                time_loop_cpu_s="", run_wall_s="", load=""))
    write_csv(os.path.join(out, "cheapest.csv"), res)
    with open(os.path.join(out, "cheapest.md"), "w") as f:
        f.write("| scene | target error | degree | cells | CFL | error | CPU time loop [s] | wall run [s] | load |\n")
        f.write("|---|---|---|---|---|---|---|---|---|\n")
        for r in res:
            f.write("| %s | %g | %s | %s | %s | %s | %s | %s | %s |\n" % (
                r["scene"], r["target_error"], r["degree"], r["cells"], r["cfl"], r["error"],
                r["time_loop_cpu_s"], r["run_wall_s"], r["load"]))


def main():
    ap = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    ap.add_argument("build")
    ap.add_argument("out")
    ap.add_argument("--quick", action="store_true", help="a few meshes and degrees (a smoke run)")
    ap.add_argument("--only", default=",".join(SCENES))
    ap.add_argument("--skip-stability", action="store_true")
    ap.add_argument("--skip-work-precision", action="store_true")
    a = ap.parse_args()
    os.makedirs(a.out, exist_ok=True)
    t0, c0 = time.time(), os.times()
    all_rows, limits = [], []
    only = a.only.split(",")
    for name in only:
        sc = SCENES[name]
        if not a.skip_work_precision:
            all_rows += work_precision(a.build, a.out, name, sc, a.quick)
        if sc["stability"] and not a.skip_stability:
            limits += stability(a.build, a.out, name, sc, a.quick)
    if all_rows:
        cheapest(a.out, all_rows)
    if limits:
        write_csv(os.path.join(a.out, "stability-limits.csv"), limits)
    c1 = os.times()
    with open(os.path.join(a.out, "runtime.txt"), "w") as f:
        f.write("study %s (%s): wall %.1f s, CPU of the runs %.1f s, load at the end %s\n" % (
            "quick" if a.quick else "full", ",".join(only), time.time() - t0,
            (c1.children_user - c0.children_user) + (c1.children_system - c0.children_system), load()))
    print(open(os.path.join(a.out, "runtime.txt")).read())


if __name__ == "__main__":
    sys.exit(main())
