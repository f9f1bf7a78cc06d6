#!/usr/bin/python3
"""A second Ctrl-C must not leave an unusable directory:
SIGINT twice in quick succession after the first checkpoint; the run exits
130 with a complete final checkpoint (the second signal waits until it is in
place), and --resume finishes the run. Four trials.

usage: double_sigint.py EXE PRM   (in an empty directory)
"""
import glob
import os
import signal
import subprocess
import sys
import time

exe, prm = sys.argv[1], sys.argv[2]
good = 0
trials = 4
for trial in range(trials):
    d = f'out{trial}'
    base = [exe, prm, '--set', f'Output/directory={d}', '--set', 'Output/progress interval=0',
            '--set', 'Checkpoint/every steps=20']
    p = subprocess.Popen(base, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True)
    deadline = time.time() + 60
    while not glob.glob(f'{d}/checkpoints/*.ckpt') and time.time() < deadline:
        time.sleep(0.01)
    p.send_signal(signal.SIGINT)
    time.sleep(0.002 * trial)
    p.send_signal(signal.SIGINT)
    p.wait()
    complete = glob.glob(f'{d}/checkpoints/*.ckpt')
    lone_tmp = glob.glob(f'{d}/checkpoints/.*.tmp') and not complete
    r = subprocess.run(base + ['--resume'], capture_output=True, text=True)
    ok = p.returncode in (0, 130) and complete and not lone_tmp and r.returncode == 0
    if not ok:
        print(f'trial {trial}: exit {p.returncode}, checkpoints {len(complete)}, '
              f'resume exit {r.returncode}: {r.stderr.strip()[:200]}', file=sys.stderr)
    good += bool(ok)
print(f'trials with a usable directory after two SIGINTs (resumed to the end): {good} of {trials}')
