#!/usr/bin/python3
"""The troubled-cell indicator on a shock: prm/elasticity_shock.prm (a
compressive pulse that steepens into a shock, P2, 1200 cells, characteristic
limiter) with Limiter/indicator = modal_energy (default) or kxrcf.

usage: shock_cells.py EXE PRM [--indicator modal_energy|kxrcf|modal_energy_neighbours]
                      [--threshold T] [--max-flagged N]
                      [--count flagged_cells|blended_cells] [--set ...]

Prints, per output time, whether the indicator flagged some cells and no more
than N (a handful around the shock, where the limiter in every cell finds
hundreds of troubled cells), and whether the limited solution has no
overshoot: strain >= -0.01 (the undisturbed state is 0, the pulse is
compressive: strain > 0) at every output time. A flagged set that missed the
shock would leave the shock's oscillations in place. The counts go to stderr.
The indicator runs with its automatic threshold unless --threshold T is
given (the shipped case sets its own: prm/elasticity_shock.prm).
With --count blended_cells the cells subcell blending acts on are counted
instead (Limiter/subcell blending), and the largest strain of the run must
stay within 1 % of the reference plateau 0.3567 (9600 cells) as well.
"""
import argparse
import csv
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), '..', 'common'))
import granular_run  # noqa: E402

a = argparse.ArgumentParser()
a.add_argument('exe')
a.add_argument('prm')
a.add_argument('--indicator', default='modal_energy')
a.add_argument('--threshold', default='0')
a.add_argument('--max-flagged', type=int, default=12)
a.add_argument('--count', default='flagged_cells')
a.add_argument('--set', action='append', default=[])
args = a.parse_args()

summary = granular_run.run(args.exe, args.prm, 'run',
                 ['Limiter/indicator=' + args.indicator,
                  'Limiter/indicator threshold=' + args.threshold, 'Output/write vtu=false'] +
                 args.set)
with open('run/timeseries.csv') as f:
    rows = list(csv.DictReader(f))
for r in rows[1:]:
    flagged, troubled = int(float(r[args.count])), int(float(r['troubled_cells']))
    ok = 1 <= flagged <= args.max_flagged
    print(f't = {float(r["time"]):g}: {args.count.replace("_", " ")} in [1, {args.max_flagged}]: '
          f'{"yes" if ok else "no"}; min strain >= -0.01: '
          f'{"yes" if float(r["min_strain"]) >= -0.01 else "no"}')
    print(f't = {r["time"]}: flagged {flagged}, troubled {troubled}, '
          f'strain [{r["min_strain"]}, {r["max_strain"]}]', file=sys.stderr)
print(f'max strain over the run: {summary["diagnostics"]["max_strain"]:.4f}', file=sys.stderr)
if args.count == 'blended_cells':
    print('max strain over the run within 1 % of the plateau 0.3567: ' +
          ('yes' if abs(summary['diagnostics']['max_strain'] / 0.3567 - 1) <= 0.01 else 'no'))
