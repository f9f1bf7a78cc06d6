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


def main():
    if len(sys.argv) != 4:
        sys.exit(__doc__)
    n = int(sys.argv[1])
    if n < 2:
        sys.exit('N must be >= 2')
    edge_file, vertex_file = sys.argv[2], sys.argv[3]
    avenue = n // 2

    def vid(i, j):  # junction in column i, row j (1-based ids)
        return 1 + i + n * j

    def alpha(is_row, index):
        return 2 if index == avenue else 1

    edges = []

    def street(a, b, al, initial='0.1'):
        edges.append((a, b, al, initial, '', ''))

    def inflow(b, al, phase):
        # density alpha (0.12 + 0.3 exp(-((t - 2)/0.8)^2)), a little later
        # on every other street
        t0 = 2 + 0.25 * phase
        g = f'{al}*(0.12 + 0.3*exp(-((t - {t0:g})/0.8)^2))'
        edges.append(('free', b, al, f'{0.1 * al:g}', 'dirichlet', g))

    def outflow(a, al):
        # the exits are narrower (70 % of the street's capacity): at the rush
        # hour the traffic jams back into the grid from them
        edges.append((a, 'free', f'{0.7 * al:g}', f'{0.07 * al:g}', 'outflow', ''))

    for j in range(n):  # rows: even eastbound, odd westbound
        al = alpha(True, j)
        cols = list(range(n)) if j % 2 == 0 else list(range(n - 1, -1, -1))
        inflow(vid(cols[0], j), al, j % 2)
        for a, b in zip(cols, cols[1:]):
            street(vid(a, j), vid(b, j), al, f'{0.1 * al:g}')
        outflow(vid(cols[-1], j), al)
    for i in range(n):  # columns: even northbound, odd southbound
        al = alpha(False, i)
        rows = list(range(n)) if i % 2 == 0 else list(range(n - 1, -1, -1))
        inflow(vid(i, rows[0]), al, (i + 1) % 2)
        for a, b in zip(rows, rows[1:]):
            street(vid(i, a), vid(i, b), al, f'{0.1 * al:g}')
        outflow(vid(i, rows[-1]), al)

    with open(edge_file, 'w') as f:
        f.write(f'# a {n} x {n} city grid (contrib/make_network_grid.py {n})\n')
        f.write('id,from,to,length,flux,parameter,initial,far_end,far_end_data\n')
        for k, (a, b, al, initial, far, g) in enumerate(edges, 1):
            f.write(f'{k},{a},{b},1,traffic,{al},{initial},{far},{g}\n')
    with open(vertex_file, 'w') as f:
        f.write(f'# the junctions of the {n} x {n} city grid\n')
        f.write('id,x,y\n')
        for j in range(n):
            for i in range(n):
                f.write(f'{vid(i, j)},{i},{j}\n')
    print(f'{edge_file}: {len(edges)} edges, {vertex_file}: {n * n} junctions')


main()
