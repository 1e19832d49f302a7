/* The closure strategy (options: strategy closure): Newton on all loop-closure equations of a
 * resolver group at once, in the positions the group places, from where the first block that
 * closes at its state puts them, then (polish) one step more; then every block's state is read
 * off the solution and the resolver finishes the row from there (resolve_group, without a
 * polishing step of its own: the block's Add-link residuals meet the tolerance at once; exact
 * rates, conditioning, orientation).  A group's
 * closure: place() the positions of the last pass, equations() the residuals g (length units)
 * and their Jacobian at positions x (its nonzero entries: the rest is zeroed here), adopt()
 * puts x into the work and reads every block's state off it (lengths, branches). */
typedef struct {
    int n;  /* unknowns: x and y of each position the group places */
    void (*place)(const void *ctx, double x[]);
    void (*equations)(const void *ctx, const double x[], double g[], double jac[][LINKGEN_NMAX]);
    void (*adopt)(void *ctx, const double x[], double a[][LINKGEN_NMAX]);
} closure_group;

/* Newton on the closure equations from positions x until max|g| <= tol, then (polish) one step
 * more; at most max_iter steps (*its), a polishing one too.  A solution farther than reach from
 * the start is another assembly and refused.  Returns 1 on success. */
static int closure_newton(const closure_group *c, const void *ctx, double x[], double tol, int max_iter,
                          double reach, int polish, int *its)
{
    double start[LINKGEN_NMAX], g[LINKGEN_NMAX], rhs[LINKGEN_NMAX], dx[LINKGEN_NMAX];
    double jac[LINKGEN_NMAX][LINKGEN_NMAX], worst = 0.0, moved = 0.0;
    int i, j;
    for (i = 0; i < c->n; i++) start[i] = x[i];
    for (*its = 0;; ++*its) {
        for (i = 0; i < c->n; i++)
            for (j = 0; j < c->n; j++) jac[i][j] = 0.0;
        c->equations(ctx, x, g, jac);
        for (i = 0, worst = 0.0; i < c->n; i++)
            if (!(fabs(g[i]) <= worst)) worst = fabs(g[i]); /* a nan stays (fmax would drop it) */
        if ((worst <= tol && !polish) || *its == max_iter) break;
        for (i = 0; i < c->n; i++) rhs[i] = -g[i];
        if (solve_linear(c->n, (const double (*)[LINKGEN_NMAX])jac, rhs, dx) == 0.0) return 0;
        for (i = 0; i < c->n; i++) x[i] += dx[i];
        if (worst <= tol) {
            ++*its;
            break;
        }
    }
    if (!(worst <= tol)) return 0;
    for (i = 0; i < c->n; i++)
        if (!(fabs(x[i] - start[i]) <= moved)) moved = fabs(x[i] - start[i]);
    return moved <= reach;
}

/* One resolver step by the closure strategy (resolve_group's arguments and result, c the
 * group's closure): the positions start where the first block that closes at its state puts
 * them (the one that solved the last row, *used, first; the others in order), Newton on the
 * closure equations, every block's state read off the solution, then resolve_group from
 * there (no polishing step there: the closure took it).  *its gets the closure's Newton steps
 * and the resolver's. */
static int resolve_closure(const closure_group *c, const group_fn fns[], const bend_fn bends[],
                           branches_fn branches, int count, lengths_fn lengths, void *ctx,
                           double a[][LINKGEN_NMAX], double ad[][LINKGEN_NMAX], int first, int *used, int *its, double *sigma, const double *chains, int order,
                           const resolver_mechanism *m, const resolver_policy *p, int full)
{
    double x[LINKGEN_NMAX], zero[LINKGEN_NMAX], f[LINKGEN_NMAX], df[LINKGEN_NMAX];
    resolver_policy polished = *p;
    int t, i, steps, closed = 0, solved;
    for (i = 0; i < LINKGEN_NMAX; i++) zero[i] = 0.0;
    *its = 0;
    for (t = 0; t < count && !closed; t++) {
        const int k = t == 0 ? *used : (t - 1 < *used ? t - 1 : t);
        if (a[first + k][0] != a[first + k][0]) continue;  /* a stale state (nan) is not tried */
        branches(ctx, k, a[first + k]);
        closed = !fns[k](ctx, a[first + k], zero, zero, 0, f, df, NULL);
    }
    if (!closed) return 0;
    c->place(ctx, x);
    closed = closure_newton(c, ctx, x, p->tolerance * m->length_scale, p->max_iterations,
                            p->max_move * m->length_scale, p->polish, &steps);
    *its = steps;
    if (!closed) return 0;
    c->adopt(ctx, x, a + first);
    polished.polish = 0;  /* the closure's own step was the polishing one */
    solved = resolve_group(fns, bends, branches, count, lengths, ctx, a, ad, first, used, its, sigma, chains, order,
                           m, &polished, full);
    *its += steps;
    return solved;
}
