#!/usr/bin/python3
"""Runs one deal.II-style test of granular_dg and compares its result with
NAME.output by numdiff.

A test runs the program (on NAME.prm or on explicit arguments), checks the
exit code, extracts what it compares (a whole output file, some CSV columns,
some summary.json keys, or the program's stderr) into NAME.result and
calls numdiff with the tolerances stated in tests/CMakeLists.txt.
Standard library only; started by ctest with Debian's /usr/bin/python3.
"""
import argparse
import csv
import json
import os
import shutil
import subprocess
import sys


def extract_columns(path, columns, skip_comments=True):
    with open(path) as f:
        lines = [l for l in f if not (skip_comments and l.startswith('#'))]
    rows = list(csv.reader(lines))
    header = rows[0]
    missing = [c for c in columns if c not in header]
    if missing:
        sys.exit(f'run_test: columns {missing} not in {path} (has {header})')
    idx = [header.index(c) for c in columns]
    out = [','.join(columns)]
    for r in rows[1:]:
        out.append(','.join(r[i] for i in idx))
    return '\n'.join(out) + '\n'


def extract_json(path, keys):
    with open(path) as f:
        data = json.load(f)
    out = []
    for key in keys:
        value = data
        for part in key.split('/'):
            value = value[part]
        if isinstance(value, list):
            value = ' '.join(repr(v) for v in value)
        out.append(f'{key} = {value}')
    return '\n'.join(out) + '\n'


def main():
    p = argparse.ArgumentParser()
    p.add_argument('--exe', required=True)
    p.add_argument('--name', required=True)
    p.add_argument('--workdir', required=True)
    p.add_argument('--expected', required=True)
    p.add_argument('--prm')
    p.add_argument('--args', default='', help='extra arguments, "|"-separated')
    p.add_argument('--expect-exit', type=int, default=0)
    p.add_argument('--compare', default='stderr',
                   help='stderr | stdout | FILE | FILE:col,col | summary.json:key,key')
    p.add_argument('--numdiff', default='', help='numdiff options, "|"-separated')
    p.add_argument('--mpi', type=int, default=0)
    p.add_argument('--expect-files', default='',
                   help='comma-separated files the (failed) run must have written, '
                        'relative to the work directory')
    p.add_argument('--copy', action='append', default=[],
                   help='a file to put into the work directory before the run')
    p.add_argument('--absent-files', default='',
                   help='comma-separated files the run must not have written')
    p.add_argument('--keep-output', action='store_true',
                   help='do not redirect the output directory (bad-input tests)')
    a = p.parse_args()

    if os.path.exists(a.workdir):
        shutil.rmtree(a.workdir)
    os.makedirs(a.workdir)
    outdir = os.path.join(a.workdir, 'out')

    for f in a.copy:
        shutil.copy(f, a.workdir)
    cmd = [a.exe]
    if a.prm:
        # run on a copy in the work directory, so messages name it as a
        # user would see it (by relative path)
        shutil.copy(a.prm, a.workdir)
        cmd.append(os.path.basename(a.prm))
    extra = [x for x in a.args.split('|') if x]
    if not a.keep_output:
        cmd += ['--set', f'Output/directory={outdir}',
                '--set', 'Output/progress interval=0']
    cmd += extra
    if a.mpi > 0:
        cmd = ['mpirun', '--allow-run-as-root', '--oversubscribe', '-np', str(a.mpi)] + cmd
    print('run_test: ' + ' '.join(f"'{c}'" if ' ' in c else c for c in cmd), flush=True)
    proc = subprocess.run(cmd, cwd=a.workdir, capture_output=True, text=True)
    sys.stdout.write(proc.stdout)
    sys.stderr.write(proc.stderr)
    if proc.returncode != a.expect_exit:
        sys.exit(f'run_test: exit code {proc.returncode}, expected {a.expect_exit}')

    present = [f for f in a.absent_files.split(',')
               if f and os.path.exists(os.path.join(a.workdir, f))]
    if present:
        sys.exit(f'run_test: the run wrote {present}, which it must not')

    result_path = os.path.join(a.workdir, a.name + '.result')
    if a.compare == 'stderr':
        # the contract: bad input gives exactly one line on stderr and
        # leaves nothing half-written in the work directory
        lines = proc.stderr.splitlines()
        if a.mpi > 0:
            # mpirun adds its own lines about the exit code
            lines = [x for x in lines if x.startswith('granular_dg')]
        if len(lines) != 1:
            sys.exit(f'run_test: expected one line on stderr, got {len(lines)}')
        if a.expect_files:
            missing = [f for f in a.expect_files.split(',')
                       if not os.path.exists(os.path.join(a.workdir, f))]
            if missing:
                sys.exit(f'run_test: the failed run did not write {missing}')
        else:
            left = [f for f in os.listdir(a.workdir)
                    if f not in [a.name + '.result', os.path.basename(a.prm or '')] +
                    [os.path.basename(c) for c in a.copy]]
            if left:
                sys.exit(f'run_test: a failed run left files behind: {left}')
        text = lines[0] + '\n'
    elif a.compare == 'stdout':
        text = proc.stdout
    else:
        target, _, selection = a.compare.partition(':')
        path = os.path.join(outdir, target)
        if not os.path.exists(path):
            sys.exit(f'run_test: the run did not write {path}')
        if not selection:
            with open(path) as f:
                text = f.read()
        elif target.endswith('.json'):
            text = extract_json(path, selection.split(','))
        else:
            text = extract_columns(path, selection.split(','))
    with open(result_path, 'w') as f:
        f.write(text)

    # @SCENES@ in the expected output stands for the program's list of
    # scenes (granular_dg --list-scenes, joined by '|'): a new scene folder
    # changes no stored output
    expected = a.expected
    with open(a.expected) as f:
        expected_text = f.read()
    if '@SCENES@' in expected_text:
        scenes = subprocess.run([a.exe, '--list-scenes'], capture_output=True, text=True,
                                check=True).stdout.split()
        expected = os.path.join(a.workdir, a.name + '.expected')
        with open(expected, 'w') as f:
            f.write(expected_text.replace('@SCENES@', '|'.join(scenes)))

    # fields are split at white space, commas and '=' (CSV, JSON-ish lines)
    nd = ['numdiff', '-q', '-s', ' \t\n,='] + [x for x in a.numdiff.split('|') if x] + [result_path, expected]
    print('run_test: ' + ' '.join(nd), flush=True)
    diff = subprocess.run(nd, capture_output=True, text=True)
    if diff.returncode != 0:
        print(subprocess.run(['numdiff'] + nd[2:], capture_output=True, text=True).stdout)
        sys.exit(f'run_test: {a.name}.result differs from {expected}')
    print(f'run_test: {a.name} passed')


if __name__ == '__main__':
    main()
