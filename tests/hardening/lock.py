#!/usr/bin/python3
"""The output directory is locked while a run writes it: a
second run or a resume on it exits 2 with one line naming the holder's PID;
once the holder is killed (kill -9) the OS releases the lock and a new run
proceeds.

usage: lock.py EXE PRM   (in an empty directory; prints one line per check)
"""
import os
import signal
import subprocess
import sys
import time

exe, prm = sys.argv[1], sys.argv[2]
base = [exe, prm, '--set', 'Output/directory=out', '--set', 'Output/progress interval=0']

first = subprocess.Popen(base + ['--set', 'Time stepping/final time=1e6',
                                 '--set', 'Checkpoint/every steps=50'],
                         stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)
deadline = time.time() + 60
while not os.path.exists('out/checkpoints') and time.time() < deadline:
    time.sleep(0.05)


def refused(*extra):
    p = subprocess.run(base + list(extra), capture_output=True, text=True)
    lines = p.stderr.splitlines()
    names_pid = bool(lines) and f'process {first.pid} ' in lines[-1]
    return f'exit {p.returncode}, {len(lines)} line(s), names the PID: {"yes" if names_pid else "no"}'


print('a second run while the first writes: ' + refused('--set', 'Output/overwrite=true'))
print('a resume while the first writes: ' + refused('--resume'))
os.kill(first.pid, signal.SIGKILL)
first.wait()
p = subprocess.run(base + ['--set', 'Output/overwrite=true'], capture_output=True, text=True)
print(f'after kill -9 of the first, a new run: exit {p.returncode}')
