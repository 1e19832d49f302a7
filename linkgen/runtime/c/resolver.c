/* Over-constraint resolver: Newton-Raphson on the Add-link lengths.
 * group(ctx, a, live, f) runs the steps of one resolver group with the Add-link
 * records a and writes the residual records f; live == 0 zeroes the rates of
 * everything the group reads, so a unit Add-link rate gives one exact Jacobian
 * column through the velocity channel.  Returns 1 when a chain cannot close. */
typedef int (*group_fn)(void *ctx, const VARIABLE a[], int live, VARIABLE f[]);

/* Solve m x = b (n <= LINKGEN_NMAX) by Gaussian elimination with partial pivoting; returns det(m). */
static double solve_linear(int n, const double m[][LINKGEN_NMAX], const double b[], double x[])
{
    double a[LINKGEN_NMAX][LINKGEN_NMAX + 1];
    double det = 1.0;
    int r, c, j;
    for (r = 0; r < n; r++) {
        for (c = 0; c < n; c++) a[r][c] = m[r][c];
        a[r][n] = b[r];
    }
    for (c = 0; c < n; c++) {
        int p = c;
        for (r = c + 1; r < n; r++) if (fabs(a[r][c]) > fabs(a[p][c])) p = r;
        if (a[p][c] == 0.0) {
            for (r = 0; r < n; r++) x[r] = NAN;
            return 0.0;
        }
        if (p != c) {
            for (j = 0; j <= n; j++) { double t = a[c][j]; a[c][j] = a[p][j]; a[p][j] = t; }
            det = -det;
        }
        det *= a[c][c];
        for (r = c + 1; r < n; r++) {
            double k = a[r][c] / a[c][c];
            for (j = c; j <= n; j++) a[r][j] -= k * a[c][j];
        }
    }
    for (r = n - 1; r >= 0; r--) {
        double s = a[r][n];
        for (j = r + 1; j < n; j++) s -= a[r][j] * x[j];
        x[r] = s / a[r][r];
    }
    return det;
}

/* Residuals and Jacobian at a, one pass per Add-link; returns 1 when a chain cannot close. */
static int jacobian(group_fn group, void *ctx, int n, const double a[], double f[], double jac[][LINKGEN_NMAX])
{
    VARIABLE rec[LINKGEN_NMAX], res[LINKGEN_NMAX];
    int i, j;
    for (j = 0; j < n; j++) {
        for (i = 0; i < n; i++) { rec[i].v = a[i]; rec[i].dv = (i == j) ? 1.0 : 0.0; rec[i].ddv = 0.0; }
        if (group(ctx, rec, 0, res)) return 1;
        for (i = 0; i < n; i++) { f[i] = res[i].v; jac[i][j] = res[i].dv; }
    }
    return 0;
}

/* |det J| over the product of its column norms (at least 1): 1 is ideal, 0 singular. */
static double conditioning(int n, const double jac[][LINKGEN_NMAX], double det)
{
    double prod = 1.0;
    int i, j;
    for (j = 0; j < n; j++) {
        double s = 0.0;
        for (i = 0; i < n; i++) s += jac[i][j] * jac[i][j];
        prod *= sqrt(s);
    }
    return fabs(det) / fmax(prod, 1.0);
}

/* Iterate the Add-link lengths until max|f| <= tol, then one step more.  A step
 * that makes a chain fail to close is halved (up to 8 times).  Returns 1 on
 * success with jac the Jacobian at the returned a. */
static int newton(group_fn group, void *ctx, int n, double a[], double tol, int max_iter,
                  double jac[][LINKGEN_NMAX], int *iterations)
{
    double f[LINKGEN_NMAX], f2[LINKGEN_NMAX], dx[LINKGEN_NMAX], trial[LINKGEN_NMAX], rhs[LINKGEN_NMAX];
    double jac2[LINKGEN_NMAX][LINKGEN_NMAX];
    int it, i, j, halving;
    *iterations = 0;
    if (jacobian(group, ctx, n, a, f, jac)) return 0;
    for (it = 1; it <= max_iter; it++) {
        double t = 1.0, worst = 0.0;
        int closed = 0;
        *iterations = it;
        for (i = 0; i < n; i++) rhs[i] = -f[i];
        if (solve_linear(n, (const double (*)[LINKGEN_NMAX])jac, rhs, dx) == 0.0) return 0;
        for (halving = 0; halving < 9; halving++) {
            for (i = 0; i < n; i++) trial[i] = a[i] + t * dx[i];
            if (!jacobian(group, ctx, n, trial, f2, jac2)) { closed = 1; break; }
            t /= 2;
        }
        if (!closed) return 0;
        for (i = 0; i < n; i++) worst = fmax(worst, fabs(f[i]));
        for (i = 0; i < n; i++) {
            a[i] = trial[i];
            f[i] = f2[i];
            for (j = 0; j < n; j++) jac[i][j] = jac2[i][j];
        }
        if (worst <= tol) return 1;
    }
    return 0;
}

/* Exact Add-link rates by the implicit-function theorem (J adot = -df/dt at adot = 0,
 * J addot = -d2f/dt2 at addot = 0, the same J), then the final pass with them.
 * Returns the status of the final pass. */
static int addlink_rates(group_fn group, void *ctx, int n, const double a[], const double jac[][LINKGEN_NMAX],
                         int order, double *sigma)
{
    VARIABLE rec[LINKGEN_NMAX], res[LINKGEN_NMAX];
    double rhs[LINKGEN_NMAX], rates[LINKGEN_NMAX], accs[LINKGEN_NMAX], det;
    int i;
    for (i = 0; i < n; i++) { rec[i].v = a[i]; rec[i].dv = 0.0; rec[i].ddv = 0.0; rhs[i] = 0.0; rates[i] = 0.0; accs[i] = 0.0; }
    if (order >= 1) {
        group(ctx, rec, 1, res);
        for (i = 0; i < n; i++) rhs[i] = -res[i].dv;
        det = solve_linear(n, jac, rhs, rates);
        if (order >= 2 && det != 0.0) {
            for (i = 0; i < n; i++) rec[i].dv = rates[i];
            group(ctx, rec, 1, res);
            for (i = 0; i < n; i++) rhs[i] = -res[i].ddv;
            solve_linear(n, jac, rhs, accs);
        } else if (det == 0.0) {
            for (i = 0; i < n; i++) accs[i] = NAN;
        }
    } else {
        det = solve_linear(n, jac, rhs, rates);
    }
    *sigma = conditioning(n, jac, det);
    for (i = 0; i < n; i++) { rec[i].v = a[i]; rec[i].dv = rates[i]; rec[i].ddv = accs[i]; }
    return group(ctx, rec, 1, res);
}
