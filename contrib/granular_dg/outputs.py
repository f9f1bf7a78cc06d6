"""Readers of granular_dg's output files (doc/program.md, "Outputs"), and
the writers of the scripts' own CSV and markdown tables. A file that does not
read as the program writes it raises OutputError naming the file and line."""
import csv
import glob
import json
import os
import re
from pathlib import Path

import numpy as np

NUMBER = r"[-+]?(?:\d+\.?\d*|\.\d+)(?:[eE][-+]?\d+)?|[-+]?nan|[-+]?inf"
SUMMARY_KEYS = ("scene", "n_time_steps", "final_time", "status")
BENCHMARK_KEYS = ("case", "n_dofs", "steps_per_repetition", "repetitions", "cpu_s_per_step_median",
                  "step_dof_updates_per_s_per_core_median", "rk_dof_updates_per_s_per_core_median",
                  "step_dof_updates_per_s_wall_median", "load_before", "load_after")


class OutputError(ValueError):
    """A file of a run that is missing or does not read as the program writes it."""


class Table:
    """A CSV file: its '#' comment lines, header and columns (numpy arrays)."""

    def __init__(self, path, comments, header, columns):
        self.path, self.comments, self.header, self.columns = path, comments, header, columns

    def __getitem__(self, name):
        if name not in self.columns:
            raise OutputError("%s: no column '%s' (it has %s)" % (self.path, name, ", ".join(self.header)))
        return self.columns[name]

    def __contains__(self, name):
        return name in self.columns

    def __len__(self):
        return len(self.columns[self.header[0]])

    def rows(self):
        """The rows as dicts."""
        return [dict(zip(self.header, r)) for r in zip(*(self.columns[h] for h in self.header))]

    def groups(self, column):
        """{value: Table of the rows with it} for the values of a column, in order."""
        col = self[column]
        return {v: Table(self.path, self.comments, self.header, {h: c[col == v] for h, c in self.columns.items()})
                for v in dict.fromkeys(col)}

    def value(self, key):
        """The number after KEY ('KEY = 1.5' or 'KEY 1.5') in the comment lines."""
        m = re.search(re.escape(key) + r"\s*=?\s*(" + NUMBER + ")", "\n".join(self.comments))
        if not m:
            raise OutputError("%s: no '%s' in its comment lines %s" % (self.path, key, self.comments))
        return float(m.group(1))

    @property
    def time(self):
        """T of a '# time = T' comment line (profiles, slices)."""
        return self.value("time")


def read_table(path, numbers=True):
    """A CSV file as a Table; numbers=False keeps non-numeric columns as strings
    (the scripts' own tables; the program writes numbers only)."""
    try:
        lines = Path(path).read_text().splitlines()
    except OSError as e:
        raise OutputError("%s: cannot be read (%s)" % (path, e.strerror)) from None
    comments = [l[1:].strip() for l in lines if l.startswith("#")]
    body = [(n + 1, l) for n, l in enumerate(lines) if l.strip() and not l.startswith("#")]
    if not body:
        raise OutputError("%s: no header line" % path)
    rows = list(csv.reader(l for _, l in body))
    header = rows[0]
    if "" in header or len(set(header)) < len(header):
        raise OutputError("%s, line %d: empty or repeated column names in %s" % (path, body[0][0], header))
    for (n, _), r in zip(body[1:], rows[1:]):
        if len(r) != len(header):
            raise OutputError("%s, line %d: %d fields, the header has %d" % (path, n, len(r), len(header)))
    data = list(zip(*rows[1:])) or [()] * len(header)
    return Table(path, comments, header, {h: _column(path, h, c, body, numbers) for h, c in zip(header, data)})


def _column(path, name, values, body, numbers):
    """A column as floats (or strings, numbers=False); else an error naming
    the first field that is not a number."""
    try:
        return np.array(values, dtype=float)
    except ValueError:
        if not numbers:
            return np.array(values, dtype=str)
    for (n, _), v in zip(body[1:], values):
        if not re.fullmatch(NUMBER, v.strip(), re.I):
            raise OutputError("%s, line %d: column '%s' is '%s', not a number" % (path, n, name, v))
    raise OutputError("%s: column '%s' does not read as numbers" % (path, name))


def read_json(path, keys=()):
    """A JSON object with the given keys."""
    try:
        data = json.loads(Path(path).read_text())
    except OSError as e:
        raise OutputError("%s: cannot be read (%s)" % (path, e.strerror)) from None
    except json.JSONDecodeError as e:
        raise OutputError("%s, line %d: not JSON (%s)" % (path, e.lineno, e.msg)) from None
    missing = [k for k in keys if not isinstance(data, dict) or k not in data]
    if missing:
        raise OutputError("%s: no %s" % (path, ", ".join(missing)))
    return data


def _reader(name, keys=()):
    """The reader of a run's file NAME, given its directory: a Table, or the
    JSON object with the keys."""
    read = (lambda path: read_json(path, keys)) if name.endswith(".json") else read_table
    return lambda directory: read(os.path.join(directory, name))


# a run's summary.json, the benchmark.json of a --benchmark run, its timeseries.csv and convergence.csv, and
# the column scene's history.csv
summary, benchmark = _reader("summary.json", SUMMARY_KEYS), _reader("benchmark.json", BENCHMARK_KEYS)
timeseries, convergence, history = map(_reader, ("timeseries.csv", "convergence.csv", "history.csv"))


def files(directory, prefix):
    """A run's numbered files PREFIX-NNNN.csv, in output order."""
    pattern = re.compile(re.escape(prefix) + r"-\d+\.csv$")
    return sorted(p for p in glob.glob(os.path.join(directory, prefix + "-*.csv")) if pattern.search(p))


def latest(directory, prefix):
    """The last of a run's PREFIX-NNNN.csv files."""
    found = files(directory, prefix)
    if not found:
        raise OutputError("%s: no %s-NNNN.csv" % (directory, prefix))
    return found[-1]


def profiles(directory):
    """The 1D profiles profile-NNNN.csv of a run, in output order."""
    return [read_table(p) for p in files(directory, "profile")]


def _time_of(path):
    with open(path) as f:
        return Table(path, [f.readline()[1:]], [], {}).time


def profile_at(directory, time, rtol=1e-9):
    """The profile of a run at the given output time."""
    found = files(directory, "profile")
    for path in found:
        if abs(_time_of(path) - time) <= rtol * max(1, abs(time)):
            return read_table(path)
    raise OutputError("%s: no profile at t = %g (it has t = %s)"
                      % (directory, time, ", ".join("%g" % _time_of(p) for p in found)))


def slices(directory):
    """{time: Table} of the 2D strip's slice-NNNN.csv files."""
    return {t.time: t for t in map(read_table, files(directory, "slice"))}


def edge_profiles(directory):
    """[Table per edge] of the last snapshot of a network run."""
    found = glob.glob(os.path.join(directory, "profile-*-edge-*.csv"))
    key = lambda p: tuple(int(x) for x in re.search(r"profile-(\d+)-edge-(\d+)\.csv$", p).groups())
    if not found:
        raise OutputError("%s: no profile-NNNN-edge-K.csv" % directory)
    last = max(key(p)[0] for p in found)
    return [read_table(p) for p in sorted((p for p in found if key(p)[0] == last), key=key)]


def sgn_map(directory):
    """(t, z, sgn(v)) of the column's sgn-map.csv: times, cell centres, values."""
    t = read_table(os.path.join(directory, "sgn-map.csv"))
    try:
        z = np.array(t.header[1:], dtype=float)
    except ValueError:
        raise OutputError("%s: the header after 'time' is not cell centres" % t.path) from None
    return t["time"], z, np.array([t[h] for h in t.header[1:]]).T


def select(rows, **values):
    """The rows (dicts) with the given values."""
    return [r for r in rows if all(r[k] == v for k, v in values.items())]


def write_csv(path, rows):
    """Rows (dicts) as CSV, the columns in order of first appearance."""
    if not rows:
        return
    keys = list(dict.fromkeys(k for r in rows for k in r))
    with open(path, "w", newline="") as f:
        w = csv.DictWriter(f, fieldnames=keys)
        w.writeheader()
        w.writerows(rows)


def markdown(header, rows):
    """A markdown table of header cells and rows of cells (an empty cell: '| |')."""
    lines = ["| %s |" % " | ".join(header), "|" + "---|" * len(header)]
    lines += [re.sub(r"(?<=\|)  (?=\|)", " ", "| %s |" % " | ".join(str(c) for c in r)) for r in rows]
    return "\n".join(lines) + "\n"
