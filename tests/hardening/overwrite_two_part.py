#!/usr/bin/python3
"""Output/overwrite = true over a two-part run of the layered strip
(Boundary conditions/periodic from > 0, the first part in OUT/before-periodic/)
removes that part's folder with its bookkeeping when a one-part run takes
the directory, and keeps the folder when the user put a file into it (with
that file only); a two-part run over a two-part run keeps its new first
part.

usage: overwrite_two_part.py EXE PRM   (in an empty directory)
"""
import os
import subprocess
import sys

exe, prm = sys.argv[1], sys.argv[2]
base = [exe, prm, '--set', 'Output/directory=out', '--set', 'Output/progress interval=0',
        '--set', 'Mesh/x max=60', '--set', 'Mesh/cells x=240',
        '--set', 'Time stepping/final time=40', '--set', 'Output/output times=10, 20, 30']
two_part = ['--set', 'Boundary conditions/periodic from=20']
overwrite = ['--set', 'Output/overwrite=true']


def run(*extra):
    return subprocess.run(base + list(extra), capture_output=True, text=True).returncode


def listing():
    return sorted(os.listdir('out/before-periodic')) if os.path.isdir('out/before-periodic') else None


print(f'two-part run: exit {run(*two_part)}, out/before-periodic/ holds results: '
      + ('yes' if 'summary.json' in (listing() or []) else 'no'))
print(f'two-part run over it: exit {run(*two_part, *overwrite)}, out/before-periodic/ holds '
      'results: ' + ('yes' if 'summary.json' in (listing() or []) else 'no'))
print(f'one-part run over it: exit {run(*overwrite)}, out/before-periodic/ left: {listing()}')
print(f'two-part run again: exit {run(*two_part, *overwrite)}')
open('out/before-periodic/mine.txt', 'w').write('the user\'s\n')
print(f'one-part run over it with a file of the user\'s in the folder: exit {run(*overwrite)}, '
      f'out/before-periodic/ left: {listing()}')
