"""linkgen: systematic kinematic analysis of closed-loop planar linkages, as code."""

import os

# linkgen's linear algebra is small dense matrices: BLAS threads only add overhead
# (an SVD of the 100-dyad constraint Jacobian took 24 times longer with them on two
# busy cores).  Users who want threads can set the variable themselves.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__version__ = "0.1.0"


def __getattr__(name: str) -> object:
    """``linkgen.load`` and ``linkgen.Mechanism``: the Python API (linkgen.api), imported on first use so
    that the command line starts fast."""
    if name in ("load", "Mechanism"):
        from . import api

        return getattr(api, name)
    raise AttributeError(f"module 'linkgen' has no attribute {name!r}")
