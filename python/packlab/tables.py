"""CSV tables in the layout the command line writes (header line, ``#`` comments, 17
significant digits), so that results computed in Python feed the same ``packlab.plot``
figures as those of the command line."""

import os
import tempfile


def write_table(path, columns, comment=None):
    """Writes ``columns`` (a dict name -> 1-D array, all the same length) as a CSV table,
    atomically (temporary name, then rename). ``comment`` lines are written first, each
    prefixed with ``#``. Returns the path."""
    import numpy as np

    path = os.fspath(path)
    names = list(columns)
    arrays = [np.asarray(columns[name]) for name in names]
    n = {len(a) for a in arrays}
    if len(n) > 1:
        raise ValueError(f"write_table: columns differ in length: {dict(zip(names, map(len, arrays)))}")

    def fmt(v):
        if isinstance(v, (bool, np.bool_)):
            return "1" if v else "0"
        if isinstance(v, (int, np.integer)):
            return str(int(v))
        if isinstance(v, (str, np.str_)):
            if "," in v or "\n" in v:
                raise ValueError(f"write_table: text values cannot hold ',' or newlines: {v!r}")
            return str(v)
        return f"{float(v):.17g}"

    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=".table-", suffix=".csv", dir=folder)
    try:
        with os.fdopen(fd, "w") as f:
            if comment:
                for line in str(comment).splitlines():
                    f.write(f"# {line}\n")
            f.write(",".join(names) + "\n")
            for row in zip(*arrays):
                f.write(",".join(fmt(v) for v in row) + "\n")
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)
    return path


def read_table(path):
    """Reads a packlab CSV table into a dict of NumPy arrays (text columns stay lists)."""
    from .plot import read_csv

    return read_csv(path)
