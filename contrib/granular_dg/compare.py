"""Comparing runs: two output trees file by file (before/after a change of
the code), and the differences between two runs' fields that the studies
measure (hopper stresses over theta, the 2D strip's slices, a profile's
value at a point)."""
import json
import math
import os
import re
from pathlib import Path

import numpy as np

from .outputs import NUMBER, OutputError, read_table

# keys and columns, by whole name, that measure the process: times (NAME_s), rates, peak
# memory and the memory block (allocations, which a resumed run makes in another order),
# the step a run resumed from (physics such as wall_work stays compared)
TIMING = re.compile(r"^(\w*_s|dof_updates\w*|peak_rss\w*|memory|\w*_bytes_per_dof|resumed_from_step)$")
SKIPPED = re.compile(r"(^|/)checkpoints/|\.tmp$|\.log$|(^|/)(times\.txt|benchmark\.json)$")


def rel(a, b):
    """The difference of two numbers relative to the larger (0 for two NaN)."""
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    scale = max(abs(a), abs(b))
    return abs(a - b) / scale if scale > 0 else abs(a - b)


def json_difference(x, y, path, diffs):
    """The largest relative difference of two JSON values (timing keys skipped)."""
    if isinstance(x, dict) and isinstance(y, dict):
        diffs += ["%s/%s: new after" % (path, k) for k in y if k not in x and not TIMING.search(k)]
        missing = [k for k in x if k not in y and not TIMING.search(k)]
        diffs += ["%s/%s: missing after" % (path, k) for k in missing]
        return max([math.inf if missing else 0.0] + [json_difference(x[k], y[k], "%s/%s" % (path, k), diffs)
                                                      for k in x if k in y and not TIMING.search(k)])
    if isinstance(x, list) and isinstance(y, list) and len(x) == len(y):
        return max([json_difference(a, b, path, diffs) for a, b in zip(x, y)] + [0.0])
    numbers = [isinstance(v, (int, float)) or (isinstance(v, str) and re.fullmatch(NUMBER, v)) for v in (x, y)]
    if all(numbers):
        return rel(float(x), float(y))
    if x != y:
        diffs.append("%s: %r != %r" % (path, x, y))
        return math.inf
    return 0.0


def csv_difference(a, b, diffs):
    """The largest difference of two CSV files, each number relative to the
    largest magnitude of its column in either file (timing columns skipped)."""
    ta, tb = read_table(a, numbers=False), read_table(b, numbers=False)
    if ta.header != tb.header or len(ta) != len(tb) or len(ta.comments) != len(tb.comments):
        diffs.append("header, rows or comment lines differ")
        return math.inf
    worst = 0.0
    for ca, cb in zip(ta.comments, tb.comments):
        if re.sub(NUMBER, "", ca) != re.sub(NUMBER, "", cb):
            diffs.append("comment differs: %r / %r" % (ca, cb))
            return math.inf
        worst = max([worst] + [rel(float(p), float(q)) for p, q in zip(re.findall(NUMBER, ca), re.findall(NUMBER, cb))])
    for h in (h for h in ta.header if not TIMING.search(h)):
        x, y = ta[h], tb[h]
        if x.dtype.kind != "f" or y.dtype.kind != "f" or (np.isnan(x) != np.isnan(y)).any():
            if list(x.astype(str)) != list(y.astype(str)):
                diffs.append("column %s differs" % h)
                return math.inf
            continue
        scale = max(np.nanmax(np.abs(x), initial=0), np.nanmax(np.abs(y), initial=0))
        worst = max(worst, np.nanmax(np.abs(x - y), initial=0) / (scale if scale > 0 else 1))
    return worst


def file_difference(a, b, diffs):
    """(largest difference, identical to the letter but for timings) of two files."""
    if a.endswith(".json"):
        ta, tb = Path(a).read_text(), Path(b).read_text()
        untimed = [[l for l in t.splitlines() if not TIMING.search(l.split(":")[0].strip().strip('"'))]
                   for t in (ta, tb)]
        return json_difference(json.loads(ta), json.loads(tb), "", diffs), untimed[0] == untimed[1]
    if a.endswith(".csv"):
        worst = csv_difference(a, b, diffs)
        return worst, worst == 0
    ta, tb = Path(a).read_bytes(), Path(b).read_bytes()
    if a.endswith(".prm"):  # but for the output directory
        ta, tb = (re.sub(rb"\n *set directory *=[^\n]*", b"", t) for t in (ta, tb))
    if ta == tb:
        return 0.0, True
    diffs.append("VTU bytes differ (Float32 output; numbers compared in CSV/JSON)" if a.endswith(".vtu")
                 else "bytes differ")
    return (math.inf if a.endswith(".pvd") else 0.0), False


def compare_trees(before, after, tol=1e-13):
    """Every CSV, JSON, VTU/PVTU/PVD and prm file of BEFORE and AFTER compared: the lines
    to print and whether they agree (within tol)."""
    def files(top):
        return {os.path.relpath(os.path.join(root, name), top) for root, _, names in os.walk(top) for name in names
                if name.endswith((".csv", ".json", ".vtu", ".pvtu", ".pvd", ".prm"))}
    lines, bad, worst_all, n, bitwise = [], [], 0.0, 0, True
    old, new = files(before), files(after)
    if not old and not new:
        raise OutputError("%s and %s hold no output files (CSV, JSON, VTU, PVD, prm) to compare"
                          % (before, after))
    for r in sorted(r for r in old | new if not SKIPPED.search(r)):
        if r not in new or r not in old:
            bad.append("%s: %s after" % (r, "missing" if r in old else "new"))
            continue
        diffs = []
        worst, same = file_difference(os.path.join(before, r), os.path.join(after, r), diffs)
        n, worst_all, bitwise = n + 1, max(worst_all, worst), bitwise and same
        if worst > tol or (diffs and not r.endswith(".vtu")):
            bad.append("; ".join(["%s: max rel diff %.3g" % (r, worst)] + diffs[:3]))
        elif diffs:
            lines.append("note %s: %s" % (r, "; ".join(diffs[:2])))
    verdict = "DIFFERENT" if bad else "bitwise" if bitwise else "within %g" % tol
    return lines + bad + ["%d files compared, max relative difference %.3g: %s" % (n, worst_all, verdict)], not bad


def stress_l1(stress, ref=None):
    """Relative L1 difference over theta of a hopper stress-NNNN.csv's
    (T_rr, T_rtheta)/r from another's (ref), or from the radial field it
    carries (ref None)."""
    rr, rt = (ref["T_rr_over_r"], ref["T_rtheta_over_r"]) if ref is not None else \
        (stress["radial_T_rr_over_r"], stress["radial_T_rtheta_over_r"])
    num = np.abs(stress["T_rr_over_r"] - rr) + np.abs(stress["T_rtheta_over_r"] - rt)
    return float(np.trapz(num, stress["theta"]) / np.trapz(np.abs(rr) + np.abs(rt), stress["theta"]))


def value_at(table, column, x):
    """A profile's value at x: the mean of both sides at a face, else interpolated."""
    at = np.isclose(table["x"], x, atol=1e-9)
    return float(np.mean(table[column][at]) if at.any() else np.interp(x, table["x"], table[column]))


def slice_l1(run, ref, below):
    """(L1 over x < below, L1 over the slice, max over x < below) of run - ref,
    each (x, values) linear between its samples and discontinuous where a
    sample point repeats (a cell's end): two-point Gauss on every interval of
    the union of both runs' sample points, so no point sits on a jump and a
    run against itself gives 0."""
    edges = np.unique(np.concatenate([run[0], ref[0]]))
    edges = edges[edges <= run[0].max()]
    mid, half = 0.5 * (edges[1:] + edges[:-1]), 0.5 * np.diff(edges)
    x = np.concatenate([mid - half / np.sqrt(3.0), mid + half / np.sqrt(3.0)])
    w = np.concatenate([half, half])
    e = np.abs(np.interp(x, *run) - np.interp(x, *ref))
    return np.sum((e * w)[x < below]), np.sum(e * w), e[x < below].max()


def total_variation(x, values, below):
    """The total variation of values over x < below (the samples, jumps
    between cells included): ringing raises it."""
    return np.sum(np.abs(np.diff(values[x < below])))
