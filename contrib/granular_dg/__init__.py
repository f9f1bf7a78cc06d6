"""What the scripts of contrib/ share: running granular_dg (run), reading
its outputs (outputs), comparing runs (compare), matplotlib set-up (plot)
and ParaView set-up (paraview). The scripts put contrib/ on the path by
being there; run them with Debian's /usr/bin/python3. The readers need only
the standard library and numpy."""


def parser(doc):
    """An ArgumentParser whose help is the script's docstring."""
    import argparse
    return argparse.ArgumentParser(description=doc, formatter_class=argparse.RawDescriptionHelpFormatter)
