#!/usr/bin/python3
"""An output directory that holds a previous run: refused without
Output/overwrite; with it, exactly the files the previous run wrote (its
manifest) are removed, so that a user's files survive even when their names
look like the program's; refused too when the previous run was killed
before summary.json.

usage: previous_run.py EXE PRM   (run in an empty directory; prints one line
per check, compared with previous_run.output)
"""
import os
import subprocess
import sys

exe, prm = sys.argv[1], sys.argv[2]


def run(*extra):
    p = subprocess.run([exe, prm, '--set', 'Output/directory=out',
                        '--set', 'Output/progress interval=0', *extra],
                       capture_output=True, text=True)
    lines = p.stderr.splitlines()
    return p.returncode, lines


# the first run writes one snapshot more than the ones after it
code, _ = run('--set', 'Output/output interval=0.025')
print(f'first run: exit {code}')
last = sorted(f for f in os.listdir('out') if f.startswith('profile-'))[-1]
# files of the user's, one with a name like the program's
open('out/solution-important.txt', 'w').close()
open('out/notes.txt', 'w').close()
code, err = run()
print(f'second run without overwrite: exit {code}, {len(err)} line(s) on stderr')
print(err[-1] if err else '')
print(f'  results untouched: {os.path.exists("out/" + last)}')
code, err = run('--set', 'Output/overwrite=true')
print(f'with overwrite = true: exit {code}')
print(f'  the previous run\'s last snapshot removed: {not os.path.exists("out/" + last)}')
print(f'  solution-important.txt kept: {os.path.exists("out/solution-important.txt")}')
print(f'  notes.txt kept: {os.path.exists("out/notes.txt")}')
# a run killed before it wrote summary.json still leaves results behind
os.remove('out/summary.json')
code, err = run()
print(f'killed run (no summary.json): exit {code}, {len(err)} line(s) on stderr')
print(err[-1] if err else '')
# a run that wrote checkpoints: the refusal points to --resume, and
# overwrite discards the checkpoints too
os.makedirs('out/checkpoints', exist_ok=True)
open('out/checkpoints/step-0000000007.ckpt', 'w').close()
code, err = run()
print(f'run with checkpoints: exit {code}, {len(err)} line(s) on stderr')
print(err[-1] if err else '')
code, err = run('--set', 'Output/overwrite=true')
print(f'with overwrite = true: exit {code}')
print(f'  checkpoints removed: {not os.path.exists("out/checkpoints")}')
