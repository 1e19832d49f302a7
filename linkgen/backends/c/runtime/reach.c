/* Whether a mechanism with one input reaches an input value from the sketch: the values
 * between the middles of the nearest gaps where a chain cannot close, an angle modulo
 * whole turns.  Past a gap a chain can close again, on another circuit of the mechanism.
 * Returns 0 where theta is reached, -1 past the gap below, 1 past the gap above (for an
 * angle, the nearer of the two); a nan bound: no gap on that side. */
static int reach_at(double theta, double low, double high, int periodic)
{
    const double two_pi = 2.0 * 3.141592653589793;
    if (periodic) {
        const double t = theta - two_pi * floor((theta - low) / two_pi);
        if (t < high) return 0;
        return t - high <= low + two_pi - t ? 1 : -1;
    }
    if (theta <= low) return -1;
    if (theta >= high) return 1;
    return 0;
}
