"""The numbers that steer extraction and the resolver, each defined once."""

from __future__ import annotations

import math

RESOLVER_TOLERANCE = 1e-10  # relative to the length scale; one Newton step is taken past it
RESOLVER_MAX_ITERATIONS = 8
CONTINUATION_HALVINGS = 20
RESOLVER_MAX_MOVE = 0.1  # relative to the length scale: farther from the start lengths is another assembly
RESOLVER_MIN_CHAIN_SIGMA = 0.05  # below it, a block's Add-links are a poor coordinate of the assembly
MAX_VARIANTS = 8  # fallback Add-link candidates per resolver group
GOOD_LEVER = 0.25  # a block that magnifies its frame angle's error more than fourfold ranks after the others
PROBE_ANGLE = math.radians(5.0)  # the paper's +5 degrees for ranking Add-link candidates
PROBE_LENGTH = 0.05  # times the length scale, for prismatic and distance inputs
MAX_MAGNITUDE = 1e30  # the largest coordinate, range bound, speed and program input, in size (file units)
LENGTH_SCALES = (1e-30, 1e30)  # the sketch sizes linkgen supports, in file units
