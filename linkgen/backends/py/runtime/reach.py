# Whether a mechanism with one input reaches an input value from the sketch: the values
# between the middles of the nearest gaps where a chain cannot close, an angle modulo whole
# turns.  Past a gap a chain can close again, on another circuit of the mechanism.


def reach_at(theta, low, high, periodic):
    """0 where theta is reached, -1 past the gap below, 1 past the gap above (for an angle,
    the nearer of the two); a nan bound: no gap on that side."""
    if periodic:
        t = theta - 2 * PI * floor((theta - low) / (2 * PI))
        if t < high:
            return 0
        return 1 if t - high <= low + 2 * PI - t else -1
    if theta <= low:
        return -1
    if theta >= high:
        return 1
    return 0
