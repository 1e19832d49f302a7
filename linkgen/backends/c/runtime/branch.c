/* Branch of a two-link chain that passes change points (where its two assemblies
 * cross, as a parallelogram four-bar with all pivots in line): the sketch's branch
 * b0, flipped at every change point between the sketch's input value theta0 and theta. */
static int branch_at(double theta, int b0, double theta0, const double points[], int n_points, int periodic)
{
    const double two_pi = 2.0 * 3.141592653589793;
    double n = 0.0;
    int k;
    for (k = 0; k < n_points; k++) {
        if (periodic) n += floor((theta - points[k]) / two_pi) - floor((theta0 - points[k]) / two_pi);
        else n += (double)(theta >= points[k]) - (double)(theta0 >= points[k]);
    }
    return fmod(n, 2.0) == 0.0 ? b0 : -b0;
}
