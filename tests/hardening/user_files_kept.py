#!/usr/bin/python3
"""A run never removes or writes over a file the user put into its output
directory:

1. Output/overwrite = true removes only what the previous run wrote (the
   files its manifest lists and its own step-NNNNNNNNNN.ckpt checkpoints); a
   file the user put into OUT/checkpoints/ stays, with the folder, as do
   files beside the results (OUT/notes.txt, OUT/sub/x.txt).
2. A case file named parameters.prm inside its own output directory is
   refused (exit 2, one line), not replaced by the parameter dump; the file
   is unchanged afterwards.

usage: user_files_kept.py EXE PRM   (in an empty directory; prints one line
per check)
"""
import os
import shutil
import subprocess
import sys

exe, prm = sys.argv[1], os.path.abspath(sys.argv[2])
base = [exe, prm, '--set', 'Output/directory=out', '--set', 'Output/progress interval=0',
        '--set', 'Time stepping/max steps=20', '--set', 'Checkpoint/every steps=10']


def run(args, cwd='.'):
    return subprocess.run(args, capture_output=True, text=True, cwd=cwd)


p = run(base)
print(f'first run: exit {p.returncode}, checkpoints written: '
      f'{len([f for f in os.listdir("out/checkpoints") if f.startswith("step-")])}')
user_files = ['out/checkpoints/my_model.pt', 'out/notes.txt', 'out/sub/x.txt']
for f in user_files:
    os.makedirs(os.path.dirname(f), exist_ok=True)
    with open(f, 'w') as out:
        out.write('the user\'s\n')
previous = set(f for f in os.listdir('out/checkpoints') if f.startswith('step-'))
# (this run stops at step 15 and writes only its own checkpoint there)
p = run(base + ['--set', 'Output/overwrite=true', '--set', 'Checkpoint/every steps=0',
                '--set', 'Time stepping/max steps=15'])
print(f'overwrite: exit {p.returncode}')
for f in user_files:
    print(f'  {f} kept: {"yes" if os.path.isfile(f) else "no"}')
left = previous & set(os.listdir('out/checkpoints'))
print(f'  checkpoints of the previous run left: {len(left)}')

# a case file named parameters.prm in its own output directory
os.makedirs('case', exist_ok=True)
with open(prm) as f:
    text = '# the user\'s case file, with comments\n' + f.read()
with open('case/parameters.prm', 'w') as f:
    f.write(text)
p = run([exe, 'parameters.prm', '--set', 'Output/directory=.', '--set',
         'Output/progress interval=0', '--set', 'Time stepping/max steps=5'], cwd='case')
lines = p.stderr.splitlines()
with open('case/parameters.prm') as f:
    unchanged = f.read() == text
print(f'case file parameters.prm in its output directory: exit {p.returncode}, '
      f'{len(lines)} line(s), names Output/directory: '
      f'{"yes" if lines and "Output/directory" in lines[-1] else "no"}, '
      f'file unchanged: {"yes" if unchanged else "no"}')
