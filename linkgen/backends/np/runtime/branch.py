# Branch of a two-link chain that passes change points (where its two assemblies cross, as a
# parallelogram four-bar with all pivots in line), on arrays of rows: the sketch's branch b0,
# flipped at every change point between the sketch's input value theta0 and theta.


def branch_at(theta, b0, theta0, points, periodic):
    """b0, or -b0 where an odd number of change points lie from theta0 to theta (an array)."""
    n = 0
    for p in points:
        if periodic:
            n = n + (np.floor((theta - p) / (2 * PI)) - np.floor((theta0 - p) / (2 * PI)))
        else:
            n = n + (np.greater_equal(theta, p).astype(int) - (theta0 >= p))
    return np.where(n % 2 == 0, b0, -b0)
