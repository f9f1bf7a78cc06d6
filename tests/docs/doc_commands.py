#!/usr/bin/python3
"""Every granular_dg command quoted in README.md and doc/*.md runs as written:
each is started (in a scratch directory that sees the repository's prm/,
tests/ and contrib/ and the build's program as build/granular_dg) and must
either finish with exit 0 (or the exit code its text announces, "exit code
3") or still be running after a few seconds (a long case whose input was
accepted). Bad input (exit 2) or an internal error fails the test.

usage: doc_commands.py SOURCE_DIR EXE [--seconds S]

Commands with placeholders (CASE.prm, SCENE, [...], ..., shell variables)
and --resume (which needs the run before it) are not run; the mesh
placeholder N becomes 100.
Prints the number of commands checked and whether all ran; what failed goes
to stderr.
"""
import argparse
import concurrent.futures
import glob
import os
import re
import shlex
import shutil
import subprocess
import sys
import tempfile

a = argparse.ArgumentParser()
a.add_argument('source')
a.add_argument('exe')
a.add_argument('--seconds', type=float, default=3.)
args = a.parse_args()


def commands(path):
    """(command, expected exit code) of every build/granular_dg command in a
    markdown file: code-block lines (with backslash continuations) and inline
    code spans."""
    text = open(path).read()
    found = []
    lines = text.split('\n')
    in_block, i = False, 0
    while i < len(lines):
        line = lines[i]
        if line.strip().startswith('```'):
            in_block = not in_block
        elif in_block and 'build/granular_dg ' in line:
            cmd = line[line.index('build/granular_dg'):]
            while cmd.rstrip().endswith('\\') and i + 1 < len(lines):
                i += 1
                cmd = cmd.rstrip()[:-1] + ' ' + lines[i].strip()
            found.append((cmd.split('  #')[0].strip(), line))
        elif not in_block:
            for span in re.findall(r'`([^`]*build/granular_dg [^`]*)`', line):
                found.append((span[span.index('build/granular_dg'):], line))
        i += 1
    out = []
    for cmd, context in found:
        # a number for the mesh placeholder N (Hopper/cells=N, focus_N)
        cmd = re.sub(r'=N\b', '=100', re.sub(r'_N\b', '_100', cmd))
        if re.search(r'CASE\.prm|SCENE|\[|\.\.\.|\$|--resume|\|', cmd):
            continue
        expect = 3 if 'exit code 3' in context else 0
        out.append((cmd, expect))
    return out


def run(item, scratch):
    cmd, expect = item
    argv = shlex.split(cmd)
    if argv[0] != 'build/granular_dg':
        return None
    argv[0] = args.exe
    work = tempfile.mkdtemp(dir=scratch)
    for d in ('prm', 'tests', 'contrib', 'doc'):
        os.symlink(os.path.join(args.source, d), os.path.join(work, d))
    try:
        p = subprocess.run(argv + ['--set', 'Output/progress interval=0'], cwd=work,
                           capture_output=True, text=True, timeout=args.seconds)
        code, err = p.returncode, p.stderr.strip().splitlines()
    except subprocess.TimeoutExpired:
        return None
    finally:
        shutil.rmtree(work, ignore_errors=True)
    if code == expect:
        return None
    return f'{cmd}\n    exit {code}: {err[-1] if err else ""}'


docs = [os.path.join(args.source, 'README.md')] + sorted(
    glob.glob(os.path.join(args.source, 'doc', '*.md')))
items = [c for d in docs for c in commands(d)]
scratch = tempfile.mkdtemp()
with concurrent.futures.ThreadPoolExecutor(max_workers=2) as pool:
    failures = [f for f in pool.map(lambda c: run(c, scratch), items) if f]
shutil.rmtree(scratch, ignore_errors=True)
for f in failures:
    print(f, file=sys.stderr)
print(f'commands checked: at least 20: {"yes" if len(items) >= 20 else "no"}')
print(f'all run as written: {"yes" if not failures else "no"}')
