#!/usr/bin/python3
"""An independent implementation of the finite volume scheme (4.1) of Musch,
Fjordholm & Risebro (scalar conservation laws on networks, Networks and
Heterogeneous Media 17, 2022) for the five examples of their Section 7, in
plain numpy: the reference the C++ degree-0 results are tested against
(tests/network/example_7_*_table.output are written by this script).

Scheme: cells of width dx = 2^-l on every edge of length 1, a vertex cell of
width dx_0 = N dx / 2 (N edge ends; the roundabout of 7.1 counts twice),
upwind (= Engquist-Osher) fluxes, forward Euler with dt = 0.5 dx / max|f'|
over the current state (edges and vertex), the last step landing on T,
cell averages of the initial data, the vertex starting at c_0. Error: the
true L1 norm over all edges and the vertex cell at T.

  /usr/bin/python3 tests/network/fv_reference.py [--levels 3-8] [--examples 7.1,7.3] [--csv DIR]
"""
import math
import os
import types

import numpy as np

import argparse

SQRT2 = math.sqrt(2.0)


# the fluxes as (f, f', Engquist-Osher numerical flux F(u, v))
def burgers():
    f = lambda u: 0.5 * u * u
    return f, lambda u: u, lambda u, v: f(np.maximum(u, 0.0)) + f(np.minimum(v, 0.0))


def linear(a=1.0):
    return lambda u: a * u, lambda u: a + 0.0 * u, lambda u, v: max(a, 0.0) * u + min(a, 0.0) * v


def traffic(alpha):
    f, m = lambda u: 4.0 * u * (1.0 - u / alpha), 0.5 * alpha
    return f, lambda u: 4.0 - 8.0 * u / alpha, lambda u, v: f(np.minimum(u, m)) + f(np.maximum(v, m)) - alpha


def const(c):
    return lambda x: c + 0 * x


def example(name, T, c0, edges, exact, breaks, vertex, init_breaks=lambda k: []):
    """edges: list of (kind, flux, initial(x), far_end) with kind in/out/loop,
    far_end None (zero gradient) or a Dirichlet value; exact(k, x, t) vector
    in x; breaks(k, t) and init_breaks(k): its discontinuities on edge k;
    vertex(t); the vertex starts at c0; T the final time."""
    return types.SimpleNamespace(name=name, T=T, c0=c0, edges=edges, exact=exact, breaks=breaks, vertex=vertex,
                                 init_breaks=init_breaks)


def example_7_1():
    s1 = (2 + SQRT2) / 2
    t1 = 0.5 / s1
    c1 = math.sqrt(5.0 / 3.0)
    s2 = (1 + c1) / 2
    b = burgers()
    return example('7.1', 0.7, 1.0,
                   [('in', b, lambda x: np.where(x < 0.5, 2.0, SQRT2), 2.0), ('loop', b, const(1.0), None),
                    ('out', b, const(1.0), None), ('out', b, const(1.0), None)],
                   lambda k, x, t: (np.where(x < 0.5 + s1 * t, 2.0, SQRT2) if k == 0 else
                                    np.where((t > t1) & (x < s2 * (t - t1)), c1, 1.0)),
                   lambda k, t: [0.5 + s1 * t] if k == 0 else ([s2 * (t - t1)] if t > t1 else []),
                   lambda t: 1.0 if t < t1 else c1, lambda k: [0.5] if k == 0 else [])


def example_7_2():
    c0 = (3 - math.sqrt(7.0)) / 2

    def exact(k, x, t):
        if k < 2:
            return 0.5 + 0 * x
        if k == 2:
            fan = 1 - x / (4 * t) if t > 0 else 0 * x
            return np.where(x < (4 - 4 * c0) * t, c0, np.where(x < 4 * t, fan, 0.0))
        if k == 3:
            return c0 + 0 * x
        return np.where(x < (3 - c0) * t, c0, 1.0)
    return example('7.2', 0.2, c0,
                   [('in', traffic(1.0), const(0.5), None), ('in', traffic(1.0), const(0.5), None),
                    ('out', traffic(2.0), const(0), None), ('out', traffic(4.0), const(c0), None),
                    ('out', traffic(4.0), const(1), None)],
                   exact, lambda k, t: ([(4 - 4 * c0) * t, 4 * t] if k == 2 else [(3 - c0) * t] if k == 4 else []),
                   lambda t: c0)


def example_7_3():
    lin = linear(1.0)
    return example('7.3', 0.5, 2.0 / 3.0,
                   [('in', lin, lambda x: np.where(x < 0.8, 2.0, 1.0), 2.0), ('in', lin, const(1), 1.0)] +
                   [('out', lin, const(2.0 / 3.0), 2.0 / 3.0)] * 3,
                   lambda k, x, t: (np.where(x < 0.8 + t, 2.0, 1.0) if k == 0 else
                                    1 + 0 * x if k == 1 else np.where(x < t - 0.2, 1.0, 2.0 / 3.0)),
                   lambda k, t: [0.8 + t] if k == 0 else [] if k == 1 else [t - 0.2],
                   lambda t: 2.0 / 3.0 if t < 0.2 else 1.0, lambda k: [0.8] if k == 0 else [])


def example_7_4():
    c0 = math.sqrt(2.0 / 3.0)

    def exact(k, x, t):
        if k < 2:
            return 1 + 0 * x
        if k == 2:
            return np.where(x < 0.5 * c0 * t, c0, 0.0)
        if k == 3:
            return c0 + 0 * x
        fan = x / t if t > 0 else 0 * x
        return np.where(x < c0 * t, c0, np.where(x < 2 * t, fan, 2.0))
    b = burgers()
    return example('7.4', 0.3, c0,
                   [('in', b, const(1), None), ('in', b, const(1), None), ('out', b, const(0), None),
                    ('out', b, const(c0), None), ('out', b, const(2), None)],
                   exact, lambda k, t: ([0.5 * c0 * t] if k == 2 else [c0 * t, 2 * t] if k == 4 else []),
                   lambda t: c0)


def example_7_5():
    c0, c1 = math.sqrt(2.0 / 3.0), math.sqrt(5.0 / 3.0)
    t1, s = 0.2 / 1.5, 0.5 * (c0 + c1)
    b = burgers()
    return example('7.5', 0.5, c0,
                   [('in', b, lambda x: np.where(x < 0.8, 2.0, 1.0), 2.0), ('in', b, const(1), 1.0)] +
                   [('out', b, const(c0), c0)] * 3,
                   lambda k, x, t: (np.where(x < 0.8 + 1.5 * t, 2.0, 1.0) if k == 0 else
                                    1 + 0 * x if k == 1 else np.where((t > t1) & (x < s * (t - t1)), c1, c0)),
                   lambda k, t: ([0.8 + 1.5 * t] if k == 0 else [] if k == 1 else [s * (t - t1)] if t > t1 else []),
                   lambda t: c0 if t < t1 else c1, lambda k: [0.8] if k == 0 else [])


EXAMPLES = {'7.1': example_7_1, '7.2': example_7_2, '7.3': example_7_3, '7.4': example_7_4,
            '7.5': example_7_5}
GAUSS_X, GAUSS_W = np.polynomial.legendre.leggauss(8)


def cell_integrals(g, edges_x, breaks):
    """int over each cell [edges_x[i], edges_x[i+1]] of g, split at breaks."""
    out = np.zeros(len(edges_x) - 1)
    for i in range(len(edges_x) - 1):
        a, b = edges_x[i], edges_x[i + 1]
        pts = [a] + sorted(p for p in breaks if a < p < b) + [b]
        for lo, hi in zip(pts[:-1], pts[1:]):
            x = 0.5 * (lo + hi) + 0.5 * (hi - lo) * GAUSS_X
            out[i] += 0.5 * (hi - lo) * np.dot(GAUSS_W, g(x))
    return out


def solve(ex, level):
    n = 2 ** level
    dx = 1.0 / n
    faces = np.linspace(0.0, 1.0, n + 1)
    # the edges' ends at the vertex: one per in or out edge, two of a loop
    ends = [k for k, e in enumerate(ex.edges) for _ in range(2 if e[0] == 'loop' else 1)]
    dx0 = len(ends) * dx / 2
    u = [cell_integrals(init, faces, ex.init_breaks(k)) / dx
         for k, (_, _, init, _) in enumerate(ex.edges)]
    u0 = ex.c0
    t, T, steps = 0.0, ex.T, 0
    while t < T * (1 - 1e-14):
        lam = max(max(np.max(np.abs(fl[1](uk))) for (_, fl, _, _), uk in zip(ex.edges, u)),
                  max(abs(ex.edges[k][1][1](u0)) for k in ends))
        dt = 0.5 * dx / lam
        if t + dt >= T * (1 - 1e-14):
            dt = T - t
        new = []
        vertex_net = 0.0  # sum_out F - sum_in F
        for k, (kind, fl, _, far) in enumerate(ex.edges):
            uk = u[k]
            # ghost values left of cell 0 and right of cell n-1: the vertex's, or the far end's data
            far_end = [far if far is not None else uk[0 if kind == 'in' else -1]]
            left, right = far_end if kind == 'in' else [u0], far_end if kind == 'out' else [u0]
            ext = np.concatenate((left, uk, right))
            flux = fl[2](ext[:-1], ext[1:])  # n + 1 face fluxes
            new.append(uk - dt / dx * (flux[1:] - flux[:-1]))
            if kind != 'out':
                vertex_net -= flux[-1]
            if kind != 'in':
                vertex_net += flux[0]
        u0 = u0 - dt / dx0 * vertex_net
        u = new
        t += dt
        steps += 1
    err_edges = sum(np.sum(cell_integrals(lambda x, k=k: np.abs(u[k][np.minimum(
        (x / dx).astype(int), n - 1)] - ex.exact(k, x, T)), faces, ex.breaks(k, T)))
        for k in range(len(ex.edges)))
    err_vertex = dx0 * abs(u0 - ex.vertex(T))
    return {'level': level, 'steps': steps, 'l1': err_edges + err_vertex, 'l1_vertex': err_vertex, 'u0': u0}


def main():
    parser = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawDescriptionHelpFormatter)
    parser.add_argument('--levels', default='3-8')
    parser.add_argument('--examples', default='7.1,7.2,7.3,7.4,7.5')
    parser.add_argument('--csv', help='write DIR/example_7_X_table.output (the test references)')
    a = parser.parse_args()
    lo, hi = (int(v) for v in a.levels.split('-'))
    if a.csv:
        os.makedirs(a.csv, exist_ok=True)
    for name in a.examples.split(','):
        ex = EXAMPLES[name]()
        rows, prev = [], None
        for level in range(lo, hi + 1):
            r = solve(ex, level)
            r['eoc'] = math.log2(prev / r['l1']) if prev else float('nan')
            prev = r['l1']
            rows.append(r)
            print('%s level %2d steps %5d  L1 %.12g  EOC %5.2f  vertex %.3g' %
                  (ex.name, level, r['steps'], r['l1'], r['eoc'], r['l1_vertex']))
        if a.csv:
            path = os.path.join(a.csv, 'example_%s_table.output' % name.replace('.', '_'))
            with open(path, 'w') as f:
                f.write('level,time_steps,l1_error,eoc,l1_error_vertex\n')
                for r in rows:
                    f.write('%d,%d,%.12g,%s,%.12g\n' % (
                        r['level'], r['steps'], r['l1'],
                        'nan' if math.isnan(r['eoc']) else '%.12g' % r['eoc'], r['l1_vertex']))


if __name__ == '__main__':
    main()
