#!/usr/bin/python3
"""Checkpoint/restart equivalence: a run that is stopped, killed or
interrupted and then resumed must end with the output of a run that was not.

usage: resume_test.py EXE PRM MODE [--np A] [--resume-np B] [--every K]
                      [--set Section/name=value ...]      (in an empty directory)

MODE
  stop:N   the run stops at Time stepping/max steps = N (exit 0, a checkpoint
           at step N); then --resume runs it to the end
  kill     SIGKILL at a random moment after its first checkpoint (the ranks,
           then the rest of the process group: mpirun); then --resume
  sigint   SIGINT after its first checkpoint: exit 130, one line on stderr,
           summary.json status 'interrupted by SIGINT ...', a checkpoint; then
           --resume

The reference run (directory ref/) and the interrupted one (run/) use the same
parameters (checkpoints every K steps, default 10) on A ranks (0: serial, no
mpirun); the resumed run uses B ranks (default A). Compared: every file the
reference wrote but checkpoints/ and summary.json byte for byte (same rank
counts), the numbers of every CSV file column-scaled beyond the print
resolution (tests/common/csv_compare.py, as tests/mpi does), and every
summary.json entry but the timings (exactly; on another rank count to 1e-12
of the entry's scale). Prints one line per check; the test compares them with the stored
output (the numbers at the tolerance the test states). What varies from run
to run (the step of the kill) goes to stderr.
"""
import argparse
import json
import os
import random
import signal
import subprocess
import sys
import time

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import csv_compare  # noqa: E402

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
a.add_argument('mode')
a.add_argument('--np', type=int, default=0)
a.add_argument('--resume-np', type=int, default=-1)
a.add_argument('--every', type=int, default=10)
a.add_argument('--set', action='append', default=[])
args = a.parse_args()
resume_np = args.np if args.resume_np < 0 else args.resume_np

# not compared: the clocks, and what says how the run went rather than what
# it computed
TIMING = {'wall_time_s', 'time_loop_s', 'time_loop_cpu_s', 'dof_updates_per_s',
          'dof_updates_per_cpu_s_per_rank', 'resumed_from_step', 'n_mpi_ranks',
          'cpu_time_loop_s', 'dof_updates_per_cpu_s'}


def command(directory, np, *extra):
    # absolute: the pattern that finds the ranks of a killed MPI run
    cmd = [args.exe, args.prm, '--set', f'Output/directory={os.path.abspath(directory)}',
           '--set', 'Output/progress interval=0',
           '--set', f'Checkpoint/every steps={args.every}']
    for s in args.set:
        cmd += ['--set', s]
    cmd += list(extra)
    if np > 0:
        cmd = ['mpirun', '--allow-run-as-root', '--oversubscribe', '-np', str(np)] + cmd
    return cmd


def run(directory, np, *extra):
    p = subprocess.run(command(directory, np, *extra), capture_output=True, text=True)
    return p.returncode, p.stdout, p.stderr


def checkpoints(directory):
    found = []
    for root, dirs, files in os.walk(directory):
        if os.path.basename(root) == 'checkpoints':
            found += [os.path.join(root, f) for f in files if f.endswith('.ckpt')]
    return sorted(found)


def interrupt(sig):
    """Start run/, wait for its first checkpoint, send sig at a random moment
    after it, while the time loop still runs (a signal that came too late,
    after the run completed, is retried with a shorter delay). Returns
    (exit code, stderr)."""
    for attempt in range(6):
        if os.path.exists('run'):
            subprocess.run(['rm', '-rf', 'run'])
        p = subprocess.Popen(command('run', args.np), stdout=subprocess.DEVNULL,
                             stderr=subprocess.PIPE, text=True, start_new_session=True)
        while p.poll() is None and not checkpoints('run'):
            time.sleep(0.005)
        delay = random.uniform(0, 0.4) / 2 ** attempt
        time.sleep(delay)
        if p.poll() is not None:
            print(f'attempt {attempt}: the run ended before the signal', file=sys.stderr)
            continue
        if sig == signal.SIGKILL:
            if args.np > 0:
                # the ranks first, and mpirun, left alive for a moment, removes
                # their shared-memory segments (/dev/shm/vader_segment.*, 4 MB
                # a rank), which stay on the machine when it is killed with them
                subprocess.run(['pkill', '-KILL', '-P', str(p.pid)])
                try:
                    p.wait(timeout=10)
                except subprocess.TimeoutExpired:
                    pass
            try:
                os.killpg(p.pid, signal.SIGKILL)
            except ProcessLookupError:
                pass
            # ranks that mpirun started in process groups of their own
            pattern = 'Output/directory=' + os.path.abspath('run')
            subprocess.run(['pkill', '-KILL', '-f', pattern])
            while subprocess.run(['pgrep', '-f', pattern], capture_output=True).returncode == 0:
                time.sleep(0.05)
        elif args.np == 0:
            os.kill(p.pid, sig)
        else:
            os.killpg(p.pid, sig)
        _, err = p.communicate()
        print(f'signal {sig} after {delay:.3f} s; checkpoints then: '
              f'{[os.path.basename(c) for c in checkpoints("run")]}', file=sys.stderr)
        done = (os.path.exists('run/summary.json') and status_of('run') == 'completed') or \
            at_the_end('run')
        if done or (sig == signal.SIGINT and p.returncode != 128 + sig):
            print(f'attempt {attempt}: the signal came after the time loop (exit '
                  f'{p.returncode}); again, sooner', file=sys.stderr)
            continue
        return p.returncode, err
    sys.exit('resume_test: the run always ended before it could be interrupted')


def at_the_end(directory):
    """Whether the newest checkpoint of directory/checkpoints is at the
    reference run's last step: a kill that lands after the final checkpoint
    but before summary.json leaves nothing to resume."""
    try:
        with open('ref/summary.json') as f:
            last = json.load(f)['n_time_steps']
    except (OSError, KeyError, ValueError):
        return False
    steps = [int(os.path.basename(c)[5:15]) for c in checkpoints(directory)
             if os.path.dirname(c) == os.path.join(directory, 'checkpoints')]
    return bool(steps) and max(steps) >= last


def last_summary(directory):
    """summary.json (of the part that ran last, for two-part runs); None if none."""
    found = [os.path.join(r, 'summary.json') for r, d, f in os.walk(directory)
             if 'summary.json' in f]
    if not found:
        return None
    with open(max(found, key=os.path.getmtime)) as f:
        return json.load(f)


def status_of(directory):
    s = last_summary(directory)
    return s['status'] if s else '(no summary.json)'


def cost_recorded(directory):
    """Whether summary.json of a run that stopped early records the cost of
    its time loop (wall and CPU time, throughput), as a completed run's does."""
    s = last_summary(directory)
    if s is None:
        return 'no: no summary.json'
    ok = all(s[k] > 0 for k in ('time_loop_s', 'time_loop_cpu_s', 'dof_updates_per_s',
                                'dof_updates_per_cpu_s_per_rank'))
    return 'yes' if ok else 'no: ' + ', '.join(f'{k} {s[k]}' for k in sorted(TIMING) if k in s)


def flatten(d, prefix=''):
    out = {}
    for k, v in d.items():
        if isinstance(v, dict):
            out.update(flatten(v, prefix + k + '/'))
        else:
            out[prefix + k] = v
    return out


def same(summary, key, v, rel):
    """Entry key of summary equals v: exactly (rel = 0), or numbers to rel of
    their scale (the largest of the entry and its _x/_y partner) beyond the
    print resolution."""
    u = summary[key]
    if rel == 0 or not isinstance(u, (int, float)) or not isinstance(v, (int, float)):
        return u == v
    keys = [key[:-2] + '_x', key[:-2] + '_y'] if key[-2:] in ('_x', '_y') else [key]
    scale = max(abs(summary.get(k, 0.)) for k in keys)
    allowed = rel * scale + max(csv_compare.print_unit(u), csv_compare.print_unit(v))
    return abs(u - v) <= allowed


code, _, err = run('ref', args.np)
print(f'reference run: exit {code}')
if code != 0:
    sys.exit('resume_test: the reference run failed: ' + err)

if args.mode.startswith('stop:'):
    n = args.mode[5:]
    code, out, err = run('run', args.np, '--set', f'Time stepping/max steps={n}')
    status = status_of('run')
    print(f'stopped run: exit {code}; status: {status.split(";")[0]}')
    print(f"  the time loop's cost in summary.json: {cost_recorded('run')}")
elif args.mode == 'kill':
    code, err = interrupt(signal.SIGKILL)
    # (mpirun exits with 128 + 9 when its ranks were killed)
    killed = code in (-signal.SIGKILL, 128 + signal.SIGKILL)
    print(f'killed run: exit {"SIGKILL" if killed else code}, '
          f'{"has" if checkpoints("run") else "no"} checkpoint')
elif args.mode == 'sigint':
    code, err = interrupt(signal.SIGINT)
    lines = err.splitlines()
    status = status_of('run')
    print(f'interrupted run: exit {code}, {len(lines)} line(s) on stderr, '
          f'{"has" if checkpoints("run") else "no"} checkpoint')
    print(f'  stderr: {" ".join(lines[-1].split()[:4]) if lines else ""} ...')
    print(f'  status: {" ".join(status.split()[:3])} ...')
    print(f'  {"the status names the checkpoint" if ".ckpt; continue with --resume" in status else status}')
    print(f"  the time loop's cost in summary.json: {cost_recorded('run')}")
else:
    sys.exit('resume_test: unknown mode ' + args.mode)

code, out, err = run('run', resume_np, '--resume')
print(f'resumed run: exit {code}')
if code != 0:
    sys.exit('resume_test: the resumed run failed: ' + err)
for line in out.splitlines():
    if 'resuming from' in line:
        print(line.strip(), file=sys.stderr)

# every file of the reference, byte for byte (with the same rank count)
files = []
for root, dirs, names in os.walk('ref'):
    dirs[:] = [d for d in dirs if d != 'checkpoints']
    files += [os.path.relpath(os.path.join(root, f), 'ref') for f in names if f != 'summary.json']
files.sort()
missing = [f for f in files if not os.path.exists(os.path.join('run', f))]
print(f'files compared: {len(files)}, missing in the resumed run: {len(missing)}')
def content(path):
    with open(path, 'rb') as f:
        data = f.read()
    if os.path.basename(path) == 'parameters.prm':
        # the output directories differ by name (and nothing else: a resumed
        # run's parameters are the uninterrupted run's)
        data = b'\n'.join(l for l in data.split(b'\n') if b'set directory' not in l)
    if os.path.basename(path) == '.granular_dg-manifest':
        # the files the run wrote, in the order it wrote them: a set
        data = b'\n'.join(sorted(data.split(b'\n')))
    return data


if resume_np == args.np:
    # HDF5 snapshots store their objects' creation times: not comparable byte
    # for byte (their data are the solution the CSVs and solution.xdmf check)
    h5 = [f for f in files if f.endswith('.h5')]
    if h5:
        print(f'HDF5 files present in both runs (not compared byte for byte): {len(h5)}')
    differ = [f for f in files if f not in missing and f not in h5 and
              content(os.path.join('ref', f)) != content(os.path.join('run', f))]
    print(f'files not byte-identical: {len(differ)}')
    for f in differ:
        print('  differs: ' + f, file=sys.stderr)
extra = []
for root, dirs, names in os.walk('run'):
    dirs[:] = [d for d in dirs if d != 'checkpoints']
    extra += [os.path.relpath(os.path.join(root, f), 'run') for f in names
              if not os.path.exists(os.path.join('ref', os.path.relpath(os.path.join(root, f), 'run')))]
print(f'files only in the resumed run: {len(extra)}')

worst = 0.
for f in files:
    if f.endswith('.csv') and f not in missing:
        d = csv_compare.difference(os.path.join('ref', f), os.path.join('run', f))
        if d is None:
            print(f'{f}: differs in shape', file=sys.stderr)
            worst = float('inf')
            continue
        print(f'{f}: beyond the print resolution {d[0]:.3e} ({d[2]}), '
              f'column-scaled {d[1]:.3e}', file=sys.stderr)
        worst = max(worst, d[0])
print(f'max column-scaled CSV difference: {worst:.3e}')

with open('ref/summary.json') as f:
    s0 = flatten(json.load(f))
with open('run/summary.json') as f:
    s1 = flatten(json.load(f))
rel = 0. if resume_np == args.np == 0 else 1e-12
# the memory report (bytes per DoF) depends on the rank count and the
# process, not on the results
keys = [k for k in s0 if k.split('/')[-1] not in TIMING and not k.endswith('_bytes_per_dof')]
bad = [k for k in keys if k not in s1 or not same(s0, k, s1[k], rel)]
print(f'summary.json entries compared: {len(keys)}, differing: {len(bad)}')
for k in bad:
    print(f'  {k}: {s0[k]} vs {s1.get(k)}', file=sys.stderr)
# (a two-part run killed in its first part starts the second afresh: no
# resumed_from_step there; where a kill lands is random)
print(f'resumed_from_step recorded: {"yes" if s1.get("resumed_from_step", 0) > 0 else "no"}',
      file=sys.stderr if args.mode == 'kill' else sys.stdout)
