"""What the scripts of contrib/ share: running granular_dg (run), reading
its outputs (outputs), comparing runs (compare) and matplotlib set-up (plot).
The scripts put contrib/ on the path by being there; run them with Debian's
/usr/bin/python3. The readers need only the standard library and numpy."""
import argparse
import os


def parser(doc):
    """An ArgumentParser whose help is the script's docstring."""
    return argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)


def directory(path):
    """argparse type: a directory that exists (a mistyped one would read as empty)."""
    if os.path.isdir(path):
        return path
    raise argparse.ArgumentTypeError("%s is not a directory" % path)


def add(to, spec):
    """Adds the arguments of spec to the parser `to`, each a name or (name, add_argument's keywords)."""
    for argument in spec:
        name, options = (argument, {}) if isinstance(argument, str) else argument
        to.add_argument(name, **options)
    return to


def arguments(doc, spec):
    """The parsed command line of a script without commands."""
    return add(parser(doc), spec).parse_args()


def main(doc, commands):
    """Runs the command of the command line COMMAND ARGUMENTS...: commands is
    {COMMAND: (function, spec)}; the function gets the parsed arguments."""
    top = parser(doc)
    choices = top.add_subparsers(dest="command", required=True)
    for name, (function, spec) in commands.items():
        add(choices.add_parser(name), spec).set_defaults(function=function)
    a = top.parse_args()
    from .outputs import OutputError
    try:
        a.function(a)
    except OutputError as e:  # missing or malformed outputs: one line, exit 2
        top.exit(2, "%s: error: %s\n" % (top.prog, e))
