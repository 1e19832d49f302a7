# The over-constraint resolver on lanes of rows: the Python runtime's Newton-Raphson on the
# Add-link lengths (resolver.py of NAME.py), every lane at once with its own convergence.
# A block b is b.run(w, r, br, a, da, dda): its steps on the lanes, r the records it reads from
# before the group, br its chains' branches, a, da, dda the Add-link lengths, rates and
# accelerations; it returns (the steps' reports, their conditioning, the residual records, the
# worst conditioning of its chains) and leaves its records in w.  A lane is one row's pass.


def take(x, idx):
    """Lanes idx of an array, of a record (tuple) or of a list of them (a number stays)."""
    if isinstance(x, (tuple, list)):
        return type(x)(take(v, idx) for v in x)
    if isinstance(idx, slice):
        return x
    return x[idx] if isinstance(x, np.ndarray) and x.ndim else x


def put(into, idx, x):
    """into[idx] = x for every array of a record (into: arrays of all lanes)."""
    for target, value in zip(into, x):
        target[idx] = value


def still(record, width):
    """A record with its rates zeroed: its first width fields (the position) kept."""
    return tuple(record[:width]) + (0.0,) * (len(record) - width)


def solve_lanes(m, b):
    """m x = b on every lane (m[i][j], b[i] arrays of lanes) by Gaussian elimination with partial
    pivoting, the first largest pivot as the Python runtime's solve_linear takes it; returns
    (x, det), x nan and det 0 on a lane with a zero pivot."""
    n = len(b)
    if n == 1:  # one Add-link: the same operations, without the pivot search
        det = np.asarray(m[0][0], dtype=REAL)
        x = np.asarray(b[0], dtype=REAL) / det
        det = det if det.shape == x.shape else np.broadcast_to(det, x.shape)
        zero = det == 0
        if zero.any():
            return [np.where(zero, NAN, x)], np.where(zero, 0.0, det)
        return [x], det
    a = [[np.asarray(v, dtype=REAL) for v in row] + [np.asarray(b[i], dtype=REAL)] for i, row in enumerate(m)]
    det = np.ones(np.broadcast_shapes(*(v.shape for row in a for v in row)), dtype=REAL)
    zero = det == 0
    for c in range(n):
        p, best = np.full(det.shape, c), np.abs(a[c][c])
        for r in range(c + 1, n):
            bigger = np.abs(a[r][c]) > best
            p, best = np.where(bigger, r, p), np.where(bigger, np.abs(a[r][c]), best)
        zero = zero | (best == 0)
        for r in range(c + 1, n):
            swap = p == r
            if swap.any():
                for j in range(c, n + 1):
                    a[c][j], a[r][j] = np.where(swap, a[r][j], a[c][j]), np.where(swap, a[c][j], a[r][j])
                det = np.where(swap, -det, det)
        det = det * a[c][c]
        for r in range(c + 1, n):
            k = a[r][c] / a[c][c]
            for j in range(c, n + 1):
                a[r][j] = a[r][j] - k * a[c][j]
    x = [None] * n
    for r in range(n - 1, -1, -1):
        s = 0.0
        for j in range(r + 1, n):
            s = s + a[r][j] * x[j]
        x[r] = (a[r][n] - s) / a[r][r]
    if zero.any():
        x = [np.where(zero, NAN, v) for v in x]
        det = np.where(zero, 0.0, det)
    return x, det


def block_pass(b, w, r, br, a, da, dda, fast=False):
    """One pass of block b (at order 1 where fast): (failed lanes, residual records, chains,
    reports, conditioning)."""
    report, sigma, f, chains = (b.run1 if fast else b.run)(w, r, br, a, da, dda)
    failed = False
    for st, _ in report:
        failed = failed | (st == 1)
    return np.broadcast_to(failed, np.shape(a[0])), f, chains, report, sigma


def jacobian_lanes(b, w, r, br, a):
    """Residuals and Jacobian at a (one pass at order 1 per Add-link, unit rate, r the reads
    still): (failed lanes, f, jac, chains of the last pass, sensitivities), each an array of the
    lanes; the sensitivities are the rates of the block's records at each unit rate, in the
    order of b.writes, Add-link after Add-link."""
    n, lanes = len(a), np.shape(a[0])
    failed, f, jac, chains, sens = False, None, [[None] * n for _ in range(n)], None, []
    for j in range(n):
        unit = [1.0 if i == j else 0.0 for i in range(n)]
        bad, rec, chains, _, _ = block_pass(b, w, r, br, a, unit, unit, True)
        failed = failed | bad
        f = [lanes_of(x[0], lanes[0]) for x in rec]
        for i in range(n):
            jac[i][j] = lanes_of(rec[i][1], lanes[0])
        for name, _, width in b.writes:
            sens += [lanes_of(v, lanes[0]) for v in getattr(w, name)[width:2 * width]]
    return np.array(failed), f, jac, lanes_of(chains, lanes[0]), sens


def newton_lanes(b, w, r, br, a, tol, max_iter, reach, halvings):
    """The Python runtime's newton on every lane: iterate until max|f| <= tol, then one step
    more; a step that makes a chain fail is halved up to halvings times; a solution farther
    than reach from the start is refused.  Returns (ok, a, its, jac, chains, sensitivities),
    each of all the lanes (a, jac, chains and the sensitivities of the last pass where ok)."""
    lanes, n = np.shape(a[0])[0], len(a)
    ok, its = np.zeros(lanes, dtype=bool), np.zeros(lanes, dtype=int)
    out_a = [np.full(lanes, NAN, dtype=REAL) for _ in range(n)]
    out_jac = [[np.full(lanes, NAN, dtype=REAL) for _ in range(n)] for _ in range(n)]
    out_chains = np.full(lanes, NAN, dtype=REAL)
    out_sens = None
    failed, f, jac, _, _ = jacobian_lanes(b, w, r, br, a)
    idx, start = np.arange(lanes), a
    for it in range(1, max_iter + 1):
        if failed.any():  # these lanes end here
            keep = ~failed
            idx, a, start, f, jac, r, br = (take(x, keep) for x in (idx, a, start, f, jac, r, br))
        if not idx.size:
            break
        its[idx] = it
        dx, det = solve_lanes(jac, [-v for v in f])
        t = np.ones(idx.size, dtype=REAL)
        trial = [x + d for x, d in zip(a, dx)]
        failed, f2, jac2, chains, sens = jacobian_lanes(b, w, r, br, trial)
        failed = failed | (det == 0)
        for _ in range(halvings):  # a step that makes a chain fail: halved
            again = np.flatnonzero(failed & (det != 0))
            if not again.size:
                break
            t[again] = t[again] / 2
            part = [take(x, again) + t[again] * take(d, again) for x, d in zip(a, dx)]
            bad, fp, jp, cp, sp = jacobian_lanes(b, w, take(r, again), take(br, again), part)
            trial, f2, sens = _replaced(trial, part, again), _replaced(f2, fp, again), _replaced(sens, sp, again)
            chains = _replaced([chains], [cp], again)[0]
            jac2 = [_replaced(row, part_row, again) for row, part_row in zip(jac2, jp)]
            failed[again] = bad
        done = ~failed
        for v in f:
            done = done & (np.abs(v) <= tol)
        a, f, jac = trial, f2, jac2
        if idx.size == lanes and done.all():  # every lane converged at once (the usual row): no copies
            for x, s in zip(a, start):
                done = done & (np.abs(x - s) <= reach)
            return done, a, its, jac, np.asarray(chains, dtype=REAL), sens
        if done.any():
            near = done
            for x, s in zip(a, start):
                near = near & (np.abs(x - s) <= reach)
            at = idx[done]
            ok[at] = near[done]
            for k in range(n):
                out_a[k][at] = a[k][done]
                for j in range(n):
                    out_jac[k][j][at] = jac[k][j][done]
            out_chains[at] = chains[done]
            if out_sens is None:
                out_sens = [np.full(lanes, NAN, dtype=REAL) for _ in sens]
            for o, v in zip(out_sens, sens):
                o[at] = v[done]
            failed = failed | done
    return ok, out_a, its, out_jac, out_chains, out_sens or []


def _replaced(arrays, parts, idx):
    """Copies of the arrays with the entries idx replaced by those of parts."""
    out = []
    for x, p in zip(arrays, parts):
        x = np.array(x, dtype=REAL)
        x[idx] = p
        out.append(x)
    return out


def conditioning(jac, det):
    """|det J| over the product of its column norms (at least 1), on every lane."""
    prod = 1.0
    for j in range(len(jac)):
        s = 0.0
        for row in jac:
            s = s + row[j] * row[j]
        prod = prod * np.sqrt(s)
    return np.abs(det) / np.maximum(prod, 1.0)


def rates_lanes(b, w, r, br, a, jac, sens, order):
    """The Python runtime's addlink_rates on every lane: the Add-link rates (and at order 2 the
    accelerations) by the implicit-function theorem, then the final pass, which leaves the
    block's records in w (r: the reads as they are).  The final pass is the pass at the rates:
    its accelerations are the pass's plus the Add-link accelerations times the records'
    sensitivities (sens, from Newton's last pass: the same positions), as accelerations are
    linear in them.  Returns (failed lanes, sigma, orientation, reports, conditioning)."""
    n = len(a)
    zero = [0.0] * n
    _, det = solve_lanes(jac, zero)
    sigma = conditioning(jac, det)
    _, rec, _, _, _ = block_pass(b, w, r, br, a, zero, zero, True)
    rates, _ = solve_lanes(jac, [-x[1] for x in rec])
    if (det == 0).any():  # no rates at a singular Jacobian
        rates = [np.where(det == 0, NAN, x) for x in rates]
    failed, rec, _, report, steps = block_pass(b, w, r, br, a, rates, zero)
    if order >= 2:
        accs, _ = solve_lanes(jac, [-x[2] for x in rec])
        if (det == 0).any():
            accs = [np.where(det == 0, NAN, x) for x in accs]
        k = 0
        for j in range(n):
            for name, _, width in b.writes:
                record = list(getattr(w, name))
                for i in range(width):
                    record[2 * width + i] = record[2 * width + i] + accs[j] * sens[k + i]
                setattr(w, name, tuple(record))
                k += width
    return failed, sigma, np.sign(det), report, steps
