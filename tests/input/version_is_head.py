#!/usr/bin/python3
"""--version names the git revision that was built: HEAD's short hash (with
"-dirty" when tracked files were changed at build time), taken at every
build rather than when cmake was configured. The engine and the launcher
agree. Outside a git checkout both sides are "unknown".

usage: version_is_head.py LAUNCHER ENGINE SOURCE_DIR
"""
import re
import subprocess
import sys

launcher, engine, source = sys.argv[1:4]
git = subprocess.run(['git', '-C', source, 'rev-parse', '--short', 'HEAD'],
                     capture_output=True, text=True)
head = git.stdout.strip() if git.returncode == 0 else 'unknown'
built = []
for exe in (launcher, engine):
    out = subprocess.run([exe, '--version'], capture_output=True, text=True).stdout
    m = re.search(r'\(git ([0-9a-z]+)(-dirty)?\)', out)
    built.append(m.group(1) if m else 'no revision in: ' + out.strip())
print('launcher and engine name one revision: ' + ('yes' if built[0] == built[1] else 'no ' + str(built)))
print('it is HEAD: ' + ('yes' if built[0] == head else f'no ({built[0]} built, HEAD {head})'))
