"""packlab: random sphere packings, their microstructure and DEM load tests.

The plotting helpers live in ``packlab.plot``; the compiled core (``packlab._core``) is added
by the Python-module work and re-exported here when it is built.
"""

__all__ = ["plot"]

try:  # the compiled extension is optional: plots work without it
    from ._core import *  # noqa: F401,F403
except ImportError:  # pragma: no cover - depends on the build
    pass
