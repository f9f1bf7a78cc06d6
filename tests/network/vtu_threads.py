#!/usr/bin/python3
"""A network VTU snapshot in several pieces is the same file, byte for byte,
whether one thread compresses its pieces one after another or several
compress them at once.

usage: vtu_threads.py EXE PRM [--set Section/name=value ...]   (in an empty directory)

Runs PRM twice: bound to one core (`taskset -c 0`: the writer then uses one
thread) and on every core this process may use (one writer thread per core).
Prints per snapshot of the second run its number of <Piece> elements and
whether the file equals the first run's byte for byte (1) or not (0). On a
machine with one core both runs write alike, and stderr says so.
"""
import glob
import os
import subprocess
import sys

exe, prm, overrides = sys.argv[1], sys.argv[2], sys.argv[3:]
cores = len(os.sched_getaffinity(0))
if cores < 2:
    print(f'vtu_threads: this process may use {cores} core: both runs use one writer thread',
          file=sys.stderr)


def run(directory, prefix):
    cmd = prefix + [exe, prm, '--set', f'Output/directory={directory}',
                    '--set', 'Output/progress interval=0'] + overrides
    proc = subprocess.run(cmd, capture_output=True, text=True)
    if proc.returncode != 0:
        sys.exit(f'vtu_threads: {" ".join(cmd)} exited with {proc.returncode}:\n{proc.stderr}')


run('one_core', ['taskset', '-c', '0'])
run('all_cores', [])
snapshots = sorted(glob.glob('all_cores/solution-*.vtu'))
if not snapshots:
    sys.exit('vtu_threads: the run wrote no VTU snapshot')
for path in snapshots:
    with open(path, 'rb') as f:
        threaded = f.read()
    with open(os.path.join('one_core', os.path.basename(path)), 'rb') as f:
        sequential = f.read()
    print(os.path.basename(path), 'pieces', threaded.count(b'<Piece '),
          'same_bytes', int(threaded == sequential))
