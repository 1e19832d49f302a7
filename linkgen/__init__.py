"""linkgen: systematic kinematic analysis of closed-loop planar linkages, as code."""

import os

# linkgen's linear algebra is small dense matrices: BLAS threads only add overhead
# (an SVD of the 100-dyad constraint Jacobian took 24 times longer with them on two
# busy cores).  Users who want threads can set the variable themselves.
os.environ.setdefault("OPENBLAS_NUM_THREADS", "1")

__version__ = "0.1.0"
