#!/usr/bin/python3
"""Smoke test of `granular_dg --benchmark`: runs it with the given arguments
(a case file and --set overrides, as tests/run_test.py passes them), then
checks that OUTPUT/benchmark.json is well formed and self-consistent and
prints what must not vary between runs (no timing values: speed is measured
by contrib/benchmark.py, never asserted in tests).

    check_benchmark.py CASE.prm [--set ...] --exe=GRANULAR_DG
"""
import json
import math
import os
import subprocess
import sys

exe = [a[6:] for a in sys.argv[1:] if a.startswith('--exe=')][-1]
args = [a for a in sys.argv[1:] if not a.startswith('--exe=')]
p = subprocess.run([exe, '--benchmark'] + args, capture_output=True, text=True)
if p.returncode != 0:
    sys.exit('granular_dg --benchmark exited with %d: %s' % (p.returncode, p.stderr.strip()))
outdir = [a.split('=', 1)[1] for a in args if a.startswith('Output/directory=')][-1]
with open(os.path.join(outdir, 'benchmark.json')) as f:
    b = json.load(f)


def check(what, ok):
    print('%s: %s' % (what, 'ok' if ok else 'FAILED'))
    return ok


good = True
positive = lambda x: isinstance(x, (int, float)) and math.isfinite(x) and x > 0
reps = b['cpu_s_per_step']
good &= check('cpu_s_per_step has one positive entry per repetition',
              len(reps) == b['repetitions'] and all(positive(x) for x in reps))
good &= check('min <= median', b['cpu_s_per_step_min'] <= b['cpu_s_per_step_median'] * (1 + 1e-12))
for key in ('step_dof_updates_per_s_per_core_best', 'step_dof_updates_per_s_per_core_median',
            'rk_dof_updates_per_s_per_core_median', 'step_dof_updates_per_s_wall_median',
            'wall_s_per_step_median'):
    good &= check(key + ' positive', positive(b[key]))
rate = b['n_dofs'] * b['n_stages'] / b['cpu_s_per_step_min']
good &= check('best rate = n_dofs * n_stages / least CPU per step',
              abs(rate / b['step_dof_updates_per_s_per_core_best'] - 1) < 1e-9)
good &= check('rk rate >= whole-step rate',
              b['rk_dof_updates_per_s_per_core_median'] >= b['step_dof_updates_per_s_per_core_median'] * (1 - 1e-9))
ph = b['phases_us_per_step_median']
good &= check('phases non-negative, operator > 0',
              all(v >= 0 for v in ph.values()) and ph['operator'] > 0)
good &= check('phases sum within the wall time per step',
              sum(ph.values()) <= 1e6 * max(b['wall_s_per_step_median'], 1e-12) * 1.5 + 1)
good &= check('load average recorded', len(b['load_before'].split()) == 3)
good &= check('no snapshots written', not any(f.endswith('.vtu') for f in os.listdir(outdir)))
print('scene = %s' % b['case']['scene'])
print('physics = %s' % b['case']['physics'])
print('engine = %s' % b['case']['engine'])
print('dim = %d, degree = %d, n_dofs = %d, n_stages = %d' % (b['case']['dim'], b['case']['degree'],
                                                            b['n_dofs'], b['n_stages']))
print('repetitions = %d, steps_per_repetition = %d' % (b['repetitions'], b['steps_per_repetition']))
sys.exit(0 if good else 1)
