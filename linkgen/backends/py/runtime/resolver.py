# Over-constraint resolver: Newton-Raphson on the Add-link lengths.
# group(a, live) runs the steps of one resolver group with the Add-link records
# a = [(length, rate, acc), ...] and returns (status, f) with f the residual
# records; live=False zeroes the rates of everything the group reads, so a
# unit Add-link rate gives one exact Jacobian column through the velocity channel.


def solve_linear(m, b):
    """Solve m x = b by Gaussian elimination with partial pivoting; return (x, det)."""
    n = len(b)
    a = [list(row) + [b[i]] for i, row in enumerate(m)]
    det = 1.0
    for c in range(n):
        p = max(range(c, n), key=lambda r: abs(a[r][c]))
        if a[p][c] == 0.0:
            return [NAN] * n, 0.0
        if p != c:
            a[c], a[p] = a[p], a[c]
            det = -det
        det *= a[c][c]
        for r in range(c + 1, n):
            k = a[r][c] / a[c][c]
            for j in range(c, n + 1):
                a[r][j] -= k * a[c][j]
    x = [0.0] * n
    for r in range(n - 1, -1, -1):
        x[r] = (a[r][n] - sum(a[r][j] * x[j] for j in range(r + 1, n))) / a[r][r]
    return x, det


def _record(length, rate, acc):
    """An Add-link record of the program's order (rates always: the Jacobian needs them)."""
# if order >= 2
    return (length, rate, acc)
# else
    return (length, rate)
# endif


def _jacobian(group, a):
    """Residuals and Jacobian at a (one pass per Add-link); None when a chain cannot close."""
    n = len(a)
    jac = [[0.0] * n for _ in range(n)]
    f = None
    for j in range(n):
        st, rec = group([_record(a[i], 1.0 if i == j else 0.0, 0.0) for i in range(n)], False)
        if st:
            return None, None
        f = [r[0] for r in rec]
        for i in range(n):
            jac[i][j] = rec[i][1]
    return f, jac


def conditioning(jac, det):
    """|det J| over the product of its column norms (at least 1): 1 is ideal, 0 singular."""
    prod = 1.0
    for j in range(len(jac)):
        prod *= sqrt(sum(row[j] * row[j] for row in jac))
    return abs(det) / max(prod, 1.0)


def newton(group, a, tol, max_iter, reach):
    """Iterate the Add-link lengths until max|f| <= tol, then one step more.

    A solution farther than reach from the start lengths is another assembly: refused.

    Returns (ok, a, iterations, jac) with jac the Jacobian at the returned a.
    A step that makes a chain fail to close is halved (up to 3 times; then the block
    fails and the next block is tried).
    """
    start = a
    f, jac = _jacobian(group, a)
    if f is None:
        return False, a, 0, None
    for it in range(1, max_iter + 1):
        dx, det = solve_linear(jac, [-v for v in f])
        if det == 0.0:
            return False, a, it, None
        t = 1.0
        for _ in range(4):
            trial = [a[i] + t * dx[i] for i in range(len(a))]
            f2, jac2 = _jacobian(group, trial)
            if f2 is not None:
                break
            t /= 2
        else:
            return False, a, it, None
        done = all(abs(v) <= tol for v in f)  # a nan fails every comparison
        a, f, jac = trial, f2, jac2
        if done:
            return all(abs(x - y) <= reach for x, y in zip(a, start)), a, it, jac
    return False, a, max_iter, None


def addlink_rates(group, a, jac, order):
    """Exact Add-link rates by the implicit-function theorem, then the final pass.

    J adot = -df/dt|adot=0 with J the Newton Jacobian gives the rates at every order (they
    start the next row); at order 2, J addot = -d2f/dt2|addot=0 the accelerations.
    Returns the final pass's status, sigma and the block's orientation: the sign of det J,
    which stays the same along the assembly while the block's chains keep their branches
    (it changes only at a singular position; a solution of the other sign is another assembly).
    """
    n = len(a)
    _, det = solve_linear(jac, [0.0] * n)
    sigma = conditioning(jac, det)
    rates = accs = [0.0] * n
    if det != 0.0:
        st, rec = group([_record(a[i], 0.0, 0.0) for i in range(n)], True)
        rates, _ = solve_linear(jac, [-r[1] for r in rec])
# if order >= 2
        if order >= 2:
            st, rec = group([_record(a[i], rates[i], 0.0) for i in range(n)], True)
            accs, _ = solve_linear(jac, [-r[2] for r in rec])
# endif
    else:
        rates = accs = [NAN] * n
    st, _ = group([_record(a[i], rates[i], accs[i]) for i in range(n)], True)
    return st, sigma, 1 if det > 0.0 else -1 if det < 0.0 else 0


def resolve_variants(groups, a, first, tol, max_iter, reach, order, prefer, sizes, chains, min_sigma):
    """Newton on a group's blocks (its chosen Add-link candidate, then the fallbacks), the
    preferred block first, the others in order.  The first that converges with its chains
    conditioned at least min_sigma (chains(): the worst of the last pass, from the block's
    lever down) is kept; else the best conditioned of those that converge, a later block
    only when more than twice as well conditioned (a block whose chains are near a toggle is
    a poor coordinate of the assembly; blocks that share that chain tie up to rounding, and
    the order, not the rounding, decides).  The caller then measures every block's state on
    the solved pairs.

    a[first + k] is block k's state: its sizes[k] start lengths, its branches, its orientation.
    Returns (k, Newton steps, sigma, orientation), k = -1 when no block converges.
    """
    its, best, best_sigma = 0, -1, -1.0
    for k in [prefer] + [j for j in range(len(groups)) if j != prefer]:
        ok, x, its, jac = newton(groups[k], a[first + k][:sizes[k]], tol, max_iter, reach)
        if not ok:
            continue
        if chains() < min_sigma:
            if chains() > 2 * best_sigma:
                best, best_sigma = k, chains()
            continue
        st, sigma, turn = addlink_rates(groups[k], x, jac, order)
        if st != 1:
            return k, its, sigma, turn
    if best >= 0:
        ok, x, its, jac = newton(groups[best], a[first + best][:sizes[best]], tol, max_iter, reach)
        if ok:
            st, sigma, turn = addlink_rates(groups[best], x, jac, order)
            if st != 1:
                return best, its, sigma, turn
    return -1, its, 0.0, 0


def advance(a, rates, step, sizes):
    """Block states moved by step along their rates.  An Add-link length is a distance:
    where its prediction passes zero the two pairs pass each other, so it is reflected."""
    return [[abs(v + step * r) if i < n else v + step * r for i, (v, r) in enumerate(zip(g, gr))]
            for g, gr, n in zip(a, rates, sizes)]


def predict(warm, inputs, sizes):
    """Resolver start values for new inputs: the warm states advanced along their rates
    (first-order Taylor in the warm row's input direction; rates exist at every order,
    so a program gives the same positions whatever order it computes)."""
    w_in, w_rates, a, ad = warm
    den = sum(r * r for r in w_rates)
    tau = sum((x - y) * r for x, y, r in zip(inputs, w_in, w_rates)) / den if den > 0 else 0.0
    return advance(a, ad, tau, sizes)


def within(inputs, last, limits):
    """Whether no input moved farther from the last row than a continuation step."""
    return all(abs(x - y) <= lim for x, y, lim in zip(inputs, last, limits))


def on_path(prev, guess, new, sizes, slack):
    """Whether a solved state new is where the predictor guess pointed from prev: no
    block's Add-link length moved from the guess by more than a tenth of the largest predicted
    move (plus slack); a larger correction is a jump to another assembly, or a step too long
    for the curve.  A block that solved both and turned its orientation (the last entry of a
    block's state, after its sizes[k] lengths and its branches; 0 where it did not solve) has
    passed a singular position.  Where two assemblies pass close the nearer one can lie within
    the tenth, so a turned block must be within a hundredth: the path crosses the singular
    position along its tangent, as a mechanism goes straight through a change point."""
    move = max((abs(g[i] - p[i]) for p, g, n in zip(prev, guess, sizes) for i in range(n)), default=0.0)
    share = 0.01 if any(p[-1] * x[-1] < 0.0 for p, x in zip(prev, new)) else 0.1
    return all(abs(x[i] - g[i]) <= share * move + slack for g, x, n in zip(guess, new, sizes) for i in range(n))


def continuation(run, base, a, target, limits, periodic, halvings, sizes, slack, reach, low):
    """Follow the assembly from inputs base (solved with block states a) to target.

    Angle inputs go the shorter way round, else the other way; where the one input is an
    angle with a reach (the values it reaches from the sketch, modulo whole turns, from low
    up; low is nan without one; base and target are inside it), it goes the one way round
    that stays inside the reach.  Each step moves no input by
    more than its limit and no Add-link length, as predicted, by more than reach; it starts
    Newton from the tangent predictor and is halved where Newton fails or lands off the path
    (see on_path), up to halvings times in a row.  run(inputs, rates, order, a) -> (ok, a,
    rates) solves with input rates per unit of the path.  Returns the block states at
    target, or None when the way (both ways without a reach) is cut.
    """
    if periodic[0] and low == low:
        turns = [x - 2 * PI * floor((x - low) / (2 * PI)) for x in (base[0], target[0])]
        return walk(run, base, a, [base[0] + turns[1] - turns[0]], limits, halvings, sizes, slack, reach)
    goal = [t - 2 * PI * floor((t - b) / (2 * PI) + 0.5) if p else t for t, b, p in zip(target, base, periodic)]
    reached = walk(run, base, a, goal, limits, halvings, sizes, slack, reach)
    other = [(g - 2 * PI if g > b else g + 2 * PI if g < b else g) if p else g
             for g, b, p in zip(goal, base, periodic)]
    if reached is None and other != goal:
        reached = walk(run, base, a, other, limits, halvings, sizes, slack, reach)
    return reached


WALK_PASSES = 1000  # a walk gives up after this many passes of the procedure


def walk(run, base, a, goal, limits, halvings, sizes, slack, reach):
    """Continuation along the straight path from base to goal (see continuation).  Near a
    singular position the lengths' rates are large and the steps short (the prediction
    holds only there); a step that makes no progress in floating point cuts the path, and
    so do WALK_PASSES passes (at once where the path needs more steps than that)."""
    d = [g - b for g, b in zip(goal, base)]
    h_max = min([1.0] + [lim / abs(x) for lim, x in zip(limits, d) if x != 0.0])
    if h_max * WALK_PASSES < 1.0:
        return None
    ok, a, rate = run(base, d, 1, a)
    if not ok:
        return None
    t, h, cuts, passes = 0.0, h_max, 0, 1
    while t < 1.0:
        if passes == WALK_PASSES:
            return None
        passes += 1
        fast = max((abs(r[i]) for r, n in zip(rate, sizes) for i in range(n) if r[i] == r[i]), default=0.0)
        if fast * h > reach:
            h = reach / fast
        tt = min(1.0, t + h)
        if tt == t:
            return None
        trial = [b + tt * x for b, x in zip(base, d)] if tt < 1.0 else goal
        guess = advance(a, rate, tt - t, sizes)
        ok, a2, rate2 = run(trial, d, 1, guess)
        if ok and on_path(a, guess, a2, sizes, slack):
            t, a, rate, h, cuts = tt, a2, rate2, min(2 * h, h_max), 0
        else:
            h, cuts = h / 2, cuts + 1
            if cuts > halvings:
                return None
    return a
