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
        for (i = 0; i < n; i++) {
            rec[i].v = a[i];
            rec[i].dv = (i == j) ? 1.0 : 0.0;
#if LINKGEN_ORDER >= 2
            rec[i].ddv = 0.0;
#endif
        }
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
 * that makes a chain fail to close is halved (up to 3 times; then the block
 * fails and the next block is tried).  A solution farther than reach from the
 * start is another assembly and refused.  Returns 1 on success with jac the
 * Jacobian at the returned a. */
static int newton(group_fn group, void *ctx, int n, double a[], double tol, int max_iter, double reach,
                  double jac[][LINKGEN_NMAX], int *iterations)
{
    double start[LINKGEN_NMAX];
    double f[LINKGEN_NMAX], f2[LINKGEN_NMAX], dx[LINKGEN_NMAX], trial[LINKGEN_NMAX], rhs[LINKGEN_NMAX];
    double jac2[LINKGEN_NMAX][LINKGEN_NMAX];
    int it, i, j, halving;
    *iterations = 0;
    for (i = 0; i < n; i++) start[i] = a[i];
    if (jacobian(group, ctx, n, a, f, jac)) return 0;
    for (it = 1; it <= max_iter; it++) {
        double t = 1.0, worst = 0.0;
        int closed = 0;
        *iterations = it;
        for (i = 0; i < n; i++) rhs[i] = -f[i];
        if (solve_linear(n, (const double (*)[LINKGEN_NMAX])jac, rhs, dx) == 0.0) return 0;
        for (halving = 0; halving < 4; halving++) {
            for (i = 0; i < n; i++) trial[i] = a[i] + t * dx[i];
            if (!jacobian(group, ctx, n, trial, f2, jac2)) { closed = 1; break; }
            t /= 2;
        }
        if (!closed) return 0;
        for (i = 0; i < n; i++)
            if (!(fabs(f[i]) <= worst)) worst = fabs(f[i]); /* a nan stays (fmax would drop it) */
        for (i = 0; i < n; i++) {
            a[i] = trial[i];
            f[i] = f2[i];
            for (j = 0; j < n; j++) jac[i][j] = jac2[i][j];
        }
        if (worst <= tol) {
            double moved = 0.0;
            for (i = 0; i < n; i++)
                if (!(fabs(a[i] - start[i]) <= moved)) moved = fabs(a[i] - start[i]);
            return moved <= reach;
        }
    }
    return 0;
}

/* Exact Add-link rates by the implicit-function theorem (J adot = -df/dt at adot = 0),
 * at order 2 the accelerations too (J addot = -d2f/dt2 at addot = 0, the same J), then
 * the final pass with them.  The rates are found at every order (they start the next
 * row).  *turn is the block's orientation, the sign of det J: it stays the same along the
 * assembly while the block's chains keep their branches (it changes only at a singular
 * position; a solution of the other sign is another assembly).  Returns the status of
 * the final pass. */
static int addlink_rates(group_fn group, void *ctx, int n, const double a[], const double jac[][LINKGEN_NMAX],
                         int order, double *sigma, double *turn)
{
    VARIABLE rec[LINKGEN_NMAX], res[LINKGEN_NMAX];
    double rhs[LINKGEN_NMAX], rates[LINKGEN_NMAX], det;
    int i;
    memset(rec, 0, sizeof rec);  /* entries past n are never read; zeroed for the compiler's sake */
    memset(rhs, 0, sizeof rhs);
    for (i = 0; i < n; i++) {
        rec[i].v = a[i];
        rec[i].dv = 0.0;
#if LINKGEN_ORDER >= 2
        rec[i].ddv = 0.0;
#endif
    }
    group(ctx, rec, 1, res);
    for (i = 0; i < n; i++) rhs[i] = -res[i].dv;
    det = solve_linear(n, jac, rhs, rates);
    for (i = 0; i < n; i++) rec[i].dv = rates[i];
#if LINKGEN_ORDER >= 2
    if (order >= 2) {
        double accs[LINKGEN_NMAX];
        group(ctx, rec, 1, res);
        for (i = 0; i < n; i++) rhs[i] = -res[i].ddv;
        solve_linear(n, jac, rhs, accs);
        for (i = 0; i < n; i++) rec[i].ddv = det != 0.0 ? accs[i] : NAN;
    }
#else
    (void)order;
#endif
    *sigma = conditioning(n, jac, det);
    *turn = det > 0.0 ? 1.0 : det < 0.0 ? -1.0 : 0.0;
    return group(ctx, rec, 1, res);
}

/* Newton on a group's blocks (its chosen Add-link candidate, then the fallbacks), the
 * preferred block first, the others in order.  The first that converges with its chains
 * conditioned at least min_sigma (*chains: the worst of the last pass, from the block's
 * lever down) is kept; else the best conditioned of those that converge, a later block
 * only when more than twice as well conditioned (a block whose chains are near a toggle
 * is a poor coordinate of the assembly; blocks that share that chain tie up to rounding,
 * and the order, not the rounding, decides).  a[k] holds block k's start lengths; the caller then
 * measures every block's state on the solved pairs.  Returns the block, or -1 when none
 * converges; *turn is its orientation (see addlink_rates). */
static int resolve_variants(const group_fn fns[], const int sizes[], int count, void *ctx, double a[][LINKGEN_NMAX],
                            double tol, int max_iter, double reach, int order, int prefer, int *its, double *sigma,
                            double *turn, const double *chains, double min_sigma)
{
    double jac[LINKGEN_NMAX][LINKGEN_NMAX], x[LINKGEN_NMAX], best_sigma = -1.0;
    int t, k, i, best = -1;
    for (t = 0; t < count; t++) {
        k = t == 0 ? prefer : (t - 1 < prefer ? t - 1 : t);
        for (i = 0; i < sizes[k]; i++) x[i] = a[k][i];
        if (!newton(fns[k], ctx, sizes[k], x, tol, max_iter, reach, jac, its)) continue;
        if (*chains < min_sigma) {
            if (*chains > 2.0 * best_sigma) {
                best_sigma = *chains;
                best = k;
            }
            continue;
        }
        if (addlink_rates(fns[k], ctx, sizes[k], x, (const double (*)[LINKGEN_NMAX])jac, order, sigma, turn) != 1)
            return k;
    }
    if (best < 0) return -1;
    for (i = 0; i < sizes[best]; i++) x[i] = a[best][i];
    if (newton(fns[best], ctx, sizes[best], x, tol, max_iter, reach, jac, its)
        && addlink_rates(fns[best], ctx, sizes[best], x, (const double (*)[LINKGEN_NMAX])jac, order, sigma, turn) != 1)
        return best;
    return -1;
}

/* Whether a solved state is where the predictor pointed from prev: no block's Add-link
 * length moved from the guess by more than a tenth of the largest predicted move (plus
 * slack); a larger correction is a jump to another assembly, or a step too long for the
 * curve.  A block that solved both and turned its orientation (the state's last entry,
 * after its sizes[k] lengths and its branches; 0 where the block did not solve) has passed
 * a singular position.  Where two assemblies pass close the nearer one can lie within the
 * tenth, so a turned block must be within a hundredth: the path crosses the singular
 * position along its tangent, as a mechanism goes straight through a change point. */
static int on_path(const double prev[][LINKGEN_NMAX], const double guess[][LINKGEN_NMAX],
                   const double now[][LINKGEN_NMAX], const int sizes[], double slack)
{
    double move = 0.0, share = 0.1;
    int g, i;
    for (g = 0; g < LINKGEN_NBLOCKS; g++) {
        for (i = 0; i < sizes[g]; i++) move = fmax(move, fabs(guess[g][i] - prev[g][i]));
        if (prev[g][LINKGEN_NMAX - 1] * now[g][LINKGEN_NMAX - 1] < 0.0) share = 0.01;
    }
    for (g = 0; g < LINKGEN_NBLOCKS; g++)
        for (i = 0; i < sizes[g]; i++)
            if (!(fabs(now[g][i] - guess[g][i]) <= share * move + slack)) return 0; /* a nan too */
    return 1;
}

/* Whether no input moved farther from the last row than a continuation step. */
static int within(const double in[], const double last[], const double limits[])
{
    int i;
    for (i = 0; i < LINKGEN_NINPUTS; i++)
        if (!(fabs(in[i] - last[i]) <= limits[i])) return 0;
    return 1;
}

/* Block states a moved by step along their rates into out.  An Add-link length is a
 * distance: where its prediction passes zero the two pairs pass each other, so it is
 * reflected. */
static void advance(const double a[][LINKGEN_NMAX], const double rate[][LINKGEN_NMAX], double step,
                    const int sizes[], double out[][LINKGEN_NMAX])
{
    int g, i;
    for (g = 0; g < LINKGEN_NBLOCKS; g++)
        for (i = 0; i < LINKGEN_NMAX; i++) {
            out[g][i] = a[g][i] + step * rate[g][i];
            if (i < sizes[g]) out[g][i] = fabs(out[g][i]);
        }
}

/* Resolver start values for new inputs: the warm states advanced along their rates
 * (first-order Taylor in the warm row's input direction; the rates exist at every
 * order, so the positions do not depend on the order computed). */
static void predict(const double w_in[], const double w_din[], const double w_a[][LINKGEN_NMAX],
                    const double w_ad[][LINKGEN_NMAX], const double in[], const int sizes[],
                    double a[][LINKGEN_NMAX])
{
    double num = 0.0, den = 0.0;
    int i;
    for (i = 0; i < LINKGEN_NINPUTS; i++) {
        num += (in[i] - w_in[i]) * w_din[i];
        den += w_din[i] * w_din[i];
    }
    advance(w_a, w_ad, den > 0.0 ? num / den : 0.0, sizes, a);
}

/* One pass of the procedure along a continuation path: returns 1 when it closes,
 * with the Add-link lengths a (in: start values) and their rates along the path. */
typedef int (*path_fn)(void *ctx, const double in[], const double din[], int order, double a[][LINKGEN_NMAX],
                       double rates[][LINKGEN_NMAX]);

/* A walk gives up after this many passes of the procedure. */
#define LINKGEN_WALK_PASSES 1000

/* Continuation along the straight path from base to goal (see continuation).  Near a
 * singular position the lengths' rates are large and the steps short (the prediction
 * holds only there); a step that makes no progress in floating point cuts the path, and
 * so do LINKGEN_WALK_PASSES passes (at once where the path needs more steps than that). */
static int walk(path_fn run, void *ctx, const double base[], double a[][LINKGEN_NMAX], const double goal[],
                const double limits[], int halvings, const int sizes[], double slack, double reach)
{
    double d[LINKGEN_NINPUTS], trial[LINKGEN_NINPUTS], start[LINKGEN_NBLOCKS][LINKGEN_NMAX];
    double rate[LINKGEN_NBLOCKS][LINKGEN_NMAX], guess[LINKGEN_NBLOCKS][LINKGEN_NMAX];
    double now[LINKGEN_NBLOCKS][LINKGEN_NMAX], rate2[LINKGEN_NBLOCKS][LINKGEN_NMAX];
    double t = 0.0, h, h_max = 1.0, fast;
    int g, i, cuts = 0, passes = 1;
    for (i = 0; i < LINKGEN_NINPUTS; i++) {
        d[i] = goal[i] - base[i];
        if (d[i] != 0.0) h_max = fmin(h_max, limits[i] / fabs(d[i]));
    }
    if (h_max * LINKGEN_WALK_PASSES < 1.0) return 0;
    for (g = 0; g < LINKGEN_NBLOCKS; g++)
        for (i = 0; i < LINKGEN_NMAX; i++) start[g][i] = a[g][i];
    if (!run(ctx, base, d, 1, start, rate)) return 0;
    h = h_max;
    while (t < 1.0) {
        double tt;
        if (passes++ == LINKGEN_WALK_PASSES) return 0;
        fast = 0.0;
        for (g = 0; g < LINKGEN_NBLOCKS; g++)
            for (i = 0; i < sizes[g]; i++) fast = fmax(fast, fabs(rate[g][i]));
        if (fast * h > reach) h = reach / fast;
        tt = fmin(1.0, t + h);
        if (tt == t) return 0;
        for (i = 0; i < LINKGEN_NINPUTS; i++) trial[i] = tt < 1.0 ? base[i] + tt * d[i] : goal[i];
        advance((const double (*)[LINKGEN_NMAX])start, (const double (*)[LINKGEN_NMAX])rate, tt - t, sizes, guess);
        for (g = 0; g < LINKGEN_NBLOCKS; g++)
            for (i = 0; i < LINKGEN_NMAX; i++) now[g][i] = guess[g][i];
        if (run(ctx, trial, d, 1, now, rate2)
            && on_path((const double (*)[LINKGEN_NMAX])start, (const double (*)[LINKGEN_NMAX])guess,
                       (const double (*)[LINKGEN_NMAX])now, sizes, slack)) {
            t = tt;
            h = fmin(2.0 * h, h_max);
            cuts = 0;
            for (g = 0; g < LINKGEN_NBLOCKS; g++)
                for (i = 0; i < LINKGEN_NMAX; i++) { start[g][i] = now[g][i]; rate[g][i] = rate2[g][i]; }
        } else {
            h /= 2.0;
            if (++cuts > halvings) return 0;
        }
    }
    for (g = 0; g < LINKGEN_NBLOCKS; g++)
        for (i = 0; i < LINKGEN_NMAX; i++) a[g][i] = start[g][i];
    return 1;
}

/* Follow the assembly from inputs base (solved with block states a) to target.  Angle
 * inputs go the shorter way round, else the other way; where the one input is an angle
 * with a reach (the values it reaches from the sketch, modulo whole turns, from low up; low
 * is nan without one; base and target are inside it), it goes the one way round that stays
 * inside the reach.  A step moves no input by more than its limit and no Add-link length,
 * as predicted, by more than reach; it starts Newton from the tangent predictor and is
 * halved where Newton fails or lands off the path (see on_path), up to halvings times in a
 * row.  Returns 1 with a the block states at target, 0 when the way (both ways without a
 * reach) is cut. */
static int continuation(path_fn run, void *ctx, const double base[], double a[][LINKGEN_NMAX], const double target[],
                        const double limits[], const int periodic[], int halvings, const int sizes[], double slack,
                        double reach, double low)
{
    const double two_pi = 2.0 * 3.141592653589793;
    double goal[LINKGEN_NINPUTS], other[LINKGEN_NINPUTS];
    int i, differs = 0;
    if (periodic[0] && !isnan(low)) {
        for (i = 0; i < LINKGEN_NINPUTS; i++) goal[i] = target[i];
        goal[0] = base[0] + (target[0] - two_pi * floor((target[0] - low) / two_pi))
                  - (base[0] - two_pi * floor((base[0] - low) / two_pi));
        return walk(run, ctx, base, a, goal, limits, halvings, sizes, slack, reach);
    }
    for (i = 0; i < LINKGEN_NINPUTS; i++) {
        goal[i] = periodic[i] ? target[i] - two_pi * floor((target[i] - base[i]) / two_pi + 0.5) : target[i];
        other[i] = goal[i];
        if (periodic[i] && goal[i] != base[i]) {
            other[i] = goal[i] > base[i] ? goal[i] - two_pi : goal[i] + two_pi;
            differs = 1;
        }
    }
    if (walk(run, ctx, base, a, goal, limits, halvings, sizes, slack, reach)) return 1;
    return differs && walk(run, ctx, base, a, other, limits, halvings, sizes, slack, reach);
}
