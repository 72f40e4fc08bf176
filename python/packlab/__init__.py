"""packlab: random sphere packings, their microstructure and DEM load tests.

The compiled core (``packlab._core``, pybind11) provides Packing, read/write, the generators,
the analyses and the DEM engine with NumPy arrays; it is re-exported here when it is built.
The standard figures live in ``packlab.plot`` (matplotlib, pure Python: they work without
the compiled core). Set ``PYTHONPATH=<repo>/python:<build>/python``; see docs/python.md.
"""

import pkgutil as _pkgutil

# The pure-Python files (<repo>/python/packlab) and the compiled core (<build>/python/packlab)
# live in two folders of the same package: let the package span every `packlab` folder on
# sys.path.
__path__ = _pkgutil.extend_path(__path__, __name__)

__all__ = ["plot", "tables"]

try:  # the compiled extension is optional: plots work without it
    from ._core import *  # noqa: F401,F403
    from ._core import __version__  # noqa: F401

    __all__ += [name for name in dir(_core) if not name.startswith("_")]  # noqa: F405
    _core_error = None
except ImportError as _error:  # pragma: no cover - depends on the build
    _core_error = _error

from .tables import read_table, write_table  # noqa: E402,F401

__all__ += ["read_table", "write_table", "study"]


def __getattr__(name):
    # packlab.study (parameter studies, docs/study.md) is imported on first use: importing it
    # here would load packlab.studies before `python3 -m packlab.studies` (the runner that
    # `packlab study` starts) executes it, which runpy warns about.
    if name == "study":
        from .studies import study

        return study
    raise AttributeError(f"module 'packlab' has no attribute '{name}'")
