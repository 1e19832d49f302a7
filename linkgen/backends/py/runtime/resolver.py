# Over-constraint resolver: the strategy's iteration on the Add-link lengths (Newton-Raphson,
# the paper's, or fixed-point iteration with the slope of the row's start), then exact rates.
# group(a, da, dda, live) runs the steps of one resolver group with the Add-link lengths
# a, their rates da and accelerations dda (as records of the program's order) and returns
# (status, f) with f the residual records; live=False zeroes the rates of everything the
# group reads, so a unit Add-link rate gives one exact Jacobian column through the
# velocity channel.  p is the resolver policy (the step log's, with the strategy, polish
# and predictor of the build's options), scale the length scale.


def solve_linear(m, b):
    """Solve m x = b by Gaussian elimination with partial pivoting; return (x, det)."""
    n = len(b)
    if n == 1:  # one Add-link: the elimination's own operations (1.0 * d is d, b - 0 is b)
        d = m[0][0]
        return ([b[0] / d], d) if d != 0.0 else ([NAN], 0.0)
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


def _jacobian(group, a):
    """Residuals and Jacobian at a (one pass per Add-link); None when a chain cannot close."""
    n = len(a)
    jac = [[0.0] * n for _ in range(n)]
    zero = [0.0] * n
    f = None
    for j in range(n):
        st, rec = group(a, [1.0 if i == j else 0.0 for i in range(n)], zero, False)
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


def _residuals(group, a):
    """The residuals at a (one pass); None when a chain cannot close."""
    zero = [0.0] * len(a)
    st, rec = group(a, zero, zero, False)
    return None if st else [r[0] for r in rec]


def _met(f, tol):
    """Whether every residual is at most tol (a nan fails every comparison)."""
    return all(abs(v) <= tol for v in f)


def _kept(a, start, reach):
    """1 where the lengths a lie within reach of the start lengths, else 0 (another assembly)."""
    return int(all(abs(x - y) <= reach for x, y in zip(a, start)))


def newton(group, a, tol, max_iter, reach, halvings, polish):
    """Iterate the Add-link lengths until max|f| <= tol, then (polish) one step more.

    A solution farther than reach from the start lengths is another assembly: refused.

    Returns (solved, a, iterations, jac): solved 1 or 0, jac the Jacobian at the returned a.
    A step that makes a chain fail to close is halved (up to halvings times; then the
    block fails and the next block is tried).  The cap counts every step, a polishing one too.
    """
    start = a
    f, jac = _jacobian(group, a)
    if f is None:
        return 0, a, 0, None
    for it in range(1, max_iter + 1):
        done = _met(f, tol)
        if done and not polish:
            return _kept(a, start, reach), a, it - 1, jac
        dx, det = solve_linear(jac, [-v for v in f])
        if det == 0.0:
            return 0, a, it, None
        t = 1.0
        for _ in range(halvings + 1):
            trial = [a[i] + t * dx[i] for i in range(len(a))]
            f2, jac2 = _jacobian(group, trial)
            if f2 is not None:
                break
            t /= 2
        else:
            return 0, a, it, None
        a, f, jac = trial, f2, jac2
        if done:
            return _kept(a, start, reach), a, it, jac
    if not polish and _met(f, tol):
        return _kept(a, start, reach), a, max_iter, jac
    return 0, a, max_iter, None


def fixed_point(group, a, tol, max_iter, reach, halvings, polish):
    """The literature's iteration on the decomposed group: the group's chains run round the
    loop from the Add-link lengths a, and a <- a - J0^-1 f(a) with J0 the Jacobian at the
    start (one pass per iteration instead of one per Add-link), until max|f| <= tol, then
    (polish) one step more.  It converges where the map contracts: a step whose residual
    is not smaller than the last one's (the ratio |f_k+1| / |f_k| at least 1) stops the
    iteration, and so does the cap (every step counts, a polishing one too).  A step that
    makes a chain fail to close is halved (up to halvings times).  The Jacobian at the
    solution is then measured for the exact rates.  A solution farther than reach from
    the start is another assembly: refused.

    Returns (solved, a, iterations, jac): solved 1, 0, or -1 where the iteration does not
    contract; jac the Jacobian at the returned a.
    """
    start = a
    f, j0 = _jacobian(group, a)
    if f is None:
        return 0, a, 0, None
    its = 0
    while not _met(f, tol):
        if its == max_iter - polish:
            return 0, a, its, None
        its += 1
        dx, det = solve_linear(j0, [-v for v in f])
        if det == 0.0:
            return 0, a, its, None
        t = 1.0
        for _ in range(halvings + 1):
            trial = [a[i] + t * dx[i] for i in range(len(a))]
            f2 = _residuals(group, trial)
            if f2 is not None:
                break
            t /= 2
        else:
            return 0, a, its, None
        if any(v != v for v in f2):  # a nan residual: the block fails, as Newton's does
            return 0, a, its, None
        if max(abs(v) for v in f2) >= max(abs(v) for v in f):
            return -1, a, its, None
        a, f = trial, f2
    if polish:
        its += 1
        dx, det = solve_linear(j0, [-v for v in f])
        if det == 0.0:
            return 0, a, its, None
        a = [a[i] + dx[i] for i in range(len(a))]
    f, jac = _jacobian(group, a)
    if f is None:
        return 0, a, its, None
    return _kept(a, start, reach), a, its, jac


def loop_iteration(group, a, tol, max_iter, reach, polish):
    """The literature's iteration on a loop block (strategy loop): from the assumed angle, as
    the leg's arc length s, the chains run round the loop and the angle that comes back is
    the next one, s <- s + f(s) (f: the angle that came back less the one assumed, as an arc),
    until |f| <= tol and the distance left to the fixed point, |f| q / (1 - q) with q the
    last ratio of steps, is too, then (polish) one step more.  It converges where the map contracts:
    the ratio of successive steps |f_k+1| / |f_k| estimates |g'|, and at least 1 stops it
    (the reverse loop, whose slope is the reciprocal, is the next block); so does the cap
    (every step counts, a polishing one too) and a chain that cannot close.  The Jacobian at
    the solution (g' - 1) then gives the exact rates.  A solution farther than reach from the
    start is another assembly: refused.

    Returns (solved, a, iterations, jac) as fixed_point does.
    """
    start = a
    f = _residuals(group, a)
    if f is None:
        return 0, a, 0, None
    its, q = 0, 0.0
    while not (abs(f[0]) <= tol and abs(f[0]) * q <= tol * (1.0 - q)):  # the error |f| q / (1 - q) too
        if its == max_iter - polish:
            return 0, a, its, None
        its += 1
        trial = [a[0] + f[0]]
        f2 = _residuals(group, trial)
        if f2 is None or f2[0] != f2[0]:
            return 0, a, its, None
        if abs(f2[0]) >= abs(f[0]):
            return -1, a, its, None
        q = abs(f2[0]) / abs(f[0])
        a, f = trial, f2
    if polish:
        its += 1
        a = [a[0] + f[0]]
    f, jac = _jacobian(group, a)
    if f is None:
        return 0, a, its, None
    return _kept(a, start, reach), a, its, jac


def solve_block(group, a, p, scale, loop=0):
    """The resolver strategy's iteration on one block from its start lengths a: the one
    place a strategy is chosen (p.strategy; loop: 1 for a loop block, which strategy loop
    iterates by loop_iteration, its other blocks by Newton).  Returns (solved, a,
    iterations, jac) as newton and fixed_point do."""
    tol, reach = p.tolerance * scale, p.max_move * scale
    if p.strategy == "loop" and loop:
        return loop_iteration(group, a, tol, p.max_iterations, reach, p.polish)
    if p.strategy == "fixed-point":
        return fixed_point(group, a, tol, p.max_iterations, reach, p.newton_halvings, p.polish)
    return newton(group, a, tol, p.max_iterations, reach, p.newton_halvings, p.polish)


def sensitivities(w, names):
    """The rates of the records names of w (order 2: value, rates, accelerations, each a third), one
    list: as a Jacobian pass leaves them, the records' sensitivities to an Add-link."""
    return [x for n in names for x in getattr(w, n)[len(getattr(w, n)) // 3:2 * len(getattr(w, n)) // 3]]


def bend(w, names, sens, acc):
    """The records names of w with acc times their sensitivities sens added to their accelerations."""
    k = 0
    for n in names:
        r = getattr(w, n)
        width = len(r) // 3
        setattr(w, n, r[:2 * width] + tuple(r[2 * width + i] + acc * sens[k + i] for i in range(width)))
        k += width


def addlink_rates(group, a, jac, order, records=None):
    """Exact Add-link rates by the implicit-function theorem, then the records at them.

    J adot = -df/dt|adot=0 with J the Newton Jacobian gives the rates at every order (they
    start the next row); at order 2, J addot = -d2f/dt2|addot=0 the accelerations.  With
    records (w and the names of the records the block sets) the pass at the rates leaves the
    records' positions and rates, and their accelerations are that pass's plus the Add-link
    accelerations times the records' sensitivities, as accelerations are linear in the
    Add-links' (Newton's last pass left the last Add-link's; the others' are measured again
    at a: the same bits); without, or at a singular J, one pass more with them.
    Returns the last pass's status, sigma and the block's orientation: the sign of det J,
    which stays the same along the assembly while the block's chains keep their branches
    (it changes only at a singular position; a solution of the other sign is another assembly).
    """
    n = len(a)
    zero = [0.0] * n
    _, det = solve_linear(jac, zero)
    sigma = conditioning(jac, det)
    turn = 1 if det > 0.0 else -1 if det < 0.0 else 0
    rates = accs = zero
    if det != 0.0:
        sens = []
        if order >= 2 and records is not None:
            sens = [[]] * (n - 1) + [sensitivities(*records)]
            for j in range(n - 1):
                group(a, [1.0 if i == j else 0.0 for i in range(n)], zero, False)
                sens[j] = sensitivities(*records)
        st, rec = group(a, zero, zero, True)
        rates, _ = solve_linear(jac, [-r[1] for r in rec])
        if order >= 2:
            st, rec = group(a, rates, zero, True)
            accs, _ = solve_linear(jac, [-r[2] for r in rec])
            if records is not None:
                for j in range(n):
                    bend(*records, sens[j], accs[j])
                return st, sigma, turn
    else:
        rates = accs = [NAN] * n
    st, _ = group(a, rates, accs, True)
    return st, sigma, turn


def resolve_variants(groups, a, first, order, prefer, sizes, chains, p, scale, loops=None, records=None, full=True):
    """The strategy's iteration (solve_block) on a group's blocks (its chosen Add-link
    candidate, then the fallbacks), the preferred block first, the others in order.  The
    first that converges with its chains conditioned at least p.min_chain_sigma (chains():
    the worst of the last pass, from the block's lever down) is kept; else the best
    conditioned of those that converge, a later block only when more than twice as well
    conditioned (a block whose chains are near a toggle is a poor coordinate of the
    assembly; blocks that share that chain tie up to rounding, and the order, not the
    rounding, decides).  A block whose state is stale (nan, see resolve_group) is not tried;
    where one was skipped in a row's own pass (not full), a row none of the others solves with
    its chains so conditioned fails as not converged (the driver follows it from the last row:
    a continuation pass, full, takes the best of the blocks it can try and reads every block's
    state, so the others are tried along the path).

    a[first + k] is block k's state: its sizes[k] start lengths, its branches, its orientation.
    Under strategy loop the loop blocks (loops[k] 1) come first, the Add-link blocks after.
    records: (w, the names of the records each block sets; see addlink_rates).
    Returns (k, iterations, sigma, orientation), k = -1 when no block converges, -2 when
    none does and the iteration of one of them did not contract.
    """
    its, best, best_sigma, stuck, stale = 0, -1, -1.0, False, False
    loops = loops or [0] * len(groups)
    tries = [prefer] + [j for j in range(len(groups)) if j != prefer]
    if p.strategy == "loop":
        tries = [k for k in tries if loops[k]] + [k for k in tries if not loops[k]]
    for k in tries:
        if a[first + k][0] != a[first + k][0]:  # a stale state: not read off this row's start
            stale = True
            continue
        ok, x, its, jac = solve_block(groups[k], a[first + k][:sizes[k]], p, scale, loops[k])
        stuck = stuck or ok < 0
        if ok <= 0:
            continue
        if chains() < p.min_chain_sigma:
            if chains() > 2 * best_sigma:
                best, best_sigma = k, chains()
            continue
        st, sigma, turn = addlink_rates(groups[k], x, jac, order, records and (records[0], records[1][k]))
        if st != 1:
            return k, its, sigma, turn
    if best >= 0 and (full or not stale):
        ok, x, its, jac = solve_block(groups[best], a[first + best][:sizes[best]], p, scale, loops[best])
        if ok > 0:
            st, sigma, turn = addlink_rates(groups[best], x, jac, order, records and (records[0], records[1][best]))
            if st != 1:
                return best, its, sigma, turn
    return -2 if stuck and (full or not stale) else -1, its, 0.0, 0


def resolve_group(groups, lengths, a, ad, first, slot, used, its, order, chains, m, p, records=None, full=True):
    """One resolver step: resolve_variants on the group's blocks, the one that solved the
    last row (used[slot]) first; then lengths(a, ad) reads every block's state and its rates
    off the solved pairs and the solving block keeps its orientation.  Unless full (a row's
    own pass) the other blocks' states, but a loop block's, are then stale: nan, orientation
    0 (a row's own pass needs the solving block's alone; a continuation pass, full, reads
    every block's, so that any of them can take over along the path).  its[slot] gets the
    iterations.  Returns (solved, sigma): solved 1, 0 where no block converged, -1 where a
    block's iteration did not contract."""
    count = len(groups)
    loops = m.loops[first:first + count]
    k, its[slot], sigma, turn = resolve_variants(groups, a, first, order, used[slot],
                                                 m.sizes[first:first + count], chains, p, m.length_scale,
                                                 loops, records, full)
    if k < 0:
        return (0 if k == -1 else -1), sigma
    used[slot] = k
    lengths(a, ad)
    a[first + k][-1] = float(turn)
    if not full:
        for j in range(count):
            if j != k and not loops[j]:
                a[first + j] = [NAN] * (len(a[first + j]) - 1) + [0.0]
    return 1, sigma
