#!/usr/bin/python3
"""Resuming what cannot be resumed: every case must end with exit code 2 (bad
input) and one line on stderr naming the parameter or file and why, except a
damaged newest checkpoint, which is skipped with a warning in favour of the
older one. Also: a run split by Time stepping/max steps, and a completed run.

usage: bad_resume.py EXE LAYERED_PRM COLUMN_PRM   (in an empty directory;
prints one block per case, compared verbatim with bad_resume.output)
"""
import glob
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
from granular_run import report  # noqa: E402

exe, layered, column = sys.argv[1:4]
QUICK = ['--set', 'Mesh/cells x=32', '--set', 'Time stepping/final time=0.5',
         '--set', 'Output/progress interval=0', '--set', 'Checkpoint/every steps=20']


def run(prm, directory, *extra):
    p = subprocess.run([exe, prm, '--set', f'Output/directory={directory}', *extra],
                       capture_output=True, text=True)
    return p.returncode, p.stderr.splitlines()


def newest(directory):
    return sorted(glob.glob(f'{directory}/checkpoints/step-*.ckpt'))[-1]


report('resume without a previous run', *run(layered, 'none', *QUICK, '--resume'))

# a run stopped at max steps: two checkpoints (steps 20 and 30), resumable
code, err = run(layered, 'out', *QUICK, '--set', 'Time stepping/max steps=30')
report('run stopped at max steps = 30', code, err)
print('  checkpoints: ' + ' '.join(sorted(os.path.basename(f) for f in
                                          glob.glob('out/checkpoints/*'))))
shutil.copytree('out', 'pristine')

report('resume with another degree', *run(layered, 'out', *QUICK, '--resume',
                                          '--set', 'Discretization/degree=1'))
report('resume with another mesh', *run(layered, 'out', *QUICK, '--resume',
                                        '--set', 'Mesh/cells x=64'))
report('resume and overwrite', *run(layered, 'out', *QUICK, '--resume',
                                    '--set', 'Output/overwrite=true'))
report('resume with max steps below the checkpoint',
       *run(layered, 'out', *QUICK, '--resume', '--set', 'Time stepping/max steps=25'))
report('resume with the final time before the checkpoint',
       *run(layered, 'out', *QUICK, '--resume', '--set', 'Time stepping/final time=0.1'))

# a checkpoint with a flipped byte: the older one is used
with open(newest('out'), 'r+b') as f:
    f.seek(-100, 2)
    b = f.read(1)
    f.seek(-100, 2)
    f.write(bytes([b[0] ^ 0xff]))
report('newest checkpoint corrupt', *run(layered, 'out', *QUICK, '--resume'))

# every checkpoint damaged: nothing to resume from
shutil.rmtree('out')
shutil.copytree('pristine', 'out')
files = sorted(glob.glob('out/checkpoints/*.ckpt'))
with open(files[0], 'r+b') as f:
    f.truncate(os.path.getsize(files[0]) - 10)
with open(files[1], 'w') as f:
    f.write('not a checkpoint\n')
report('all checkpoints damaged', *run(layered, 'out', *QUICK, '--resume'))

# a checkpoint of another scene put among this run's
shutil.rmtree('out')
shutil.copytree('pristine', 'out')
code, err = run(column, 'col', '--set', 'Output/progress interval=0', '--set',
                'Checkpoint/every steps=100', '--set', 'Time stepping/max steps=100')
shutil.copy(newest('col'), 'out/checkpoints/step-0000000099.ckpt')
report('a column checkpoint in a layered run', *run(layered, 'out', *QUICK, '--resume'))

# resumed to the end; then a completed run has nothing to resume
shutil.rmtree('out')
shutil.copytree('pristine', 'out')
report('resume after max steps', *run(layered, 'out', *QUICK, '--resume'))
report('resume a completed run', *run(layered, 'out', *QUICK, '--resume'))
