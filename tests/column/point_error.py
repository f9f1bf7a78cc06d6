#!/usr/bin/python3
"""The shipped shock capturing of prm/column_m1.prm against the
exact solution of the linear case: the same prm on (0, 5) at its dx = 0.025
(200 P2 cells) to t = 4.

usage: point_error.py EXE PRM

Prints the error of the strain at (z, t) = (3, 4) against the closed form
(u(3, 4) = -0.147769340095, printed by the column/closed_form test), and
whether v = 0 exactly in every stuck cell. The .output holds 1.2725e-4 with
that as numdiff's absolute tolerance, so the test passes iff the error is in
[0, 2.545e-4]: at most half of the 5.09e-4 that the limiter in every cell
leaves there (doc/column.md).
"""
import argparse
import os
import sys

import numpy as np

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import granular_run  # noqa: E402

EXACT_STRAIN_3_4 = -0.147769340095

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
args = a.parse_args()

summary = granular_run.run(args.exe, args.prm, 'run',
                           ['Mesh/length=5', 'Mesh/cells=200', 'Time stepping/final time=4',
                            'Output/output times=', 'Output/write vtu=false',
                            'Output/profile points per cell=3', 'Output/overwrite=true'])
# profile-0000.csv is t = 0, profile-0001.csv the final time
d = np.genfromtxt('run/profile-0001.csv', delimiter=',', skip_header=1, names=True)
at = np.isclose(d['x'], 3., atol=1e-9)
error = abs(float(np.mean(d['strain'][at])) - EXACT_STRAIN_3_4)
print(f'error of the strain at (3, 4): {error:.4e}')
print('v = 0 in every stuck cell: ' +
      ('1' if summary['diagnostics']['max_stuck_velocity'] == 0 else '0'))
