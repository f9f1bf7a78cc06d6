#!/usr/bin/python3
"""The readers of contrib/granular_dg against outputs the test suite writes:
what they parse must agree with what the program wrote (rows against
summary.json's steps, times across files, known values), and a malformed
file must raise OutputError naming the file and line.

    readers.py layered|network|hopper|convergence|benchmark RUN_DIR
    readers.py malformed RUN_DIR    (a layered run; corrupted copies go to the working directory)
    readers.py compare RUN_DIR      (the run against itself and against a changed copy)

Prints one line per check ('what: ok' or 'what: FAILED ...') and nothing that
varies between machines; exits 1 when a check failed.
"""
import math
import os
import re
import shutil
import subprocess
import sys

CONTRIB = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "contrib")
sys.path.insert(0, CONTRIB)
from granular_dg import outputs  # noqa: E402
from granular_dg.compare import compare_trees, stress_l1  # noqa: E402

failed = []


def check(what, ok, detail=""):
    print("%s: %s" % (what, "ok" if ok else "FAILED " + str(detail)))
    if not ok:
        failed.append(what)


def close(a, b, rtol=1e-12):
    return abs(a - b) <= rtol * max(abs(a), abs(b), 1e-300)


def same_times(a, b):
    return len(a) == len(b) and all(close(x, y) for x, y in zip(a, b))


def common(d):
    """summary.json against timeseries.csv: the last row is the final step."""
    s, t = outputs.summary(d), outputs.timeseries(d)
    check("timeseries.csv starts with time, step, dt", t.header[:3] == ["time", "step", "dt"], t.header[:3])
    check("its last step is summary.json's n_time_steps", t["step"][-1] == s["n_time_steps"],
          (t["step"][-1], s["n_time_steps"]))
    check("its last time is summary.json's final_time", close(t["time"][-1], s["final_time"]))
    check("its first row is t = 0, step 0", t["time"][0] == 0 and t["step"][0] == 0)
    check("status completed", s["status"] == "completed", s["status"])
    return s, t


def layered(d):
    s, t = common(d)
    profiles = outputs.profiles(d)
    check("one timeseries row per profile-NNNN.csv (4)", len(t) == len(profiles) == 4, (len(t), len(profiles)))
    check("profile times (# time = T) are the timeseries times", same_times([p.time for p in profiles], t["time"]))
    check("each profile: x, strain, ..., stress on [0, 300], 3 points per cell",
          all(p.header[:2] == ["x", "strain"] and "stress" in p and p["x"][0] == 0 and p["x"][-1] == 300
              and len(p) == 3 * s["n_cells"] for p in profiles), [len(p) for p in profiles])
    check("profile_at(240) is the last profile", outputs.profile_at(d, 240).path == profiles[-1].path)
    check("integral_strain of the last row is summary.json's",
          close(t["integral_strain"][-1], s["diagnostics"]["integral_strain"]))
    check("the strain integral is the wall displacement 12 at t = 80, 160, 240 (1e-8)",
          all(abs(v - 12) < 1e-8 for v in t["integral_strain"][1:]), t["integral_strain"])
    check("the readers imported no matplotlib", "matplotlib" not in sys.modules)


def network(d):
    s, t = common(d)
    check("the comment line of timeseries.csv is kept", t.comments[0].startswith("mass_balance_residual ="),
          t.comments)
    edges = outputs.edge_profiles(d)
    check("4 edges in the last snapshot", len(edges) == s["diagnostics"]["n_edges"] == 4, len(edges))
    check("one timeseries row per snapshot (7)",
          len(t) == len({p.split("-")[1] for p in os.listdir(d) if p.startswith("profile-")}) == 7, len(t))
    check("the edges' time is the final time", all(close(e.time, s["final_time"]) for e in edges))
    check("their vertex value is summary.json's vertex_value_final",
          all(close(e.value("vertex value"), s["diagnostics"]["vertex_value_final"]) for e in edges))
    check("two points per cell of 64 per edge, columns x, u, flux, exact",
          all(len(e) == 2 * s["n_cells"] // 4 and e.header == ["x", "u", "flux", "exact"] for e in edges))
    check("edge 2 is the loop", edges[1].comments[1].startswith("Edge 2: loop"), edges[1].comments)
    check("l1_error of the last row is summary.json's", close(t["l1_error"][-1], s["diagnostics"]["l1_error"]))
    check("the vertex ends at sqrt(5/3) (1e-10)", abs(t["vertex_value"][-1] - math.sqrt(5 / 3)) < 1e-10)


def hopper(d):
    s, t = common(d)
    stresses = [outputs.read_table(p) for p in outputs.files(d, "stress")]
    check("stress-NNNN.csv taus (# tau = T) are the timeseries times",
          same_times([x.value("tau") for x in stresses], t["time"]))
    check("and r/r0 = exp(-tau)", all(close(x.value("r/r0"), math.exp(-x.value("tau")), 1e-11) for x in stresses))
    steps = outputs.read_table(os.path.join(d, "hopper-steps.csv"))
    check("hopper-steps.csv: one row per step", len(steps) == steps["step"][-1] == s["n_time_steps"], len(steps))
    radial = outputs.read_table(os.path.join(d, "radial-field.csv"))
    check("radial-field.csv: 61 rows from the axis, sigma_0 of its comment",
          len(radial) == 61 and radial["theta"][0] == 0 and close(radial["sigma"][0], radial.value("sigma_0")))
    check("the field differs from itself by 0", stress_l1(stresses[1], stresses[1]) == 0)
    check("the marched field keeps the radial one (relative L1 < 1e-3)",
          all(stress_l1(x) < 1e-3 for x in stresses), [stress_l1(x) for x in stresses])


def convergence(d):
    c = outputs.convergence(d)
    degrees = c.groups("degree")
    check("degrees 0-4, cells 8-128 each", list(degrees) == [0, 1, 2, 3, 4] and
          all(list(g["cells"]) == [8, 16, 32, 64, 128] for g in degrees.values()))
    check("dofs = 2 components x (p + 1) x cells", all(c["dofs"] == 2 * (c["degree"] + 1) * c["cells"]))
    ok = True
    for g in degrees.values():
        e, h = g["l2_error"], g["h"]
        ok &= math.isnan(g["eoc"][0]) and all(close(g["eoc"][i], math.log(e[i - 1] / e[i]) / math.log(h[i - 1] / h[i]),
                                                    1e-9) for i in range(1, len(g)))
    check("eoc is log(e_coarse / e_fine) / log(h_coarse / h_fine), nan on the coarsest mesh", ok)


def benchmark(d):
    b = outputs.benchmark(d)
    check("one CPU time per repetition (2), 3 steps each",
          len(b["cpu_s_per_step"]) == b["repetitions"] == 2 and b["steps_per_repetition"] == 3)
    check("40 P2 cells of the strip: 240 DoFs, the line engine",
          b["n_dofs"] == 240 and b["case"]["engine"] == "line" and b["case"]["scene"] == "layered_strip")


def raises(what, read, expected, d):
    """read() must raise OutputError with the expected message (RUN_DIR for d)."""
    try:
        read()
    except outputs.OutputError as e:
        message = str(e).replace(d, "RUN_DIR")
        return check(what + ": OutputError naming the file", message == expected,
                     "'%s', expected '%s'" % (message, expected))
    check(what + ": OutputError naming the file", False, "none raised")


def write(path, text):
    os.makedirs(os.path.dirname(path) or ".", exist_ok=True)
    with open(path, "w") as f:
        f.write(text)


def malformed(d):
    with open(os.path.join(d, "timeseries.csv")) as f:
        lines = f.read().splitlines()
    fields = lines[2].split(",")
    write("short_row.csv", "\n".join(lines[:3] + [lines[3].rsplit(",", 1)[0]] + lines[4:]) + "\n")
    write("not_a_number.csv", "\n".join(lines[:2] + [",".join(fields[:1] + ["abc"] + fields[2:])]) + "\n")
    write("repeated_column.csv", "\n".join([lines[0].replace("step", "time")] + lines[1:]) + "\n")
    write("empty.csv", "# only a comment\n")
    write("truncated/summary.json", '{"scene": "layered_strip",\n "n_time_steps": 3,\n "final_time"')
    write("no_status/summary.json", '{"scene": "layered_strip", "n_time_steps": 3, "final_time": 1}')
    cases = [
        ("a row with a field missing", lambda: outputs.read_table("short_row.csv"),
         "short_row.csv, line 4: %d fields, the header has %d" % (len(fields) - 1, len(fields))),
        ("a field that is not a number", lambda: outputs.read_table("not_a_number.csv"),
         "not_a_number.csv, line 3: column 'step' is 'abc', not a number"),
        ("a repeated column name", lambda: outputs.read_table("repeated_column.csv"),
         "repeated_column.csv, line 1: empty or repeated column names in %s"
         % (["time"] * 2 + lines[0].split(",")[2:])),
        ("no header", lambda: outputs.read_table("empty.csv"), "empty.csv: no header line"),
        ("no such file", lambda: outputs.timeseries("nowhere"),
         "nowhere/timeseries.csv: cannot be read (No such file or directory)"),
        ("a column the file does not have", lambda: outputs.timeseries(d)["nope"],
         "RUN_DIR/timeseries.csv: no column 'nope' (it has %s)" % lines[0].replace(",", ", ")),
        ("a truncated summary.json", lambda: outputs.summary("truncated"),
         "truncated/summary.json, line 3: not JSON (Expecting ':' delimiter)"),
        ("a summary.json without status", lambda: outputs.summary("no_status"),
         "no_status/summary.json: no status"),
        ("an output time the run did not write", lambda: outputs.profile_at(d, 100),
         "RUN_DIR: no profile at t = 100 (it has t = 0, 80, 160, 240)")]
    for what, read, expected in cases:
        raises(what, read, expected, d)


def compare(d):
    lines, agree = compare_trees(d, d)
    check("the run against itself: bitwise", agree and lines[-1].endswith(": bitwise"), lines[-1:])
    shutil.rmtree("changed", ignore_errors=True)
    shutil.copytree(d, "changed")
    with open(os.path.join(d, "summary.json")) as f:
        summary = f.read()
    # as another process measures them (a resumed run allocates in another order)
    for key in ("wall_time_s", "peak_rss_bytes_per_dof", "solution_bytes_per_dof", "operator_bytes_per_dof"):
        summary = re.sub(r'("%s": )([0-9.]+)' % key, lambda m: m.group(1) + "2" + m.group(2), summary)
    with open("changed/summary.json", "w") as f:
        f.write(summary)
    lines, agree = compare_trees(d, "changed")
    check("another process's wall time and memory: bitwise", agree and lines[-1].endswith(": bitwise"),
          lines[-1:])
    with open(os.path.join(d, "timeseries.csv")) as f:
        text = f.read()
    with open("changed/timeseries.csv", "w") as f:
        f.write(text.replace("12.0000000001", "12.0000000002", 1))
    lines, agree = compare_trees(d, "changed")
    check("one strain integral changed in the 12th digit: DIFFERENT at 1e-13",
          not agree and lines[0].startswith("timeseries.csv: max rel diff 8.33e-12"), lines)
    lines, agree = compare_trees(d, "changed", 1e-10)
    check("and within 1e-10", agree and lines[-1].endswith(": within 1e-10"), lines[-1:])
    for name, value in (("wall_a", "1.5"), ("wall_b", "2.5")):  # physics named like a time is compared
        shutil.rmtree(name, ignore_errors=True)
        shutil.copytree(d, name)
        with open(name + "/summary.json", "w") as f:
            f.write(summary.replace("{", '{\n  "wall_work": %s,' % value, 1))
    lines, agree = compare_trees("wall_a", "wall_b")
    check("a changed wall_work: DIFFERENT", not agree and lines[0].startswith("summary.json: max rel diff 0.4"),
          lines)
    with open("wall_b/extra.csv", "w") as f:
        f.write("x\n1\n")
    lines, agree = compare_trees("wall_a", "wall_b")
    check("a file only AFTER has: DIFFERENT", not agree and "extra.csv: new after" in lines, lines)
    os.makedirs("empty_a", exist_ok=True)
    os.makedirs("empty_b", exist_ok=True)
    for args, message in (([d, "no_such_run"], "no_such_run is not a directory"),
                          (["empty_a", "empty_b"], "hold no output files"),
                          ([d, d, "--tolerance", "-1"], "--tolerance must be >= 0")):
        run = subprocess.run([sys.executable, os.path.join(CONTRIB, "compare_runs.py")] + args,
                             capture_output=True, text=True)
        check("compare_runs.py: " + message + ", exit 2", run.returncode == 2 and message in run.stderr,
              [run.returncode, run.stderr])


{"layered": layered, "network": network, "hopper": hopper, "convergence": convergence, "benchmark": benchmark,
 "malformed": malformed, "compare": compare}[sys.argv[1]](sys.argv[2])
sys.exit(1 if failed else 0)
