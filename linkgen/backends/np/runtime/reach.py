# Whether a mechanism with one input reaches its input values from the sketch, on arrays of
# rows: the values between the middles of the nearest gaps where a chain cannot close, an
# angle modulo whole turns.  Past a gap a chain can close again, on another circuit.


def reach_at(theta, low, high, periodic):
    """0 where theta (an array) is reached, -1 past the gap below, 1 past the gap above (for
    an angle, the nearer of the two); a nan bound: no gap on that side."""
    if periodic:
        t = theta - 2 * PI * np.floor((theta - low) / (2 * PI))
        return np.where(t < high, 0, np.where(t - high <= low + 2 * PI - t, 1, -1))
    return np.where(theta <= low, -1, np.where(theta >= high, 1, 0))
