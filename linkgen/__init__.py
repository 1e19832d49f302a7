"""linkgen: systematic kinematic analysis of closed-loop planar linkages, as code."""

__version__ = "0.1.0"
