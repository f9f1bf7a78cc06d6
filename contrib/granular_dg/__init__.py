"""What the scripts of contrib/ share: running granular_dg (run), reading
its outputs (outputs), comparing runs (compare) and matplotlib set-up (plot).
The scripts put contrib/ on the path by being there; run them with Debian's
/usr/bin/python3. The readers need only the standard library and numpy."""


def parser(doc):
    """An ArgumentParser whose help is the script's docstring."""
    import argparse
    return argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)


def main(doc, commands):
    """Runs the command of the command line COMMAND ARGUMENTS...: commands is
    {COMMAND: (function, arguments)}, each argument a name or (name,
    add_argument's keywords); the function gets the parsed arguments."""
    sub = parser(doc)
    choices = sub.add_subparsers(dest="command", required=True)
    for name, (function, arguments) in commands.items():
        command = choices.add_parser(name)
        command.set_defaults(function=function)
        for argument in arguments:
            name, options = (argument, {}) if isinstance(argument, str) else argument
            command.add_argument(name, **options)
    a = sub.parse_args()
    a.function(a)
