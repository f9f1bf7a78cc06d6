#!/usr/bin/python3
"""--benchmark times the case's own dynamics, and the smaller benchmark
defects are fixed: blocks restart from the initial state instead of
stepping past the final time, the directory gets benchmark.json and nothing
else (so a second benchmark into it runs), and benchmark.json names the
limiter.

usage: benchmark_twice.py EXE PRM   (in an empty directory)
"""
import json
import os
import subprocess
import sys

exe, prm = sys.argv[1], sys.argv[2]
cmd = [exe, '--benchmark', prm, '--set', 'Output/directory=bench',
       '--set', 'Time stepping/final time=1', '--set', 'Benchmark/steps=100',
       '--set', 'Benchmark/repetitions=2', '--set', 'Benchmark/warm-up steps=2',
       '--set', 'Output/output times=']
for attempt in ('first', 'second'):
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(f'{attempt} benchmark (202 steps of a case that ends after about 60): exit {p.returncode} '
          f'{p.stderr.strip()[:200]}')
print('files: ' + ' '.join(sorted(f for f in os.listdir('bench') if not f.startswith('.'))))
with open('bench/benchmark.json') as f:
    b = json.load(f)
print(f'limiter: {b["case"]["limiter"] if "case" in b else b.get("limiter")}')
