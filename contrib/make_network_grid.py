#!/usr/bin/python3
"""Writes a city grid for the network scene as CSV files (Network/graph file,
Network/vertex file): n x n junctions one unit apart, one-way streets between
neighbouring junctions (rows alternate east/west, columns north/south, as in a
Manhattan grid), and at the two ends of every street a road from a free end
into the grid (inflow data) and one out of it (outflow; 70 % of the street's
capacity, so that the rush hour jams back from the exits). Traffic flux
f = alpha f0(u/alpha), f0(u) = 4u(1 - u); the middle row and column are
avenues with twice the capacity (alpha = 2). The inflow densities rise to a
rush-hour peak at t = 2 and fall again; the grid starts at density 0.1.

Edges: 2 n (n - 1) streets + 4 n boundary roads (n = 6: 84 edges, 36
junctions; n = 71: 10224 edges, 5041 junctions).

usage: make_network_grid.py N EDGES.csv VERTICES.csv
"""
import sys


def write_grid(n, edge_file, vertex_file):
    """The grid's two files; returns the number of edges."""
    vid = lambda i, j: 1 + i + n * j  # the junction in column i, row j (1-based ids)
    edges = []  # (from, to, alpha, initial density, far end, far-end data)
    for rows in (True, False):  # the rows, even ones eastbound; the columns, even ones northbound
        for k in range(n):
            order = range(n) if k % 2 == 0 else range(n - 1, -1, -1)
            street = [vid(m, k) if rows else vid(k, m) for m in order]
            al = 2 if k == n // 2 else 1
            # inflow: density alpha (0.12 + 0.3 exp(-((t - t0)/0.8)^2)), t0 a little later on every other street
            t0 = 2 + 0.25 * (k % 2 if rows else (k + 1) % 2)
            edges.append(('free', street[0], al, f'{0.1 * al:g}', 'dirichlet',
                          f'{al}*(0.12 + 0.3*exp(-((t - {t0:g})/0.8)^2))'))
            edges += [(a, b, al, f'{0.1 * al:g}', '', '') for a, b in zip(street, street[1:])]
            # the exits are narrower (70 % of the street's capacity): at the rush
            # hour the traffic jams back into the grid from them
            edges.append((street[-1], 'free', f'{0.7 * al:g}', f'{0.07 * al:g}', 'outflow', ''))
    with open(edge_file, 'w') as f:
        f.write(f'# a {n} x {n} city grid (contrib/make_network_grid.py {n})\n'
                'id,from,to,length,flux,parameter,initial,far_end,far_end_data\n')
        f.writelines(f'{k},{a},{b},1,traffic,{al},{initial},{far},{g}\n' for k, (a, b, al, initial, far, g)
                     in enumerate(edges, 1))
    with open(vertex_file, 'w') as f:
        f.write(f'# the junctions of the {n} x {n} city grid\nid,x,y\n')
        f.writelines(f'{vid(i, j)},{i},{j}\n' for j in range(n) for i in range(n))
    return len(edges)


if __name__ == '__main__':
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    if int(sys.argv[1]) < 2:
        sys.exit('N must be >= 2')
    n_edges = write_grid(int(sys.argv[1]), sys.argv[2], sys.argv[3])
    print(f'{sys.argv[2]}: {n_edges} edges, {sys.argv[3]}: {int(sys.argv[1]) ** 2} junctions')
