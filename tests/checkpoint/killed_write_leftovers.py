#!/usr/bin/python3
"""What a run killed while it wrote a checkpoint leaves behind does not harm
the runs after it.

usage: killed_write_leftovers.py EXE PRM      (in an empty directory)

1. Open MPI 4.1's MPI-IO takes, at every MPI_File_open on one node, a POSIX
   semaphore named after the file's base name alone (component sharedfp/sm:
   /dev/shm/sem.OMPIO_<name>). A run killed while it holds it leaves it at 0,
   and every later run that opened a file of that name (the checkpoint of the
   same step, in any directory) waited in MPI_File_open forever: a killed
   2-rank run once made every later 2D MPI checkpoint test hang at step 40.
   The launcher keeps MPI-IO off that component (source/launcher.cc). Here
   the semaphore of the step-10 checkpoint is left taken, as such a kill
   leaves it (glibc's sem_t: 32 bytes, value 0, no waiters), and PRM runs on
   2 ranks to a checkpoint at step 10, with a deadline. This fails, by the
   deadline, when the component is in use again (try OMPI_MCA_sharedfp=sm in
   the environment).
2. The partial file of a killed write (.step-N.ckpt.tmp) and the files
   MPI-IO keeps beside it (.step-N.ckpt.tmp-JOB-PID.lock, and
   .step-N.ckpt.tmp.locktest.R while it tests file locking) are removed when
   the resumed run writes its next checkpoint; a file of the user's that
   only looks similar (.notes.lock) stays.
"""
import os
import signal
import subprocess
import sys

exe, prm = sys.argv[1], sys.argv[2]
semaphore = '/dev/shm/sem.OMPIO_.step-0000000010.ckpt.tmp'
deadline = 120  # seconds; each run takes about 2


def run(label, *extra):
    command = ['mpirun', '--allow-run-as-root', '--oversubscribe', '-np', '2', exe, prm,
               '--set', f'Output/directory={os.path.abspath("out")}',
               '--set', 'Output/progress interval=0', '--set', 'Checkpoint/every steps=10',
               '--set', 'Time stepping/final time=2',
               '--set', 'Output/output times=0.5, 1, 1.5'] + list(extra)
    p = subprocess.Popen(command, stdout=subprocess.DEVNULL, stderr=subprocess.PIPE, text=True,
                         start_new_session=True)
    try:
        _, err = p.communicate(timeout=deadline)
        print(f'{label}: exit {p.returncode}')
        if p.returncode != 0:
            print(err, file=sys.stderr)
    except subprocess.TimeoutExpired:
        os.killpg(p.pid, signal.SIGKILL)
        subprocess.run(['pkill', '-KILL', '-f', 'Output/directory=' + os.path.abspath('out')])
        p.communicate()
        print(f'{label}: still running after {deadline} s (killed): the checkpoint waits '
              'for the semaphore')
    left = sorted(os.listdir('out/checkpoints')) if os.path.isdir('out/checkpoints') else []
    print(f'  files in checkpoints/: {" ".join(left) if left else "none"}')


with open(semaphore, 'wb') as f:
    f.write(bytes(32))
try:
    run('run to step 10 on 2 ranks, the semaphore of its checkpoint taken',
        '--set', 'Time stepping/max steps=10')
finally:
    os.remove(semaphore)

for name in ['.step-0000000015.ckpt.tmp', '.step-0000000015.ckpt.tmp-4242-4242.lock',
             '.step-0000000015.ckpt.tmp.locktest.1', '.notes.lock']:
    with open(os.path.join('out/checkpoints', name), 'w') as f:
        f.write('left by a killed write\n')
run('resumed to step 20, a killed write\'s files beside the checkpoint',
    '--set', 'Time stepping/max steps=20', '--set', 'Checkpoint/resume=true')
