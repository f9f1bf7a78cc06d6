#!/usr/bin/python3
"""Resume compares parameters by meaning, not by text: a
run made with Output/directory = rel, output times '0.5, 0.75' and CFL
number 0.15 and stopped at max steps is resumed as ./rel/ with the times
'0.75, 0.5' and CFL number 0.150, and a second time by its absolute path
with CFL number 1.5e-1.

usage: resume_normalised.py EXE PRM   (in an empty directory)
"""
import os
import subprocess
import sys

exe, prm = sys.argv[1], sys.argv[2]


def run(directory, times, *extra):
    p = subprocess.run([exe, prm, '--set', f'Output/directory={directory}',
                        '--set', f'Output/output times={times}',
                        '--set', 'Output/progress interval=0',
                        '--set', 'Time stepping/final time=1', *extra],
                       capture_output=True, text=True)
    return p.returncode, p.stderr.strip()


cfl = 'Time stepping/CFL number='
code, _ = run('rel', '0.5, 0.75', '--set', 'Time stepping/max steps=5', '--set', cfl + '0.15')
print(f'first part (max steps 5): exit {code}')
code, err = run('./rel/', '0.75, 0.5', '--set', 'Time stepping/max steps=10',
                '--set', cfl + '0.150', '--resume')
print(f'resumed as ./rel/ with the times reordered, CFL 0.150: exit {code} {err[:200]}')
code, err = run(os.path.abspath('rel'), '0.5,0.75', '--set', cfl + '1.5e-1', '--resume')
print(f'resumed by the absolute path, CFL 1.5e-1: exit {code} {err[:200]}')
with open('rel/summary.json') as f:
    print('status completed: ' + ('yes' if '"status": "completed"' in f.read() else 'no'))
