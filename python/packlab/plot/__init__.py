"""Standard figures of packlab, one module per figure (``packlab.plot.<kind>``).

Each module defines ``figure(...) -> matplotlib.figure.Figure`` for use from Python and
``main(argv)`` for the command line, which runs ``python3 -m packlab.plot KIND ARGS... --out
FILE.png`` after it wrote its CSV tables. Figures read the CSV files packlab writes.
"""

import importlib
import os
import sys
import tempfile


def read_csv(path):
    """Reads a packlab CSV table (``#`` comment lines skipped) into a dict of column lists."""
    import numpy as np

    with open(path) as f:
        lines = [line for line in f if line.strip() and not line.startswith("#")]
    header = lines[0].strip().split(",")
    rows = [line.strip().split(",") for line in lines[1:]]
    columns = {}
    for k, name in enumerate(header):
        values = [row[k] for row in rows]
        try:
            columns[name] = np.array([float(v) for v in values])
        except ValueError:
            columns[name] = values
    return columns


def save(fig, path):
    """Saves atomically (temporary name, then rename) at 150 dpi."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".plot-", suffix=os.path.splitext(path)[1], dir=folder)
    os.close(fd)
    try:
        fig.savefig(tmp, dpi=150, bbox_inches="tight")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


def new_figure(width=5.0, height=3.8):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    fig, ax = plt.subplots(figsize=(width, height), layout="constrained")
    return fig, ax


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
