/* The row driver: one row of a sweep solved on the sketch's assembly, from the previous
 * row where it can (Taylor-predicted start), else by continuation from the previous row or
 * from the sketch.  run(ctx, row, in, din, ddin, order, a, ad, used) is one pass of the
 * procedure with the block states a and the preferred blocks used (both updated in place to
 * the solution) and writes the block states' rates into ad; row says whether the pass is the
 * row's own (1: reading the solving blocks' states alone, 2: every block's; else one along a
 * continuation path, reading every block's).  Returns the status code. */
typedef int (*pass_fn)(void *ctx, int row, const double in[], const double din[], const double ddin[], int order,
                       double a[][LINKGEN_NMAX], double ad[][LINKGEN_NMAX], int used[]);

/* The warm start a caller keeps between rows: whether it holds a solved row, its inputs and
 * their rates, its block states and their rates, and the blocks that solved it; for the
 * second-order predictor (else null) whether it holds the row before, its inputs and block states. */
typedef struct {
    int *valid;
    double *in, *din;
    double (*a)[LINKGEN_NMAX], (*ad)[LINKGEN_NMAX];
    int *used;
    int *back_valid;
    double *back_in;
    double (*back_a)[LINKGEN_NMAX];
} resolver_warm;

/* A continuation's view of the procedure: passes along the path, the blocks tried first. */
typedef struct {
    pass_fn run;
    void *ctx;
    const int *prefer;
} resolver_path;

/* One pass along a continuation path (rates per unit of the path, no accelerations):
 * returns 1 when it closes, with the block states a, their rates and the blocks that solved. */
static int path_pass(const resolver_path *path, const double in[], const double din[], int order,
                     double a[][LINKGEN_NMAX], double rates[][LINKGEN_NMAX], int used[])
{
    static const double zero[LINKGEN_NINPUTS] = { 0.0 };
    int g;
    for (g = 0; g < LINKGEN_NGROUPS; g++) used[g] = path->prefer[g];
    return path->run(path->ctx, 0, in, din, zero, order, a, rates, used) <= 0;
}

/* How many blocks a state has to look at: where stale (a row's own pass left it, reading the solving
 * blocks' states alone: see resolve_group) of each group the one that solved it, where no block is a
 * loop block (LINKGEN_LOOPS 0; a loop block keeps its state); else every block (a stale one looked at
 * as such). */
static int held(int stale)
{
    return stale && !LINKGEN_LOOPS ? LINKGEN_NGROUPS : LINKGEN_NBLOCKS;
}

/* The t-th of those blocks (see held), the groups' solving blocks used. */
static int block(int t, int stale, const int used[], const resolver_mechanism *m)
{
    return stale && !LINKGEN_LOOPS ? m->firsts[t] + used[t] : t;
}

/* Whether a solved state is where the predictor pointed from prev: no block's Add-link
 * length moved from the guess by more than p->path_share of the largest predicted move (plus
 * slack); a larger correction is a jump to another assembly, or a step too long for the
 * curve.  A block that solved both and turned its orientation (the state's last entry,
 * after its m->sizes[k] lengths and its branches; 0 where the block did not solve) has passed
 * a singular position.  Where two assemblies pass close the nearer one can lie within that
 * share, so a turned block must be within p->turn_share: the path crosses the singular
 * position along its tangent, as a mechanism goes straight through a change point.  Only a
 * block that solved now (used, of each group the block from its first, m->firsts) has an
 * orientation there, so only those are looked at (the same verdict as every block).  Only the
 * blocks with a state in prev and now are looked at (a stale one, nan, has none: a row's own pass is
 * judged on its solving blocks; a continuation's on every block); stale says prev's fallback
 * states are (see held). */
static int on_path(const double prev[][LINKGEN_NMAX], const double guess[][LINKGEN_NMAX],
                   const double now[][LINKGEN_NMAX], const int used[], const resolver_mechanism *m, double slack,
                   const resolver_policy *p, int stale)
{
    double move = 0.0, off = 0.0, share = p->path_share;
    int t, g, i;
    for (t = 0; t < held(stale); t++)  /* one pass: the largest predicted move and correction */
        for (g = block(t, stale, used, m), i = 0;
             i < adds(m->sizes[g]) && prev[g][0] == prev[g][0] && now[g][0] == now[g][0]; i++) {
            const double d = fabs(guess[g][i] - prev[g][i]), e = fabs(now[g][i] - guess[g][i]);
            if (d > move) move = d;  /* fmax without the call: a nan guess is checked below */
            if (e > off || e != e) off = e;  /* a nan correction stays */
        }
    for (g = 0; g < LINKGEN_NGROUPS; g++) {
        const int k = m->firsts[g] + used[g];
        if (prev[k][LINKGEN_NMAX - 1] * now[k][LINKGEN_NMAX - 1] < 0.0) share = p->turn_share;
    }
    return off <= share * move + slack;  /* a nan too */
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
 * reflected.  A branch's measure moves too: where it passes zero the chain passes its fold
 * and goes on on its other branch, as a chain outside the groups does at a change point.
 * The orientation (the last entry) is copied. */
static void advance(const double a[][LINKGEN_NMAX], const double rate[][LINKGEN_NMAX], double step,
                    const int sizes[], const int loops[], double out[][LINKGEN_NMAX])
{
    int g, i;
    for (g = 0; g < LINKGEN_NBLOCKS; g++) {
        for (i = 0; i < adds(sizes[g]); i++)  /* a loop block's arc length is an angle: not reflected */
            out[g][i] = loops[g] ? a[g][i] + step * rate[g][i] : fabs(a[g][i] + step * rate[g][i]);
        for (; i < LINKGEN_NMAX - 1; i++) out[g][i] = a[g][i] + step * rate[g][i];
        out[g][LINKGEN_NMAX - 1] = a[g][LINKGEN_NMAX - 1];
    }
}

/* How far inputs in lie from the warm row's along its input rates, in time (0 without rates). */
static double warm_tau(const resolver_warm *warm, const double in[])
{
    double num = 0.0, den = 0.0;
    int i;
    for (i = 0; i < LINKGEN_NINPUTS; i++) {
        num += (in[i] - warm->in[i]) * warm->din[i];
        den += warm->din[i] * warm->din[i];
    }
    return den > 0.0 ? num / den : 0.0;
}

/* The path the assembly is expected on at new inputs, into a: the warm states advanced along
 * their rates (order 1: first-order Taylor in the warm row's input direction), or along the
 * parabola with those rates that also passes through the row before them (order 2; first
 * order without one).  Both need positions and rates only, and the rates exist at every
 * order, so the positions do not depend on the order computed. */
static void predict(const resolver_warm *warm, const double in[], const resolver_mechanism *m, int order,
                    double a[][LINKGEN_NMAX], int stale)
{
    const double tau = warm_tau(warm, in);
    const double back = order >= 2 && *warm->back_valid ? warm_tau(warm, warm->back_in) : 0.0;
    int t, g, i;
    memcpy(a, warm->a, sizeof(double) * LINKGEN_NBLOCKS * LINKGEN_NMAX);  /* a stale state stays: advance's nan */
    for (t = 0; t < held(stale); t++) {  /* advance's operations, with the parabola for the lengths (the same bits) */
        g = block(t, stale, warm->used, m);
        for (i = 0; i < adds(m->sizes[g]); i++) {
            const double ahead = back == 0.0 ? warm->a[g][i] + tau * warm->ad[g][i]
                : warm->a[g][i] + tau * warm->ad[g][i]
                  + tau * tau * ((warm->back_a[g][i] - warm->a[g][i] - back * warm->ad[g][i]) / (back * back));
            a[g][i] = m->loops[g] ? ahead : fabs(ahead);
        }
        for (; i < LINKGEN_NMAX - 1; i++) a[g][i] = warm->a[g][i] + tau * warm->ad[g][i];
    }
}

/* Continuation along the straight path from base to goal.  Each step moves no input by
 * more than its limit (m->limits) and no Add-link length, as predicted, by more than
 * p->max_move of the length scale; it starts Newton from the tangent predictor and is
 * halved where Newton fails or lands off the path (see on_path), up to p->max_halvings
 * times in a row.  Near a singular position the lengths' rates are large and the steps
 * short (the prediction holds only there); a step that makes no progress in floating point
 * cuts the path, and so do p->walk_passes passes (at once where the path needs more steps
 * than that).  Returns 1 with a the block states at goal, 0 where the path is cut. */
static int walk(const resolver_path *path, const double base[], double a[][LINKGEN_NMAX], const double goal[],
                const resolver_mechanism *m, const resolver_policy *p)
{
    const double slack = p->path_slack * m->length_scale, reach = p->max_move * m->length_scale;
    double d[LINKGEN_NINPUTS], trial[LINKGEN_NINPUTS], start[LINKGEN_NBLOCKS][LINKGEN_NMAX];
    double rate[LINKGEN_NBLOCKS][LINKGEN_NMAX], guess[LINKGEN_NBLOCKS][LINKGEN_NMAX];
    double now[LINKGEN_NBLOCKS][LINKGEN_NMAX], rate2[LINKGEN_NBLOCKS][LINKGEN_NMAX];
    double t = 0.0, h, h_max = 1.0, fast;
    int used[LINKGEN_NGROUPS], g, i, cuts = 0, passes = 1;
    for (i = 0; i < LINKGEN_NINPUTS; i++) {
        d[i] = goal[i] - base[i];
        if (d[i] != 0.0) h_max = fmin(h_max, m->limits[i] / fabs(d[i]));
    }
    if (h_max * p->walk_passes < 1.0) return 0;
    for (g = 0; g < LINKGEN_NBLOCKS; g++)
        for (i = 0; i < LINKGEN_NMAX; i++) start[g][i] = a[g][i];
    if (!path_pass(path, base, d, 1, start, rate, used)) return 0;
    h = h_max;
    while (t < 1.0) {
        double tt;
        if (passes++ == p->walk_passes) return 0;
        fast = 0.0;
        for (g = 0; g < LINKGEN_NBLOCKS; g++)
            for (i = 0; i < adds(m->sizes[g]); i++)
                if (fabs(rate[g][i]) > fast) fast = fabs(rate[g][i]);
        if (fast * h > reach) h = reach / fast;
        tt = fmin(1.0, t + h);
        if (tt == t) return 0;
        for (i = 0; i < LINKGEN_NINPUTS; i++) trial[i] = tt < 1.0 ? base[i] + tt * d[i] : goal[i];
        advance((const double (*)[LINKGEN_NMAX])start, (const double (*)[LINKGEN_NMAX])rate, tt - t, m->sizes, m->loops,
                guess);
        for (g = 0; g < LINKGEN_NBLOCKS; g++)
            for (i = 0; i < LINKGEN_NMAX; i++) now[g][i] = guess[g][i];
        if (path_pass(path, trial, d, 1, now, rate2, used)
            && on_path((const double (*)[LINKGEN_NMAX])start, (const double (*)[LINKGEN_NMAX])guess,
                       (const double (*)[LINKGEN_NMAX])now, used, m, slack, p, 0)) {
            t = tt;
            h = fmin(2.0 * h, h_max);
            cuts = 0;
            for (g = 0; g < LINKGEN_NBLOCKS; g++)
                for (i = 0; i < LINKGEN_NMAX; i++) { start[g][i] = now[g][i]; rate[g][i] = rate2[g][i]; }
        } else {
            h /= 2.0;
            if (++cuts > p->max_halvings) return 0;
        }
    }
    for (g = 0; g < LINKGEN_NBLOCKS; g++)
        for (i = 0; i < LINKGEN_NMAX; i++) a[g][i] = start[g][i];
    return 1;
}

/* Follow the assembly from inputs base (solved with block states a) to target.  Angle
 * inputs go the shorter way round, else the other way; where the one input is an angle
 * with a reach (the values it reaches from the sketch, modulo whole turns, from m->low up;
 * m->low is nan without one; base and target are inside it), it goes the one way round that
 * stays inside the reach.  Returns 1 with a the block states at target, 0 when the way
 * (both ways without a reach) is cut. */
static int continuation(const resolver_path *path, const double base[], double a[][LINKGEN_NMAX],
                        const double target[], const resolver_mechanism *m, const resolver_policy *p)
{
    const double two_pi = 2.0 * 3.141592653589793;
    double goal[LINKGEN_NINPUTS], other[LINKGEN_NINPUTS];
    int i, differs = 0;
    if (m->periodic[0] && !isnan(m->low)) {
        for (i = 0; i < LINKGEN_NINPUTS; i++) goal[i] = target[i];
        goal[0] = base[0] + (target[0] - two_pi * floor((target[0] - m->low) / two_pi))
                  - (base[0] - two_pi * floor((base[0] - m->low) / two_pi));
        return walk(path, base, a, goal, m, p);
    }
    for (i = 0; i < LINKGEN_NINPUTS; i++) {
        goal[i] = m->periodic[i] ? target[i] - two_pi * floor((target[i] - base[i]) / two_pi + 0.5) : target[i];
        other[i] = goal[i];
        if (m->periodic[i] && goal[i] != base[i]) {
            other[i] = goal[i] > base[i] ? goal[i] - two_pi : goal[i] + two_pi;
            differs = 1;
        }
    }
    if (walk(path, base, a, goal, m, p)) return 1;
    return differs && walk(path, base, a, other, m, p);
}

/* Solve one row on the sketch's assembly.  From the warm start (the previous row) when no
 * input has moved farther than a continuation step: the resolvers start where the predictor
 * of order p->predictor points (see predict; order 0: from the warm states as they were), and
 * the row is taken when it solves on that path (see on_path; order 0: the first-order one).
 * Else, or where that fails at a resolver or lands off the path, the assembly is followed by
 * continuation from the previous row (or, without one, from the sketch) and the row solved
 * from there, reading every block's state (so that the next row can try every block); where the way is cut but the row solves all the same it is on another
 * assembly only, and gets the code m->another.  A row past the reach (past) fails at once.
 * The warm start becomes this row's where it solved (the passes write the block states' rates
 * into it at once: only predict reads them, before; a row that did not solve leaves none).
 * Returns the status code. */
static int drive(pass_fn run, void *ctx, const resolver_mechanism *m, const resolver_policy *p, int past,
                 const double in[], const double din[], const double ddin[], int order, const resolver_warm *warm)
{
    double base[LINKGEN_NINPUTS], a[LINKGEN_NBLOCKS][LINKGEN_NMAX], guess[LINKGEN_NBLOCKS][LINKGEN_NMAX];
    double (*const ad)[LINKGEN_NMAX] = warm->ad;  /* the passes' rates straight into the warm start */
    int used[LINKGEN_NGROUPS];
    const int stale = *warm->valid == 1;  /* the warm states of a row's own pass: its fallbacks' stale */
    int code = 0, solved = 0, full = 0, t, g, i;
    for (i = 0; i < LINKGEN_NINPUTS; i++) base[i] = m->sketch_in[i];
    if (past || !*warm->valid)  /* else the warm states replace them below */
        memcpy(a, m->sketch_a, sizeof a);  /* the block states copied whole (a loop per entry costs more) */
    for (g = 0; g < LINKGEN_NGROUPS; g++) used[g] = *warm->valid ? warm->used[g] : 0;
    if (past) {
        /* past a limit position: the pass fails the row at once with the limit's code */
        code = run(ctx, 1, in, din, ddin, order, a, ad, used);
    } else if (*warm->valid && within(in, warm->in, m->limits)) {
        predict(warm, in, m, p->predictor, a, stale);
        for (t = 0; t < held(stale); t++)  /* the guessed lengths, all on_path reads of the guess */
            for (g = block(t, stale, used, m), i = 0; i < adds(m->sizes[g]); i++) guess[g][i] = a[g][i];
        if (!p->predictor) memcpy(a, warm->a, sizeof a);  /* predictor order 0: the warm states as they were */
        code = run(ctx, 1, in, din, ddin, order, a, ad, used);
        solved = code <= 0 && on_path((const double (*)[LINKGEN_NMAX])warm->a, (const double (*)[LINKGEN_NMAX])guess,
                                      (const double (*)[LINKGEN_NMAX])a, used, m,
                                      p->path_slack * m->length_scale, p, stale);
    }
    if (!solved && *warm->valid) {
        for (i = 0; i < LINKGEN_NINPUTS; i++) base[i] = warm->in[i];
        memcpy(a, warm->a, sizeof a);
        for (g = 0; g < LINKGEN_NGROUPS; g++) used[g] = warm->used[g];
    }
    if (!solved && (code <= 0 || reason_of(code) == m->not_converged)) {
        int prefer[LINKGEN_NGROUPS];
        resolver_path path;
        for (g = 0; g < LINKGEN_NGROUPS; g++) prefer[g] = used[g];
        path.run = run;
        path.ctx = ctx;
        path.prefer = prefer;
        full = 1;  /* a row followed by continuation reads every block's state: the next row can start any */
        if (continuation(&path, base, a, in, m, p)) {
            code = run(ctx, 2, in, din, ddin, order, a, ad, used);
        } else {
            code = run(ctx, 2, in, din, ddin, order, a, ad, used);
            if (code <= 0) code = m->another;  /* another assembly only */
        }
        solved = code <= 0;
    }
    if (warm->back_valid) {  /* the second-order predictor's row before: the warm row, on the sketch's assembly */
        *warm->back_valid = solved && *warm->valid && code != m->another;
        if (*warm->back_valid) {
            for (i = 0; i < LINKGEN_NINPUTS; i++) warm->back_in[i] = warm->in[i];
            for (g = 0; g < LINKGEN_NBLOCKS; g++)  /* the lengths, all predict reads of the row before */
                for (i = 0; i < adds(m->sizes[g]); i++) warm->back_a[g][i] = warm->a[g][i];
        }
    }
    *warm->valid = solved ? 1 + full : 0;  /* 2: every block's state read (see stale) */
    if (solved) {
        for (i = 0; i < LINKGEN_NINPUTS; i++) { warm->in[i] = in[i]; warm->din[i] = din[i]; }
        memcpy(warm->a, a, sizeof a);
        for (g = 0; g < LINKGEN_NGROUPS; g++) warm->used[g] = used[g];
    }
    return code;
}
