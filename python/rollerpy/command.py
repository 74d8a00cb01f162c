"""The option parser every command starts from: `rollerpy NAME` in its usage, the command's
docstring as written in its --help."""
import argparse


def parser(name, doc):
    return argparse.ArgumentParser(prog="rollerpy " + name, description=doc,
                                   formatter_class=argparse.RawDescriptionHelpFormatter)
