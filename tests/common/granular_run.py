"""Run granular_dg from a test script: one place for the command line the
Python-driven tests share (output directory, no progress lines, the test's
--set overrides) and for what a failed run does to the test."""
import json
import os
import subprocess
import sys


def run(exe, prm, directory, settings=(), label=None):
    """Runs `exe prm` into `directory` with `settings` ('Section/name=value'
    strings), prints '<label>: exit N', and ends the test with the run's
    stderr if it failed. Returns the run's summary.json."""
    cmd = [exe, prm, '--set', f'Output/directory={directory}', '--set', 'Output/progress interval=0']
    for s in settings:
        cmd += ['--set', s]
    p = subprocess.run(cmd, capture_output=True, text=True)
    print(f'{label or directory}: exit {p.returncode}')
    if p.returncode != 0:
        sys.exit(p.stderr)
    with open(os.path.join(directory, 'summary.json')) as f:
        return json.load(f)


def report(title, code, err):
    """Prints a run's outcome for a test's stdout: '<title>: exit N, K
    line(s) on stderr', then each stderr line indented."""
    print(f'{title}: exit {code}, {len(err)} line(s) on stderr')
    for line in err:
        print('  ' + line)
