#!/usr/bin/python3
"""Compare two trees of granular_dg outputs, file by file (before/after a refactor).

    /usr/bin/python3 contrib/compare_runs.py BEFORE_DIR AFTER_DIR [--tolerance 1e-13]

The two must hold the same CSV, JSON, VTU and prm files, with the same columns/keys and
numbers equal to within the tolerance (what measures the process is skipped: wall and
CPU times, the rates derived from them, the peak RSS and the memory block of
summary.json, the step a run resumed from): CSV
numbers relative to the largest magnitude of their column, JSON numbers relative to
themselves. VTU/PVD/PVTU files are compared byte for byte, parameters.prm but for the
output directory. Two trees without any such file are an error (exit 2). Prints one line per file that differs, the largest relative
difference, and a verdict: 'bitwise' (every compared file identical to the letter,
those aside), 'within TOL', or 'DIFFERENT' (exit code 1).
"""
import sys

from granular_dg import arguments, directory
from granular_dg.compare import compare_trees
from granular_dg.outputs import OutputError

a = arguments(__doc__, [("before", dict(type=directory)), ("after", dict(type=directory)),
                        ("--tolerance", dict(type=float, default=1e-13))])
if not a.tolerance >= 0:
    print("compare_runs.py: error: --tolerance must be >= 0, not %g" % a.tolerance, file=sys.stderr)
    sys.exit(2)
try:
    lines, agree = compare_trees(a.before, a.after, a.tolerance)
except OutputError as e:
    print("compare_runs.py: error: %s" % e, file=sys.stderr)
    sys.exit(2)
print("\n".join(lines))
sys.exit(0 if agree else 1)
