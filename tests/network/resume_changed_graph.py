#!/usr/bin/python3
"""Resuming a network whose graph files changed since its checkpoint: the
parameters name the graph and vertex files, not their content, so the
checkpoint stores a hash of each file's bytes. A changed file must be refused
like a changed parameter (exit 2, one line on stderr naming the file), and
the run must stay resumable with the files it started with.

usage: resume_changed_graph.py EXE PRM   (in a directory holding PRM with its
graph file ring.csv and vertex file ring_vertices.csv; prints one block per
case, compared verbatim with resume_changed_graph.output)
"""
import json
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
from granular_run import report  # noqa: E402

exe, prm = sys.argv[1:3]


def run(*extra):
    p = subprocess.run([exe, prm, '--set', 'Output/directory=out',
                        '--set', 'Output/progress interval=0', *extra],
                       capture_output=True, text=True)
    return p.returncode, p.stderr.splitlines()


def replace(file, old, new):
    with open(file) as f:
        text = f.read()
    assert old in text, (file, old)
    with open(file, 'w') as f:
        f.write(text.replace(old, new))


shutil.copy('ring.csv', 'ring.csv.orig')
shutil.copy('ring_vertices.csv', 'ring_vertices.csv.orig')
report('run stopped at max steps = 100', *run('--set', 'Time stepping/max steps=100'))

# the same numbers of vertices, edges and cells: Edge 3 reversed and linear,
# the inflow 0.3 -> 0.4
replace('ring.csv', '\n3,2,3,1,traffic,1,0.2', '\n3,3,2,1,linear,1,0.2')
replace('ring.csv', 'dirichlet,0.3', 'dirichlet,0.4')
report('resume with the graph file changed (an edge reversed, its flux law, the inflow)',
       *run('--resume'))
shutil.copy('ring.csv.orig', 'ring.csv')

# Vertex 2 without volume
replace('ring_vertices.csv', '\n2,1,0', '\n2,1,0,0')
report('resume with the vertex file changed (a width factor)', *run('--resume'))
shutil.copy('ring_vertices.csv.orig', 'ring_vertices.csv')

report('resume with the files it started with', *run('--resume'))
with open('out/summary.json') as f:
    summary = json.load(f)
print(f'  status {summary["status"]}, final time {summary["final_time"]}')
