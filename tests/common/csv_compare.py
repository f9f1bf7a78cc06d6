"""Comparing the CSV files of two runs that should agree to round-off (other
MPI rank counts, a resumed run): used by tests/mpi and tests/checkpoint.

difference(a, b) returns, for two CSV files of the same shape,

    worst = max_ij (|a_ij - b_ij| - u_ij)+ / s_j,   raw = max_ij |a_ij - b_ij| / s_j

and the column of `worst`, with s_j the scale of column j: max_i |a_ij| over
the column and its vector partners (columns named alike but for a trailing
_x/_y: a momentum component that vanishes by symmetry is measured against
the vector's size, not its own round-off), and u_ij one unit in the last
(12th) significant digit the files print of a_ij and b_ij: differences below
the print resolution are not differences. None when the shapes differ.
"""
import csv
import math


def read(path):
    with open(path) as f:
        rows = list(csv.reader(l for l in f if not l.startswith('#')))
    return rows[0], [[float(x) for x in r] for r in rows[1:]]


def partners(header, j):
    """The columns scaled together with column j (itself, or its _x/_y)."""
    col = header[j]
    found = [k for k, c in enumerate(header)
             if c[-2:] in ('_x', '_y') and col[-2:] in ('_x', '_y') and c[:-2] == col[:-2]]
    return found or [j]


def print_unit(x):
    """One unit of the 12th significant digit of x (format %.12g)."""
    return 10 ** (math.floor(math.log10(abs(x))) - 11) if x else 0.


def difference(path_a, path_b):
    h0, a = read(path_a)
    h1, b = read(path_b)
    if h0 != h1 or len(a) != len(b) or any(len(r) != len(q) for r, q in zip(a, b)):
        return None
    worst, where, raw = 0., '-', 0.
    for j, col in enumerate(h0):
        scale = max(abs(r[k]) for r in a for k in partners(h0, j)) if a else 0.
        scale = scale or 1.
        for r, q in zip(a, b):
            diff = abs(r[j] - q[j])
            if diff != diff:
                return math.inf, math.inf, col
            raw = max(raw, diff / scale)
            d = max(diff - max(print_unit(r[j]), print_unit(q[j])), 0.) / scale
            if d > worst:
                worst, where = d, col
    return worst, raw, where
