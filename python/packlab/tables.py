"""CSV tables in the layout the command line writes (header line, ``#`` comments, 17
significant digits), so that results computed in Python feed the same ``packlab.plot``
figures as those of the command line."""

import contextlib
import os
import tempfile


@contextlib.contextmanager
def atomic_output(path, prefix):
    """Yields a temporary file name next to ``path`` (``prefix`` + random part + the suffix of
    ``path``) to write to; when the block completes, the file replaces ``path`` in one rename,
    and in any case no temporary file is left behind. Readers never see a half-written file."""
    path = os.fspath(path)
    folder = os.path.dirname(os.path.abspath(path))
    fd, tmp = tempfile.mkstemp(prefix=prefix, suffix=os.path.splitext(path)[1], dir=folder)
    os.close(fd)
    try:
        yield tmp
        os.replace(tmp, path)
    finally:
        if os.path.exists(tmp):
            os.remove(tmp)


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

    with atomic_output(path, ".table-") as tmp, open(tmp, "w") as f:
        if comment:
            for line in str(comment).splitlines():
                f.write(f"# {line}\n")
        f.write(",".join(names) + "\n")
        for row in zip(*arrays):
            f.write(",".join(fmt(v) for v in row) + "\n")
    return path


def read_table(path):
    """Reads a packlab CSV table into a dict of NumPy arrays (text columns stay lists)."""
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


def merged_rows(table, added, key):
    """The rows of ``table`` with those of ``added`` merged in, sorted by ``key`` (a function of
    a row): a row of ``added`` replaces the table's row with the same key, the others are kept.
    How a study run in parts (more seeds, one missing level) adds its samples to a per-sample
    table kept in docs/data."""
    rows = {key(r): r for r in table}
    rows.update({key(r): r for r in added})
    return [rows[k] for k in sorted(rows)]
