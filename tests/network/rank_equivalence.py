#!/usr/bin/python3
"""A network run on 1, 2, 3 ... MPI ranks computes the same solution bit for
bit, and a run stopped on one rank count resumes on another.

usage: rank_equivalence.py EXE PRM RANKS... [--resume STEPS:FROM:TO]
                           [--set Section/name=value ...]   (in an empty directory)

Every rank count runs PRM under mpirun into out-npN/. Against the first rank
count it prints per rank count
  - the number of profile-*.csv files that differ byte for byte and of VTU
    snapshots whose points differ (solution-NNNN.vtu on one rank, the pieces
    of solution-NNNN.pvtu on several: the same points with the same coordinates
    and values, in any order) (0: the traces exchanged at the vertices shared
    by several ranks make every stage exactly the one-rank stage);
  - the column-scaled difference of timeseries.csv beyond its print resolution
    (tests/common/csv_compare.py), without mass_balance_residual: a round-off
    quantity whose sum over the ranks is added in another order;
  - whether mass_balance_residual stays below 1e-13 on every rank count.
--resume S:A:B also stops a run on A ranks at step S (Time stepping/max steps)
and resumes it on B ranks; its profiles and VTU snapshots must equal those of
the first rank count.
"""
import argparse
import base64
import glob
import os
import struct
import subprocess
import sys
import xml.etree.ElementTree as ET
import zlib

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import csv_compare  # noqa: E402

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
a.add_argument('ranks', type=int, nargs='+')
a.add_argument('--resume', default='')
a.add_argument('--set', action='append', default=[])
args = a.parse_args()


def run(directory, n, *extra, resume=False):
    cmd = ['mpirun', '--allow-run-as-root', '--oversubscribe', '-np', str(n), args.exe] + \
          (['--resume'] if resume else []) + \
          [args.prm, '--set', f'Output/directory={directory}', '--set', 'Output/progress interval=0']
    for s in args.set:
        cmd += ['--set', s]
    cmd += list(extra)
    p = subprocess.run(cmd, capture_output=True, text=True)
    if p.returncode != 0:
        sys.exit(f'rank_equivalence: {" ".join(cmd)} exited with {p.returncode}:\n{p.stderr}')
    return directory


def solution_files(directory):
    """the profiles and VTU snapshots (solution-NNNN, without suffix) of a run"""
    return sorted([os.path.basename(f) for f in glob.glob(os.path.join(directory, 'profile-*.csv'))] +
                  [os.path.basename(f)[:-4] for f in glob.glob(os.path.join(directory, 'solution-????.vtu')) +
                   glob.glob(os.path.join(directory, 'solution-????.pvtu'))])


def vtu_points(path):
    """The points of a VTU file as DataOutBase::write_vtu writes it (binary,
    one zlib block per array): rows of the coordinates and then the point
    arrays in the order of their names."""
    piece = ET.parse(path).getroot().find('UnstructuredGrid/Piece')
    n = int(piece.get('NumberOfPoints'))

    def decode(array):
        text = ''.join(array.text.split())
        blocks, _, _, _ = struct.unpack('<4I', base64.b64decode(text[:24]))
        if blocks != 1:
            sys.exit(f'rank_equivalence: {path}: {blocks} compressed blocks, one expected')
        data = zlib.decompress(base64.b64decode(text[24:]))
        kind = {'Float32': 'f', 'Float64': 'd'}[array.get('type')]
        return struct.unpack(f'<{len(data) // struct.calcsize(kind)}{kind}', data)

    xyz = decode(piece.find('Points/DataArray')) if n else ()
    arrays = [decode(a) for a in sorted(piece.find('PointData'), key=lambda a: a.get('Name'))] if n else []
    return [xyz[3 * i:3 * i + 3] + tuple(a[i] for a in arrays) for i in range(n)]


def snapshot_points(directory, name):
    """the sorted points of snapshot `name`: its .vtu, or the pieces its .pvtu lists"""
    path = os.path.join(directory, name)
    if os.path.exists(path + '.vtu'):
        return sorted(vtu_points(path + '.vtu'))
    if not os.path.exists(path + '.pvtu'):
        return None
    pieces = ET.parse(path + '.pvtu').getroot().findall('PUnstructuredGrid/Piece')
    return sorted(p for piece in pieces for p in vtu_points(os.path.join(directory, piece.get('Source'))))


def differing(ref, other):
    """the profiles (byte for byte) and snapshots (point by point) of ref that
    other lacks or has with other contents"""
    count = 0
    for name in solution_files(ref):
        if name.startswith('solution-'):
            count += snapshot_points(ref, name) != snapshot_points(other, name)
            continue
        path = os.path.join(other, name)
        with open(os.path.join(ref, name), 'rb') as f:
            mine = f.read()
        if not os.path.exists(path):
            count += 1
            continue
        with open(path, 'rb') as f:
            count += f.read() != mine
    return count


def max_residual(directory):
    header, rows = csv_compare.read(os.path.join(directory, 'timeseries.csv'))
    j = header.index('mass_balance_residual')
    return max(abs(r[j]) for r in rows)


def without_residual(directory):
    """timeseries.csv without the mass_balance_residual column (a copy)"""
    path = os.path.join(directory, 'timeseries.csv')
    with open(path) as f:
        lines = [l for l in f if not l.startswith('#')]
    j = lines[0].strip().split(',').index('mass_balance_residual')
    out = path + '.solution'
    with open(out, 'w') as f:
        for line in lines:
            cells = line.strip().split(',')
            f.write(','.join(cells[:j] + cells[j + 1:]) + '\n')
    return out


dirs = {n: run(f'out-np{n}', n) for n in args.ranks}
ref = dirs[args.ranks[0]]
print(f'np{args.ranks[0]}: {len(solution_files(ref))} profile and VTU files')
for n in args.ranks:
    if n != args.ranks[0]:
        result = csv_compare.difference(without_residual(ref), without_residual(dirs[n]))
        if result is None:
            sys.exit(f'rank_equivalence: timeseries.csv differs in shape on {n} ranks')
        worst, raw, where = result
        print(f'np{n}: solution files differing from np{args.ranks[0]}: {differing(ref, dirs[n])}')
        print(f'np{n}: timeseries.csv but mass_balance_residual = {worst:.3e}')
        print(f'np{n} timeseries.csv: column-scaled difference {raw:.3e} ({where})', file=sys.stderr)
    print(f'np{n}: mass_balance_residual below 1e-13: {max_residual(dirs[n]) < 1e-13}')

if args.resume:
    steps, first, then = (int(x) for x in args.resume.split(':'))
    run('resumed', first, '--set', f'Time stepping/max steps={steps}')
    run('resumed', then, resume=True)
    print(f'stopped on {first} ranks at step {steps}, resumed on {then}: solution files '
          f'differing from np{args.ranks[0]}: {differing(ref, "resumed")}')
