# Branch of a two-link chain that passes change points (where its two assemblies
# cross, as a parallelogram four-bar with all pivots in line): the sketch's branch b0,
# flipped at every change point between the sketch's input value theta0 and theta.


def branch_at(theta, b0, theta0, points, periodic):
    """b0, or -b0 after an odd number of change points from theta0 to theta."""
    n = 0
    for p in points:
        if periodic:
            n += floor((theta - p) / (2 * PI)) - floor((theta0 - p) / (2 * PI))
        else:
            n += (theta >= p) - (theta0 >= p)
    return b0 if n % 2 == 0 else -b0
