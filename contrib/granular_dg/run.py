"""Running granular_dg on a case file with --set overrides into an output
directory, reusing a run that is there already, and the runs of a study
(Runs)."""
import collections
import concurrent.futures
import json
import os
import re
import subprocess
import sys
import tempfile
import threading
import time
from pathlib import Path

from . import outputs, plot

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
# no snapshots: no output times (but the final one), no VTU
NO_SNAPSHOTS = ("Output/output times=", "Output/write vtu=false")
# a hopper run's stress-NNNN.csv at 2001 theta, no step series
HOPPER_SAMPLED = ["Hopper output/step series interval=0", "Hopper output/sample points=2001"]
ENV = dict(OMPI_ALLOW_RUN_AS_ROOT="1", OMPI_ALLOW_RUN_AS_ROOT_CONFIRM="1",
           OMPI_MCA_rmaps_base_oversubscribe="1", OMPI_MCA_ess_singleton_isolated="1")

Run = collections.namedtuple("Run", "code summary stderr directory wall_s cpu_s")


def load(fields=1):
    """The load average (1, 5, 15 min: the first `fields`) as text."""
    return " ".join(Path("/proc/loadavg").read_text().split()[:fields])


def command(build, prm, directory, sets=(), ranks=1, benchmark=False):
    """The command line of a run: PRM (relative to the repository unless
    absolute) into DIRECTORY, overwriting, no progress lines, then SETS."""
    cmd = [os.path.join(os.path.abspath(build), "granular_dg")] + ["--benchmark"] * benchmark
    cmd.append(os.path.join(ROOT, prm))
    for s in ("Output/directory=" + os.path.abspath(directory), "Output/overwrite=true",
              "Output/progress interval=0") + tuple(sets):
        cmd += ["--set", s]
    return (["mpirun", "-np", str(ranks)] if ranks > 1 else []) + cmd


def _summary(directory):
    """summary.json of a run as a dict, {} when there is none (bad input)."""
    try:
        return json.loads(Path(directory, "summary.json").read_text())
    except (OSError, ValueError):
        return {}


def finished(directory):
    """The Run recorded in a directory by run_case, or a completed run of
    the program's own; None otherwise."""
    s = _summary(directory)
    if not s:
        return None
    try:
        code, err = Path(directory, "exit.txt").read_text().split("\n", 1)
    except OSError:
        if s.get("status") != "completed":
            return None
        code, err = 0, ""
    nan = float("nan")
    return Run(int(code), s, err, directory, s.get("_run_wall_s", nan), s.get("_run_cpu_s", nan))


def run_case(build, prm, directory, sets=(), ranks=1, benchmark=False, reuse=False, check=False,
             log=False, keep=True):
    """Runs granular_dg (see command()); reuse: a finished run in DIRECTORY
    is taken as it is; check: exits with the run's error unless it exits 0;
    log: stdout and stderr go to DIRECTORY.log too; keep: records the exit
    code and the stderr in DIRECTORY/exit.txt, the wall and CPU time and the
    load at the start in summary.json (_run_wall_s, _run_cpu_s, _load)."""
    done = finished(directory) if reuse else None
    if done is None:
        os.makedirs(directory, exist_ok=True)
        l0, t0 = load(), time.time()
        code, err, cpu = execute(command(build, prm, directory, sets, ranks, benchmark),
                                 directory.rstrip("/") + ".log" if log else None)
        done = Run(code, _summary(directory), err, directory, time.time() - t0, cpu)
        if keep:
            done = done._replace(summary=dict(done.summary, _run_wall_s=done.wall_s, _run_cpu_s=cpu, _load=l0))
            Path(directory, "summary.json").write_text(json.dumps(done.summary))
            Path(directory, "exit.txt").write_text("%d\n%s" % (code, err))
    if check and done.code != 0:
        sys.exit("granular_dg %s into %s: exit %d: %s" % (prm, directory, done.code, done.stderr))
    return done


def execute(cmd, log=None):
    """(exit code, stderr as one line, CPU time) of a process; its stdout
    and stderr go to the file log if given."""
    with tempfile.TemporaryFile("w+") as out, tempfile.TemporaryFile("w+") as err:
        p = subprocess.Popen(cmd, stdout=out, stderr=err, text=True, env=dict(os.environ, **ENV))
        _, status, usage = os.wait4(p.pid, 0)  # this process's CPU time, also when runs go in threads
        p.returncode = os.waitstatus_to_exitcode(status)
        out.seek(0), err.seek(0)
        stdout, stderr = out.read(), err.read()
    if log:
        Path(log).write_text(stdout + stderr)
    return p.returncode, stderr.strip().replace("\n", " "), usage.ru_utime + usage.ru_stime


def cfl_limits():
    """{scheme: [the CFL limit of degree 0..4]}: the program's table (dg::cfl_limit in source/dg/parameters.cc)."""
    rows = re.findall(r"\{([\d.,\s]+)\},?\}?;?\s*// (\w+)", Path(ROOT, "source/dg/parameters.cc").read_text())
    return {name: [float(x) for x in values.split(",")] for values, name in rows}


def tag(value):
    """A number as part of a file name: 0.25 -> 0_25."""
    return ("%.6g" % value).replace(".", "_")


class Runs:
    """The runs of a study and what it writes: run(d, prm, sets) runs PRM
    into OUT/SUBDIR/d with the common SETS and then its own, reused when it
    finished there before (delete it to rerun, or reuse=False; check: exit
    with the error of a failed run); pmap runs --jobs at a time; csv and save write OUT/NAME.csv
    and the chart OUT/NAME.png (and in the other FORMATS)."""

    def __init__(self, build, out, quick=False, jobs=1, subdir="", sets=(), check=False, formats=()):
        self.build, self.out, self.quick, self.jobs = os.path.abspath(build), os.path.abspath(out), quick, jobs
        self.subdir, self.sets, self.check, self.formats = subdir, tuple(sets), check, formats
        self.count, self.lock = {"executed": 0, "reused": 0}, threading.Lock()
        os.makedirs(self.out, exist_ok=True)

    def run(self, d, prm, sets=(), reuse=True, **kwargs):
        directory = os.path.join(self.out, self.subdir, d)
        with self.lock:
            self.count["reused" if reuse and finished(directory) else "executed"] += 1
        return run_case(self.build, prm, directory, self.sets + tuple(sets), reuse=reuse, check=self.check, **kwargs)

    def pmap(self, f, items):
        """f(*item) for the items (tuples), --jobs at a time (threads), the results in order."""
        with concurrent.futures.ThreadPoolExecutor(self.jobs) as pool:
            return list(pool.map(lambda item: f(*item), items))

    def pick(self, table, key):
        """table[key], or table["quick_" + key] in a quick study."""
        return table["quick_" + key] if self.quick else table[key]

    def csv(self, name, rows):
        outputs.write_csv(os.path.join(self.out, name + ".csv"), rows)

    def save(self, fig, name, **kwargs):
        plot.save(fig, os.path.join(self.out, name + ".png"), *self.formats, **kwargs)
