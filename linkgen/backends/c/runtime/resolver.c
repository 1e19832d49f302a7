/* Over-constraint resolver: the strategy's iteration on the Add-link lengths (Newton-Raphson,
 * the paper's, or fixed-point iteration with the slope of the row's start), then exact rates.
 * group(ctx, a, da, dda, live, f, df, ddf) runs the steps of one resolver group with the
 * Add-link lengths a, their rates da and accelerations dda, and writes the residuals f and
 * their rates df and accelerations ddf (those of the program's order; a null ddf asks for no
 * accelerations: the passes that measure residuals and the Jacobian); live == 0 zeroes
 * the rates of everything the group reads, so a unit Add-link rate gives one exact
 * Jacobian column through the velocity channel; live == 2 measures that column and the
 * residuals' rates at zero Add-link rate (reads live) at once, into df and ddf, and keeps its
 * positions' values; live == 3 is live == 1 at the a of that pass, from the values it kept
 * (the same bits, without the positions' work).  Returns 1 when a chain cannot close. */
typedef int (*group_fn)(void *ctx, const double a[], const double da[], const double dda[], int live, double f[],
                        double df[], double ddf[]);

/* The sensitivities of the records a block writes to its Add-links: with keep, their rates as a
 * Jacobian pass (unit Add-link rate, reads still) leaves them, into s in the order the block writes
 * them; else acc times s added to their accelerations (which are linear in the Add-links' ones). */
typedef void (*bend_fn)(void *ctx, double s[], double acc, int keep);

/* Block k's branches (of a group's blocks) into the work from the signs of its state s: called before
 * the resolver tries the block, so a fallback block's are set only where it is tried. */
typedef void (*branches_fn)(void *ctx, int k, const double s[]);

/* The states and rates of the blocks of one group read off the solved pairs: every block's where only
 * is negative, else block only's and the loop blocks' (the others' states are stale: nan, orientation 0;
 * their rates are left as they are); a and ad never alias the work (LINKGEN_RESTRICT: C99's restrict, which C++ has not; the same operations). */
#if defined(__cplusplus)
#define LINKGEN_RESTRICT
#else
#define LINKGEN_RESTRICT restrict
#endif
typedef void (*lengths_fn)(const void *ctx, int only, double a[LINKGEN_RESTRICT][LINKGEN_NMAX],
                           double ad[LINKGEN_RESTRICT][LINKGEN_NMAX]);

/* The resolver strategies (options: strategy), as resolver_policy.strategy names them. */
enum { RESOLVER_NEWTON, RESOLVER_FIXED_POINT, RESOLVER_CLOSURE, RESOLVER_LOOP };

/* The resolver policy (linkgen/policy.py, as the step log has it, with the strategy, polish and
 * predictor of the build's options); lengths relative to the length scale. */
typedef struct {
    double tolerance;     /* the iteration stops once every residual is at most this (after one step more: polish) */
    int max_iterations;   /* iterations at most, a polishing one too */
    int newton_halvings;  /* a Newton step that makes a chain fail to close is halved at most this often */
    double max_move;      /* a solution farther from its start is another assembly; a continuation step's limit */
    double min_chain_sigma;  /* a block whose chains are worse conditioned yields to a better one */
    int max_halvings;     /* a continuation step is halved at most this often in a row */
    double path_slack;    /* how far a solution may sit off the predicted path beyond its share of the move */
    double path_share;    /* ... its share of the largest predicted move */
    double turn_share;    /* ... where a block's orientation turned */
    int walk_passes;      /* a continuation walk gives up after this many passes */
    int strategy;         /* the resolver's iteration: RESOLVER_NEWTON, _FIXED_POINT, _CLOSURE or _LOOP */
    int polish;           /* 1: one step more once the tolerance is met */
    int predictor;        /* the warm start's order: 0, 1 or 2 */
} resolver_policy;

/* What the resolver and the row driver need of the mechanism. */
typedef struct {
    double length_scale;
    const double *sketch_in;  /* the sketch's inputs */
    const double (*sketch_a)[LINKGEN_NMAX];  /* per block: lengths, branches, orientation in the sketch */
    const int *sizes;  /* Add-links of each block */
    const int *loops;  /* 1: a loop block (strategy loop iterates it by loop_iteration) */
    const int *firsts;  /* each group's first block */
    const double *limits;  /* the continuation's largest step of each input */
    const int *periodic;  /* angle inputs: the continuation goes the shorter way round */
    double low;  /* where the reach of an angle input starts (nan: no reach) */
    int another;  /* the code of a row solvable on another assembly only */
    int not_converged;  /* a row failed with this reason is followed from the last one */
} resolver_mechanism;

/* A block's Add-links: n, known to be 1 where no block has more (LINKGEN_NADD, the most), so the compiler
 * drops the loops over them (the same operations). */
static int adds(int n)
{
    return LINKGEN_NADD == 1 ? 1 : n;
}

/* Solve m x = b (n <= LINKGEN_NMAX) by Gaussian elimination with partial pivoting; returns det(m). */
static double solve_linear(int n, const double m[][LINKGEN_NMAX], const double b[], double x[])
{
    double a[LINKGEN_NMAX][LINKGEN_NMAX + 1];
    double det = 1.0;
    int r, c, j;
    if (n == 1) {  /* one Add-link: the same operations as below, without the copies */
        x[0] = m[0][0] == 0.0 ? NAN : b[0] / m[0][0];
        return m[0][0];
    }
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

/* Residuals and Jacobian at a, one pass per Add-link, the last one (ft not null) with the residuals'
 * rates at zero Add-link rate, the reads live, into ft (group's live 2: the rates pass after the
 * iteration then has them); returns 1 when a chain cannot close. */
static int jacobian(group_fn group, void *ctx, int n, const double a[], double f[], double jac[][LINKGEN_NMAX],
                    double ft[])
{
    double unit[LINKGEN_NMAX], zero[LINKGEN_NMAX], res[LINKGEN_NMAX], dres[LINKGEN_NMAX];
    int i, j;
    n = adds(n);
    for (i = 0; i < LINKGEN_NMAX; i++) unit[i] = zero[i] = 0.0;
    for (j = 0; j < n; j++) {
        unit[j] = 1.0;
        if (group(ctx, a, unit, zero, ft && j == n - 1 ? 2 : 0, res, dres, ft && j == n - 1 ? ft : NULL)) return 1;
        unit[j] = 0.0;
        for (i = 0; i < n; i++) { f[i] = res[i]; jac[i][j] = dres[i]; }
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
    return fabs(det) / (prod > 1.0 ? prod : 1.0);
}

/* Whether every residual is at most tol (a nan fails every comparison). */
static int met(int n, const double f[], double tol)
{
    int i;
    for (i = 0; i < n; i++)
        if (!(fabs(f[i]) <= tol)) return 0;
    return 1;
}

/* 1 where the lengths a lie within reach of the start lengths, else 0 (another assembly). */
static int kept(int n, const double a[], const double start[], double reach)
{
    int i;
    for (i = 0; i < n; i++)
        if (!(fabs(a[i] - start[i]) <= reach)) return 0;
    return 1;
}

/* Iterate the Add-link lengths until max|f| <= tol, then (polish) one step more.  A step
 * that makes a chain fail to close is halved (up to halvings times; then the block
 * fails and the next block is tried).  The cap counts every step, a polishing one too.
 * A solution farther than reach from the start is another assembly and refused.
 * Returns 1 on success with jac the Jacobian at the returned a, else 0; where the last pass
 * is known to be the last (the polishing step's) it puts the residuals' rates at zero
 * Add-link rate into ft (ft not null) and sets *rated. */
static int newton(group_fn group, void *ctx, int n, double a[], double tol, int max_iter, double reach,
                  int halvings, int polish, double jac[][LINKGEN_NMAX], double ft[], int *rated, int *iterations)
{
    double start[LINKGEN_NMAX];
    double f[LINKGEN_NMAX], f2[LINKGEN_NMAX], dx[LINKGEN_NMAX], trial[LINKGEN_NMAX], rhs[LINKGEN_NMAX];
    double jac2[LINKGEN_NMAX][LINKGEN_NMAX];
    int it, i, j, halving;
    n = adds(n);
    *iterations = 0;
    for (i = 0; i < n; i++) start[i] = a[i];
    if (jacobian(group, ctx, n, a, f, jac, NULL)) return 0;
    for (it = 1; it <= max_iter; it++) {
        double t = 1.0;
        const int done = met(n, f, tol);
        int closed = 0;
        if (done && !polish) return kept(n, a, start, reach);
        *iterations = it;
        for (i = 0; i < n; i++) rhs[i] = -f[i];
        if (solve_linear(n, (const double (*)[LINKGEN_NMAX])jac, rhs, dx) == 0.0) return 0;
        for (halving = 0; halving <= halvings; halving++) {
            for (i = 0; i < n; i++) trial[i] = a[i] + t * dx[i];
            if (!jacobian(group, ctx, n, trial, f2, jac2, done ? ft : NULL)) { closed = 1; break; }
            t /= 2;
        }
        if (!closed) return 0;
        for (i = 0; i < n; i++) {
            a[i] = trial[i];
            f[i] = f2[i];
            for (j = 0; j < n; j++) jac[i][j] = jac2[i][j];
        }
        if (done) {
            if (ft) *rated = 1;
            return kept(n, a, start, reach);
        }
    }
    return !polish && met(n, f, tol) && kept(n, a, start, reach);
}

/* The residuals f at a, one pass; returns 1 when a chain cannot close. */
static int residuals(group_fn group, void *ctx, const double a[], double f[])
{
    double zero[LINKGEN_NMAX], df[LINKGEN_NMAX];
    int i;
    for (i = 0; i < LINKGEN_NMAX; i++) zero[i] = 0.0;
    return group(ctx, a, zero, zero, 0, f, df, NULL);
}

/* The largest residual in size; nan where one is nan. */
static double largest(int n, const double f[])
{
    double worst = 0.0;
    int i;
    for (i = 0; i < n; i++)
        if (!(fabs(f[i]) <= worst)) worst = fabs(f[i]); /* a nan stays (fmax would drop it) */
    return worst;
}

/* The literature's iteration on the decomposed group: the group's chains run round the loop
 * from the Add-link lengths a, and a <- a - J0^-1 f(a) with J0 the Jacobian at the start (one
 * pass per iteration instead of one per Add-link), until max|f| <= tol, then (polish) one step
 * more.  It converges where the map contracts: a step whose residual is not smaller than the
 * last one's (the ratio |f_k+1| / |f_k| at least 1) stops the iteration, and so does the cap
 * (every step counts, a polishing one too).  A step that makes a chain fail to close is
 * halved (up to halvings times); a nan residual fails the block.  The Jacobian at the
 * solution is then measured for the exact rates (jac).  A solution farther than reach from
 * the start is another assembly and refused.  Returns 1 on success, 0 on failure, -1 where
 * the iteration does not contract. */
static int fixed_point(group_fn group, void *ctx, int n, double a[], double tol, int max_iter, double reach,
                       int halvings, int polish, double jac[][LINKGEN_NMAX], int *iterations)
{
    double start[LINKGEN_NMAX], j0[LINKGEN_NMAX][LINKGEN_NMAX];
    double f[LINKGEN_NMAX], f2[LINKGEN_NMAX], dx[LINKGEN_NMAX], trial[LINKGEN_NMAX], rhs[LINKGEN_NMAX];
    int i, halving;
    n = adds(n);
    *iterations = 0;
    for (i = 0; i < LINKGEN_NMAX; i++) rhs[i] = 0.0;  /* entries past n are never read */
    for (i = 0; i < n; i++) start[i] = a[i];
    if (jacobian(group, ctx, n, a, f, j0, NULL)) return 0;
    while (!met(n, f, tol)) {
        double t = 1.0;
        int closed = 0;
        if (*iterations == max_iter - polish) return 0;
        ++*iterations;
        for (i = 0; i < n; i++) rhs[i] = -f[i];
        if (solve_linear(n, (const double (*)[LINKGEN_NMAX])j0, rhs, dx) == 0.0) return 0;
        for (halving = 0; halving <= halvings; halving++) {
            for (i = 0; i < n; i++) trial[i] = a[i] + t * dx[i];
            if (!residuals(group, ctx, trial, f2)) { closed = 1; break; }
            t /= 2;
        }
        if (!closed || isnan(largest(n, f2))) return 0;
        if (largest(n, f2) >= largest(n, f)) return -1;
        for (i = 0; i < n; i++) { a[i] = trial[i]; f[i] = f2[i]; }
    }
    if (polish) {
        ++*iterations;
        for (i = 0; i < n; i++) rhs[i] = -f[i];
        if (solve_linear(n, (const double (*)[LINKGEN_NMAX])j0, rhs, dx) == 0.0) return 0;
        for (i = 0; i < n; i++) a[i] += dx[i];
    }
    if (jacobian(group, ctx, n, a, f, jac, NULL)) return 0;
    return kept(n, a, start, reach);
}

/* The literature's iteration on a loop block (strategy loop): from the assumed angle, as the
 * leg's arc length a[0], the chains run round the loop and the angle that comes back is the
 * next one, a <- a + f(a), until |f| <= tol and the distance left to the fixed point,
 * |f| q / (1 - q) with q the last ratio of steps, is too, then (polish) one step more.  It converges where
 * the map contracts: the ratio of successive steps |f_k+1| / |f_k| estimates |g'|, and at
 * least 1 stops it (-1; the reverse loop, whose slope is the reciprocal, is the next block);
 * so do the cap (every step counts, a polishing one too) and a chain that cannot close (0).
 * The Jacobian at the solution (g' - 1) then gives the exact rates (jac).  A solution farther
 * than reach from the start is another assembly and refused. */
static int loop_iteration(group_fn group, void *ctx, double a[], double tol, int max_iter, double reach, int polish,
                          double jac[][LINKGEN_NMAX], int *iterations)
{
    const double start = a[0];
    double f[LINKGEN_NMAX], f2[LINKGEN_NMAX], trial[LINKGEN_NMAX], q = 0.0;
    *iterations = 0;
    if (residuals(group, ctx, a, f)) return 0;
    while (!(fabs(f[0]) <= tol && fabs(f[0]) * q <= tol * (1.0 - q))) {  /* the error |f| q / (1 - q) too */
        if (*iterations == max_iter - polish) return 0;
        ++*iterations;
        trial[0] = a[0] + f[0];
        if (residuals(group, ctx, trial, f2) || isnan(f2[0])) return 0;
        if (fabs(f2[0]) >= fabs(f[0])) return -1;
        q = fabs(f2[0]) / fabs(f[0]);
        a[0] = trial[0];
        f[0] = f2[0];
    }
    if (polish) {
        ++*iterations;
        a[0] += f[0];
    }
    if (jacobian(group, ctx, 1, a, f, jac, NULL)) return 0;
    return kept(1, a, &start, reach);
}

/* The resolver strategy's iteration on one block from its start lengths a: the one place a
 * strategy is chosen (p->strategy; strategy loop's loop blocks: solve_variant).  Returns what
 * newton and fixed_point return; Newton's ft and *rated as newton's. */
static int solve_block(group_fn group, void *ctx, int n, double a[], const resolver_policy *p, double scale,
                       double jac[][LINKGEN_NMAX], double ft[], int *rated, int *iterations)
{
    const double tol = p->tolerance * scale, reach = p->max_move * scale;
    if (p->strategy == RESOLVER_FIXED_POINT)
        return fixed_point(group, ctx, n, a, tol, p->max_iterations, reach, p->newton_halvings, p->polish, jac,
                           iterations);
    return newton(group, ctx, n, a, tol, p->max_iterations, reach, p->newton_halvings, p->polish, jac, ft, rated,
                  iterations);
}

/* One block's iteration: loop_iteration for a loop block (loop 1) under strategy loop, which
 * iterates its other blocks as the others do (solve_block). */
static int solve_variant(group_fn group, void *ctx, int n, int loop, double a[], const resolver_policy *p,
                         double scale, double jac[][LINKGEN_NMAX], double ft[], int *rated, int *iterations)
{
    *rated = 0;
    if (p->strategy == RESOLVER_LOOP && loop)
        return loop_iteration(group, ctx, a, p->tolerance * scale, p->max_iterations, p->max_move * scale, p->polish,
                              jac, iterations);
    return solve_block(group, ctx, n, a, p, scale, jac, ft, rated, iterations);
}

/* Exact Add-link rates by the implicit-function theorem (J adot = -df/dt at adot = 0; df/dt
 * ft where Newton's last pass measured it, else one pass at zero Add-link rate),
 * at order 2 the accelerations too (J addot = -d2f/dt2 at addot = 0, the same J).  The
 * rates are found at every order (they start the next row).  The pass at the rates leaves
 * the records' positions and rates; their accelerations are that pass's plus the Add-link
 * accelerations times the records' sensitivities (bend), which Newton's last pass left for
 * the last Add-link (the others' measured again at a: the same bits), as accelerations are
 * linear in the Add-links' ones; a singular J (no accelerations) takes one pass more with
 * them.  *turn is the block's orientation, the sign of det J: it stays the same along the
 * assembly while the block's chains keep their branches (it changes only at a singular
 * position; a solution of the other sign is another assembly).  Returns the status of the
 * last pass. */
static int addlink_rates(group_fn group, bend_fn bend, void *ctx, int n, const double a[],
                         const double jac[][LINKGEN_NMAX], const double ft[], int order, double *sigma, double *turn)
{
    double zero[LINKGEN_NMAX], unit[LINKGEN_NMAX], rhs[LINKGEN_NMAX], rates[LINKGEN_NMAX], accs[LINKGEN_NMAX];
    double f[LINKGEN_NMAX], df[LINKGEN_NMAX], ddf[LINKGEN_NMAX], sens[LINKGEN_NMAX][LINKGEN_NSENS], det;
    const int live = ft ? 3 : 1;  /* Newton's last pass (live 2) was at a: its positions kept */
    int i, j, st;
    n = adds(n);
    for (i = 0; i < LINKGEN_NMAX; i++) zero[i] = unit[i] = rhs[i] = accs[i] = 0.0;  /* entries past n are never read */
    if (order >= 2) {
        bend(ctx, sens[n - 1], 0.0, 1);
        for (j = 0; j < n - 1; j++) {
            unit[j] = 1.0;
            group(ctx, a, unit, zero, 0, f, df, NULL);
            unit[j] = 0.0;
            bend(ctx, sens[j], 0.0, 1);
        }
    }
    if (!ft) {
        group(ctx, a, zero, zero, 1, f, df, NULL);
        ft = df;
    }
    for (i = 0; i < n; i++) rhs[i] = -ft[i];
    det = solve_linear(n, jac, rhs, rates);
    *sigma = conditioning(n, jac, det);
    *turn = det > 0.0 ? 1.0 : det < 0.0 ? -1.0 : 0.0;
    if (order >= 2) {
        st = group(ctx, a, rates, zero, live, f, df, ddf);
        for (i = 0; i < n; i++) rhs[i] = -ddf[i];
        solve_linear(n, jac, rhs, accs);
        if (det != 0.0) {
            for (j = 0; j < n; j++) bend(ctx, sens[j], accs[j], 0);
            return st;
        }
        for (i = 0; i < n; i++) accs[i] = NAN;
    }
    return group(ctx, a, rates, accs, live, f, df, ddf);
}

/* The strategy's iteration (solve_variant) on a group's blocks (its chosen Add-link candidate,
 * then the fallbacks), the preferred block first, the others in order.  The first that
 * converges with its chains conditioned at least p->min_chain_sigma (*chains: the worst of
 * the last pass, from the block's lever down) is kept; else the best conditioned of those
 * that converge, a later block only when more than twice as well conditioned (a block whose
 * chains are near a toggle is a poor coordinate of the assembly; blocks that share that chain
 * tie up to rounding, and the order, not the rounding, decides).  A block whose state is stale
 * (nan, see resolve_group) is not tried; where one was skipped in a row's own pass (not full), a
 * row none of the others solves with its chains so conditioned fails as not converged (the driver
 * follows it from the last row: a continuation pass, full, takes the best of the blocks it can try
 * and reads every block's state, so the others are tried along the path).  a[k] holds block k's start lengths; scale is the length scale.  Returns the block, or -1 when none converges (-2 when
 * the iteration of one of them did not contract); *turn is its orientation (see
 * addlink_rates). */
static int resolve_variants(const group_fn fns[], const bend_fn bends[], branches_fn branches, const int sizes[],
                            const int loops[], int count, void *ctx, double a[][LINKGEN_NMAX], int order, int prefer,
                            int *its, double *sigma, double *turn, const double *chains, const resolver_policy *p, double scale,
                            int full)
{
    double jac[LINKGEN_NMAX][LINKGEN_NMAX], x[LINKGEN_NMAX], ft[LINKGEN_NMAX], best_sigma = -1.0;
    int t, k, i, pass, best = -1, stuck = 0, stale = 0, rated;
    for (pass = 0; pass < 2; pass++)  /* strategy loop: the loop blocks first, the Add-link blocks after */
    for (t = 0; t < count; t++) {
        int solved;
        k = t == 0 ? prefer : (t - 1 < prefer ? t - 1 : t);
        if (p->strategy == RESOLVER_LOOP ? (loops[k] != 0) != (pass == 0) : pass == 1) continue;
        if (a[k][0] != a[k][0]) {  /* a stale state: not read off this row's start */
            stale = 1;
            continue;
        }
        for (i = 0; i < sizes[k]; i++) x[i] = a[k][i];
        branches(ctx, k, a[k]);
        solved = solve_variant(fns[k], ctx, sizes[k], loops[k], x, p, scale, jac, ft, &rated, its);
        if (solved < 0) stuck = 1;
        if (solved <= 0) continue;
        if (*chains < p->min_chain_sigma) {
            if (*chains > 2.0 * best_sigma) {
                best_sigma = *chains;
                best = k;
            }
            continue;
        }
        if (addlink_rates(fns[k], bends[k], ctx, sizes[k], x, (const double (*)[LINKGEN_NMAX])jac,
                          rated ? ft : NULL, order, sigma, turn) != 1)
            return k;
    }
    if (best >= 0 && (full || !stale)) {
        for (i = 0; i < sizes[best]; i++) x[i] = a[best][i];
        branches(ctx, best, a[best]);
        if (solve_variant(fns[best], ctx, sizes[best], loops[best], x, p, scale, jac, ft, &rated, its) > 0
            && addlink_rates(fns[best], bends[best], ctx, sizes[best], x, (const double (*)[LINKGEN_NMAX])jac,
                             rated ? ft : NULL, order, sigma, turn) != 1)
            return best;
    }
    return stuck && (full || !stale) ? -2 : -1;
}

/* One resolver step: resolve_variants on the count blocks of a group, a[first] on (the one
 * that solved the last row, *used, first; branches() sets a block's branches in the work from its
 * state as it is tried); then lengths() reads the solving block's state and its rates off the
 * solved pairs and the block keeps its orientation.  With full (a continuation pass) every block's
 * state is read (so any of them can take over along the path); else (a row's own pass) the other
 * blocks' states, but a loop block's, are stale: nan, orientation 0.  Returns 1 when a block
 * solved, with *used that block; 0 when none converged, -1 when the iteration of one did not
 * contract. */
static int resolve_group(const group_fn fns[], const bend_fn bends[], branches_fn branches, int count,
                         lengths_fn lengths, void *ctx, double a[][LINKGEN_NMAX], double ad[][LINKGEN_NMAX], int first,
                         int *used, int *its, double *sigma, const double *chains, int order,
                         const resolver_mechanism *m, const resolver_policy *p, int full)
{
    double turn = 0.0;
    const int k = resolve_variants(fns, bends, branches, m->sizes + first, m->loops + first, count, ctx, a + first,
                                   order, *used, its, sigma, &turn, chains, p, m->length_scale, full);
    if (k < 0) return k == -1 ? 0 : -1;
    *used = k;
    lengths(ctx, full ? -1 : k, a + first, ad + first);
    a[first + k][LINKGEN_NMAX - 1] = turn;
    return 1;
}
