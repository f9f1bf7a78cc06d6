#!/usr/bin/python3
"""Operator throughput of granular_dg (its --benchmark mode) for every physics
at degrees 1-4, and of deal.II's step-67 (Euler, MatrixFree) built from
Debian's libdeal.ii-doc examples as the comparator. doc/performance.md.

    /usr/bin/python3 contrib/benchmark.py BUILD_DIR OUT_DIR [--quick] [--no-step67]
        [--degrees 1,2,3,4] [--cases name,...] [--mpi] [--step67-dims 2,1] [--reuse]

OUT_DIR gets throughput.csv and throughput.md (the table of doc/performance.md)
and one directory per run with its benchmark.json. step-67 is copied into
BUILD_DIR/step67-<dim>d-p<k>/, patched (patch_step67), built in Release and
run; its throughput is n_dofs * 5 stages * steps / CPU time of "rk time
stepping total". Rates are million DoF-stage updates per second per core (CPU
time; median of the repetitions); the load average is recorded with every
run. Run it alone: it runs one process at a time (two with --mpi).
"""
import json
import os
import re
import shutil
import subprocess
from pathlib import Path

from granular_dg import arguments, outputs
from granular_dg.run import ENV, NO_SNAPSHOTS, ROOT, cfl_limits, load, run_case
from make_network_grid import write_grid

STEP67 = "/usr/share/doc/libdeal.ii-doc/examples/step-67/step-67.cc"
# the shipped CFL numbers, capped at the SSP-RK3 limit of the degree by
# cfl_override() (the time step does not change the cost of a step)
QUIET = NO_SNAPSHOTS + ("Time stepping/check stability limit=false",)

# name: (prm, dim, extra --set overrides). Meshes as shipped, except the
# network (degree 0 ships; the limiter is on for p >= 1 as in its study), and
# the column and the 2D strip compute every cell (skip tolerance 0, skip
# cells at rest false: the cost of a full step; what skipping saves is
# measured on whole runs, doc/column.md and doc/engine.md), and
# layered_1d limits every cell (the modal-energy indicator it ships flags
# few: the benchmark keeps measuring the full limiter's cost, comparable with
# the earlier tables of doc/performance.md).
CASES = {
    "layered_1d": ("prm/layered_1d.prm", 1, ["Limiter/indicator=everywhere"]),
    "layered_2d": ("prm/layered_2d.prm", 2, ["Time stepping/skip cells at rest=false"]),
    "column": ("prm/column_m1.5.prm", 1, ["Time stepping/skip tolerance=0"]),
    "hopper": ("prm/hopper_cone_30_24_p2.prm", 1, ["Hopper/cells=800"]),
    "network": ("prm/network_example_7_3.prm", 1, ["Limiter/scheme=componentwise"]),
    # a road network of 10224 edges and 5041 junctions (a 71 x 71 city grid,
    # contrib/make_network_grid.py, written into OUT_DIR by main()), 16 cells
    # per edge: the per-edge overhead next to the star graph's
    "network_grid": ("prm/network_city_grid.prm", 1, ["Network/edge profiles=none"]),
}
# the columns of throughput.csv; the rates are MDoF/s
FIELDS = ["code", "case", "dim", "degree", "ranks", "engine", "n_dofs", "steps", "cpu_us_per_step", "mdofs_step",
          "mdofs_rk", "mdofs_wall", "ratio_to_step67", "step_ratio_to_step67", "load_before", "load_after"]


def cfl_override(prm, degree):
    """The CFL number down to the program's SSP-RK3 limit of the degree when
    the case file's is above it (the program refuses it; the time step does
    not change the cost of a step)."""
    limit = cfl_limits()["ssp_rk3"][min(degree, 4)]
    m = re.search(r"^\s*set CFL number\s*=\s*([\d.eE+-]+)", Path(ROOT, prm).read_text(), re.M)
    return ["Time stepping/CFL number=%g" % limit] if m and float(m[1]) > limit else []


def run_ours(build, out, name, degree, quick, ranks=1, reuse=False):
    prm, dim, extra = CASES[name]
    d = os.path.join(out, "%s-p%d%s" % (name, degree, "-np%d" % ranks if ranks > 1 else ""))
    if not (reuse and os.path.exists(os.path.join(d, "benchmark.json"))):
        sets = ["Discretization/degree=%d" % degree, "Benchmark/minimum time=%g" % (0.05 if quick else 0.3),
                "Benchmark/repetitions=%d" % (3 if quick else 5)] + list(QUIET) + extra + cfl_override(prm, degree)
        r = run_case(build, prm, d, sets, ranks=ranks, benchmark=True, keep=False)
        if r.code != 0:
            print("FAILED %s p%d: %s" % (name, degree, r.stderr[-300:]))
            return None
    b = outputs.benchmark(d)
    return {"code": "granular_dg", "case": name, "dim": dim, "degree": degree, "ranks": ranks,
            "engine": b["case"]["engine"], "n_dofs": int(b["n_dofs"]),
            "steps": b["steps_per_repetition"] * b["repetitions"],
            "cpu_us_per_step": 1e6 * b["cpu_s_per_step_median"],
            "mdofs_step": b["step_dof_updates_per_s_per_core_median"] / 1e6,
            "mdofs_rk": b["rk_dof_updates_per_s_per_core_median"] / 1e6,
            "mdofs_wall": b["step_dof_updates_per_s_wall_median"] / 1e6,
            "load_before": b["load_before"], "load_after": b["load_after"]}


def patch_step67(s, dim, degree, refinements, steps):
    """step-67's source with its constants replaced (dimension, degree,
    refinements, a fixed number of time steps, CPU + wall timers, no VTU
    output); in 1D its testcase 0, the 2D vortex, becomes a smooth entropy
    wave with inflow data on both ends, and the Triangulation is serial."""
    subs = [(r"constexpr unsigned int dimension\s*= \d+;", "constexpr unsigned int dimension = %d;" % dim),
            (r"constexpr unsigned int n_global_refinements = \d+;",
             "constexpr unsigned int n_global_refinements = %d;" % refinements),
            (r"constexpr unsigned int fe_degree\s*= \d+;", "constexpr unsigned int fe_degree = %d;" % degree),
            (r"while \(time < final_time - 1e-12\)", "while (timestep_number < %d)" % steps),
            (r"TimerOutput::never, TimerOutput::wall_times", "TimerOutput::never, TimerOutput::cpu_and_wall_times"),
            (r"\n    output_results\(0\);", "\n"),
            (r"constexpr double output_tick = [^;]*;", "constexpr double output_tick = 1e30;"),
            (r"timer\.print_wall_time_statistics\(MPI_COMM_WORLD\);",
             'pcout << "BENCHMARK n_dofs " << dof_handler.n_dofs() << " steps " << timestep_number'
             ' << " stages " << integrator.n_stages() << " cpu " << timer.get_summary_data('
             'TimerOutput::total_cpu_time)["rk time stepping total"] << " wall " << '
             'timer.get_summary_data(TimerOutput::total_wall_time)["rk time stepping total"] << std::endl;')]
    if dim == 1:
        # p4est has no 1D: a serial Triangulation<1>. Testcase 0 (the vortex)
        # is 2D only: in 1D a smooth entropy wave on [0, 10], rho = 1 +
        # sin(2 pi (x - t)/10)/2, u = 1, p = 1 (exact for Euler), as initial
        # and inflow data on both ends (boundary ids 0 and 1)
        subs += [(r"#ifdef DEAL_II_WITH_P4EST", "#if 0"),
                 (r"            Assert\(dim == 2, ExcNotImplemented\(\)\);",
                  "            if (dim == 1)\n"
                  "              {\n"
                  "                const double rho = 1. + 0.5 * std::sin(2. * numbers::PI * (x[0] - t) / 10.);\n"
                  "                return component == 0 ? rho : component == 1 ? rho :\n"
                  "                       1. / (gamma - 1.) + 0.5 * rho;\n"
                  "              }"),
                 (r"            euler_operator\.set_inflow_boundary\(\n              0, std::make_unique<ExactSolution<dim>>\(0\)\);(?=\n\n            break;)",
                  "            euler_operator.set_inflow_boundary(\n              0, std::make_unique<ExactSolution<dim>>(0));\n"
                  "            if (dim == 1)\n"
                  "              euler_operator.set_inflow_boundary(1, std::make_unique<ExactSolution<dim>>(0));")]
    for a, b in subs:
        s, n = re.subn(a, b, s)
        if n == 0:
            raise RuntimeError("step-67 patch did not apply: " + a)
    return s


def run_step67(build, dim, degree, refinements, steps, reuse=False):
    """step-67 built in BUILD/step67-<dim>d-p<degree>/ (once) and run three
    times: the row of its best CPU time (kept in result.json; reused)."""
    d = os.path.join(os.path.abspath(build), "step67-%dd-p%d" % (dim, degree))
    exe, result = os.path.join(d, "step-67"), os.path.join(d, "result.json")
    if reuse and os.path.exists(result):
        return json.loads(Path(result).read_text())
    if not os.path.exists(exe):
        os.makedirs(d, exist_ok=True)
        Path(d, "step-67.cc").write_text(patch_step67(Path(STEP67).read_text(), dim, degree, refinements, steps))
        shutil.copy(os.path.join(os.path.dirname(STEP67), "CMakeLists.txt"), d)
        subprocess.run(["cmake", "-S", d, "-B", d, "-DCMAKE_BUILD_TYPE=Release"], check=True,
                       stdout=subprocess.DEVNULL)
        subprocess.run(["make", "-C", d, "-j1", "step-67"], check=True, stdout=subprocess.DEVNULL)
    before, runs = load(3), []
    for _ in range(3):
        p = subprocess.run([exe], cwd=d, capture_output=True, text=True, check=True, env=dict(os.environ, **ENV))
        m = re.search(r"BENCHMARK n_dofs (\d+) steps (\d+) stages (\d+) cpu ([\d.eE+-]+) wall ([\d.eE+-]+)",
                      p.stdout)
        runs.append((float(m[4]), int(m[1]), int(m[2]), int(m[3]), float(m[5])))
    cpu, n_dofs, n_steps, stages, wall = min(runs, key=lambda r: r[0])  # the first of the best CPU time
    rate = n_dofs * stages * n_steps / cpu / 1e6
    r = {"code": "step-67", "case": "euler_entropy_wave_1d" if dim == 1 else "euler_vortex_2d", "dim": dim,
         "degree": degree, "ranks": 1, "engine": "matrix_free", "n_dofs": n_dofs, "steps": n_steps,
         "cpu_us_per_step": 1e6 * cpu / n_steps, "mdofs_step": rate, "mdofs_rk": rate,
         "mdofs_wall": n_dofs * stages * n_steps / wall / 1e6, "load_before": before, "load_after": load(3)}
    Path(result).write_text(json.dumps(r))
    return r


def write_tables(out, rows):
    s67 = {(r["dim"], r["degree"]): r["mdofs_rk"] for r in rows if r["code"] == "step-67"}
    for r in rows:
        ref = s67.get((r["dim"], r["degree"])) if r["code"] != "step-67" else None
        # the whole step (limiter, admissibility, time step included) against
        # step-67's RK, which is its whole step
        r["ratio_to_step67"] = r["mdofs_rk"] / ref if ref else ""
        r["step_ratio_to_step67"] = r["mdofs_step"] / ref if ref else ""
    outputs.write_csv(os.path.join(out, "throughput.csv"),
                      [{k: ("%.4g" % r[k] if isinstance(r[k], float) else r[k]) for k in FIELDS} for r in rows])
    Path(out, "throughput.md").write_text(outputs.markdown(
        ["code", "case", "dim", "p", "ranks", "engine", "DoFs", "CPU us/step", "MDoF/s/core step",
         "MDoF/s/core RK", "MDoF/s wall", "RK / step-67", "step / step-67", "load before -> after"],
        [[r[k] for k in ("code", "case", "dim", "degree", "ranks", "engine", "n_dofs")] +
         ["%.1f" % r[k] for k in ("cpu_us_per_step", "mdofs_step", "mdofs_rk", "mdofs_wall")] +
         ["%.2f" % r[k] if r[k] != "" else "" for k in ("ratio_to_step67", "step_ratio_to_step67")] +
         ["%s -> %s" % (r["load_before"], r["load_after"])] for r in rows]))


if __name__ == "__main__":
    a = arguments(__doc__, [
        "build", "out", ("--quick", dict(action="store_true", help="short repetitions (a smoke run)")),
        ("--no-step67", dict(action="store_true")), ("--degrees", dict(default="1,2,3,4")),
        ("--step67-degrees", dict(default="1,2,3,4")), ("--cases", dict(default=",".join(CASES))),
        ("--step67-dims", dict(default="2,1", help="2: the vortex on 128^2 cells; 1: an entropy wave on 1024 cells")),
        ("--mpi", dict(action="store_true",
                       help="also on 2 ranks: layered_2d (p = 2, 3) and network_grid (p = 0, 2), those of --cases")),
        ("--reuse", dict(action="store_true", help="take runs with a result already there"))])
    os.makedirs(a.out, exist_ok=True)
    cases, rows = [c for c in a.cases.split(",") if c], []
    if "network_grid" in cases:  # the 71 x 71 grid's files, named in the case's overrides
        grid = [os.path.join(os.path.abspath(a.out), f) for f in ("grid71.csv", "grid71_vertices.csv")]
        write_grid(71, *grid)
        CASES["network_grid"][2].extend(["Network/graph file=" + grid[0], "Network/vertex file=" + grid[1]])

    def add(row):
        if row:
            rows.append(row)
            print(row, flush=True)
            write_tables(a.out, rows)

    mpi = [(n, p, 2) for n, ps in (("layered_2d", (2, 3)), ("network_grid", (0, 2))) for p in ps
           if a.mpi and n in cases]
    for name, p, ranks in [(name, int(p), 1) for name in cases for p in a.degrees.split(",")] + mpi:
        add(run_ours(a.build, a.out, name, p, a.quick, ranks, a.reuse))
    # 2D: [0,10] x [-5,5], 4 x 2^refinements cells per direction: 128^2 cells, as
    # many DoFs as the 2D strip (0.3-1.2 M); 1D: [0, 10], 4 x 2^8 = 1024 cells
    # (the 1D cases have 1200-1600); (refinements, time steps, --quick's)
    step67 = {2: (5, 60, 20), 1: (8, 1000, 100)}
    for dim, p in ((int(d), int(p)) for d in a.step67_dims.split(",") for p in a.step67_degrees.split(",")):
        if not a.no_step67:
            refinements, steps, quick = step67[dim]
            add(run_step67(a.build, dim, p, refinements, quick if a.quick else steps, reuse=a.reuse))
    write_tables(a.out, rows)
