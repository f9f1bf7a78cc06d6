#!/usr/bin/env python3
"""Compare two trees of granular_dg outputs, file by file (before/after a refactor).

    /usr/bin/python3 contrib/compare_runs.py BEFORE_DIR AFTER_DIR [--tolerance 1e-13]

Every CSV and JSON file of BEFORE must exist in AFTER with the same columns/keys and
numbers equal to within the tolerance (timing fields are skipped: wall and CPU times
and the rates derived from them): CSV numbers relative to the largest magnitude of
their column (values near zero are judged on the column's scale, as
tests/common/csv_compare.py does), JSON numbers relative to themselves.
VTU/PVD/PVTU files are compared byte for byte, parameters.prm but for the output
directory. Prints one line per file that differs, the largest relative difference, and a
verdict: 'bitwise' (every compared file identical to the letter, timings aside),
'within TOL', or 'DIFFERENT' (exit code 1).
"""
import json
import math
import os
import re
import sys

TIMING = re.compile(r"(wall|cpu|time_loop|dof_updates|seconds|_s$|elapsed|load)", re.I)
NUMBER = re.compile(r"^[-+]?(\d+\.?\d*|\.\d+)([eE][-+]?\d+)?$|^[-+]?(nan|inf)$")


def rel(a, b):
    if a == b or (math.isnan(a) and math.isnan(b)):
        return 0.0
    scale = max(abs(a), abs(b))
    return abs(a - b) / scale if scale > 0 else abs(a - b)


def compare_values(x, y, path, diffs):
    """Recursively compare JSON values; returns max relative difference."""
    if isinstance(x, dict):
        if not isinstance(y, dict):
            diffs.append(f"{path}: type differs")
            return math.inf
        worst = 0.0
        for k in x:
            if TIMING.search(k):
                continue
            if k not in y:
                diffs.append(f"{path}/{k}: missing after")
                worst = math.inf
                continue
            worst = max(worst, compare_values(x[k], y[k], f"{path}/{k}", diffs))
        for k in y:
            if k not in x and not TIMING.search(k):
                diffs.append(f"{path}/{k}: new after")
        return worst
    if isinstance(x, list):
        if not isinstance(y, list) or len(x) != len(y):
            diffs.append(f"{path}: list length differs")
            return math.inf
        return max([compare_values(a, b, path, diffs) for a, b in zip(x, y)] + [0.0])
    if isinstance(x, (int, float)) and isinstance(y, (int, float)):
        return rel(float(x), float(y))
    if x != y:
        if isinstance(x, str) and isinstance(y, str) and NUMBER.match(x) and NUMBER.match(y):
            return rel(float(x), float(y))
        diffs.append(f"{path}: '{x}' != '{y}'")
        return math.inf
    return 0.0


def compare_csv(a, b, diffs):
    la = open(a).read().splitlines()
    lb = open(b).read().splitlines()
    if len(la) != len(lb):
        diffs.append(f"{len(la)} lines before, {len(lb)} after")
        return math.inf
    header, worst, skip = None, 0.0, set()
    # the scale of every column: its largest magnitude in either file
    scale = {}
    for line in la + lb:
        if line.startswith("#"):
            continue
        for i, v in enumerate(line.split(",")):
            try:
                scale[i] = max(scale.get(i, 0.0), abs(float(v)))
            except ValueError:
                pass
    for ra, rb in zip(la, lb):
        if ra.startswith("#") or rb.startswith("#"):
            if ra != rb:
                fa, fb = re.findall(r"[-+.\deE]+", ra), re.findall(r"[-+.\deE]+", rb)
                try:
                    worst = max([worst] + [rel(float(p), float(q)) for p, q in zip(fa, fb)])
                except ValueError:
                    diffs.append(f"comment differs: {ra!r} / {rb!r}")
                    worst = math.inf
            continue
        ca, cb = ra.split(","), rb.split(",")
        if header is None:
            header = ca
            if ca != cb:
                diffs.append(f"header differs: {ra} / {rb}")
                return math.inf
            skip = {i for i, h in enumerate(ca) if TIMING.search(h)}
            continue
        if len(ca) != len(cb):
            diffs.append("row length differs")
            return math.inf
        for i, (p, q) in enumerate(zip(ca, cb)):
            if i in skip or p == q:
                continue
            try:
                x, y = float(p), float(q)
                d = rel(x, y) if not scale.get(i) else abs(x - y) / scale[i]
                if math.isnan(x) != math.isnan(y):
                    d = math.inf
                worst = max(worst, d if not (math.isnan(x) and math.isnan(y)) else 0.0)
            except ValueError:
                diffs.append(f"'{p}' != '{q}'")
                worst = math.inf
    return worst


def main():
    args = sys.argv[1:]
    tol = 1e-13
    if "--tolerance" in args:
        i = args.index("--tolerance")
        tol = float(args[i + 1])
        del args[i:i + 2]
    before, after = args
    worst_all, n_files, bitwise, bad = 0.0, 0, True, []
    for root, _, files in os.walk(before):
        for f in sorted(files):
            a = os.path.join(root, f)
            r = os.path.relpath(a, before)
            if "checkpoints" in r.split(os.sep) or f.endswith(".tmp") or f.endswith(".log") or f == "times.txt":
                continue
            if f in ("benchmark.json",):
                continue
            b = os.path.join(after, r)
            if not os.path.exists(b):
                bad.append(f"{r}: missing after")
                continue
            n_files += 1
            diffs = []
            if f.endswith(".json"):
                worst = compare_values(json.load(open(a)), json.load(open(b)), "", diffs)
                if open(a).read() != open(b).read():
                    # identical but for timing fields?
                    ta = [l for l in open(a) if not TIMING.search(l.split(":")[0])]
                    tb = [l for l in open(b) if not TIMING.search(l.split(":")[0])]
                    bitwise &= ta == tb
            elif f.endswith(".csv"):
                worst = compare_csv(a, b, diffs)
                if worst > 0:
                    bitwise = False
            elif f.endswith((".vtu", ".pvtu", ".pvd", ".prm")):
                ta, tb = open(a, "rb").read(), open(b, "rb").read()
                if f.endswith(".prm"):
                    drop = re.compile(rb"\n *set directory *=[^\n]*")
                    ta, tb = drop.sub(b"", ta), drop.sub(b"", tb)
                same = ta == tb
                worst = 0.0 if same else (math.inf if f.endswith(".pvd") else 0.0)
                if not same:
                    bitwise = False
                    if not f.endswith(".vtu"):
                        diffs.append("bytes differ")
                    else:
                        diffs.append("VTU bytes differ (Float32 output; numbers compared in CSV/JSON)")
            else:
                continue
            worst_all = max(worst_all, worst)
            if worst > tol or (diffs and worst > 0) or (diffs and not f.endswith(".vtu")):
                bad.append(f"{r}: max rel diff {worst:.3g}; " + "; ".join(diffs[:3]))
            elif diffs:
                print(f"note {r}: " + "; ".join(diffs[:2]))
    for line in bad:
        print(line)
    verdict = "bitwise" if bitwise and not bad else ("within %g" % tol if not bad else "DIFFERENT")
    print(f"{n_files} files compared, max relative difference {worst_all:.3g}: {verdict}")
    return 1 if bad else 0


if __name__ == "__main__":
    sys.exit(main())
