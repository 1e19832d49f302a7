# Over-constraint resolver: Newton-Raphson on the Add-link lengths.
# group(a, da, dda, live) runs the steps of one resolver group with the Add-link lengths
# a, their rates da and accelerations dda (as records of the program's order) and returns
# (status, f) with f the residual records; live=False zeroes the rates of everything the
# group reads, so a unit Add-link rate gives one exact Jacobian column through the
# velocity channel.  p is the resolver policy (the step log's), scale the length scale.


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


def newton(group, a, tol, max_iter, reach, halvings):
    """Iterate the Add-link lengths until max|f| <= tol, then one step more.

    A solution farther than reach from the start lengths is another assembly: refused.

    Returns (ok, a, iterations, jac) with jac the Jacobian at the returned a.
    A step that makes a chain fail to close is halved (up to halvings times; then the
    block fails and the next block is tried).
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
        for _ in range(halvings + 1):
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
    zero = [0.0] * n
    _, det = solve_linear(jac, zero)
    sigma = conditioning(jac, det)
    rates = accs = zero
    if det != 0.0:
        st, rec = group(a, zero, zero, True)
        rates, _ = solve_linear(jac, [-r[1] for r in rec])
        if order >= 2:
            st, rec = group(a, rates, zero, True)
            accs, _ = solve_linear(jac, [-r[2] for r in rec])
    else:
        rates = accs = [NAN] * n
    st, _ = group(a, rates, accs, True)
    return st, sigma, 1 if det > 0.0 else -1 if det < 0.0 else 0


def resolve_variants(groups, a, first, order, prefer, sizes, chains, p, scale):
    """Newton on a group's blocks (its chosen Add-link candidate, then the fallbacks), the
    preferred block first, the others in order.  The first that converges with its chains
    conditioned at least p.min_chain_sigma (chains(): the worst of the last pass, from the
    block's lever down) is kept; else the best conditioned of those that converge, a later
    block only when more than twice as well conditioned (a block whose chains are near a
    toggle is a poor coordinate of the assembly; blocks that share that chain tie up to
    rounding, and the order, not the rounding, decides).

    a[first + k] is block k's state: its sizes[k] start lengths, its branches, its orientation.
    Returns (k, Newton steps, sigma, orientation), k = -1 when no block converges.
    """
    tol, reach = p.tolerance * scale, p.max_move * scale
    its, best, best_sigma = 0, -1, -1.0
    for k in [prefer] + [j for j in range(len(groups)) if j != prefer]:
        ok, x, its, jac = newton(groups[k], a[first + k][:sizes[k]], tol, p.max_iterations, reach, p.newton_halvings)
        if not ok:
            continue
        if chains() < p.min_chain_sigma:
            if chains() > 2 * best_sigma:
                best, best_sigma = k, chains()
            continue
        st, sigma, turn = addlink_rates(groups[k], x, jac, order)
        if st != 1:
            return k, its, sigma, turn
    if best >= 0:
        ok, x, its, jac = newton(groups[best], a[first + best][:sizes[best]], tol, p.max_iterations, reach,
                                 p.newton_halvings)
        if ok:
            st, sigma, turn = addlink_rates(groups[best], x, jac, order)
            if st != 1:
                return best, its, sigma, turn
    return -1, its, 0.0, 0


def resolve_group(groups, lengths, a, ad, first, slot, used, its, order, chains, m, p):
    """One resolver step: resolve_variants on the group's blocks, the one that solved the
    last row (used[slot]) first; then lengths(a, ad) reads every block's state and its rates
    off the solved pairs (so any of them can start the next row) and the solving block keeps
    its orientation.  its[slot] gets the Newton steps.  Returns (solved, sigma)."""
    k, its[slot], sigma, turn = resolve_variants(groups, a, first, order, used[slot],
                                                 m.sizes[first:first + len(groups)], chains, p, m.length_scale)
    if k < 0:
        return False, sigma
    used[slot] = k
    lengths(a, ad)
    a[first + k][-1] = float(turn)
    return True, sigma
