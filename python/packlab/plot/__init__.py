"""Standard figures of packlab, one module per figure (``packlab.plot.<kind>``).

Each module defines ``figure(...) -> matplotlib.figure.Figure`` for use from Python and
``main(argv)`` for the command line, which runs ``python3 -m packlab.plot KIND ARGS... --out
FILE.png`` after it wrote its CSV tables. Figures read the CSV files packlab writes.
"""

import importlib
import sys

from packlab.plot._common import new_figure, read_csv, save  # noqa: F401 (the public helpers)


def main(argv=None):
    argv = list(sys.argv[1:] if argv is None else argv)
    if not argv or argv[0] in ("-h", "--help"):
        print("usage: python3 -m packlab.plot KIND ARGS... --out FILE.png")
        return 0
    kind = argv.pop(0)
    try:
        module = importlib.import_module(f"packlab.plot.{kind}")
    except ModuleNotFoundError:
        print(f"packlab.plot: unknown figure '{kind}'", file=sys.stderr)
        return 2
    return module.main(argv)
