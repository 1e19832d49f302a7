def resolve_lanes(w, g, a, ad, used, order, sigma, report, skip, m, p):
    """One resolver step on lanes: the Python runtime's resolve_group on each lane's row where the
    block that solved the last row (used[g.slot]) solves this one at once (its Newton converges
    with its chains conditioned at least p.min_chain_sigma, and its final pass closes).  Those
    lanes get the block's records in w, its steps' reports and conditioning, and the block's
    state (a) and its rates (ad) read off the solution; the other blocks' states, but a loop
    block's, are stale there (nan, orientation 0: a row's own pass of resolve_group).  The
    other lanes are left unsettled, for the caller to solve one by one; the skipped ones count
    as settled.  Returns (settled lanes, Newton steps)."""
    lanes = np.shape(skip)[0]
    tol, reach = p.tolerance * m.length_scale, p.max_move * m.length_scale
    settled, its = skip.copy(), np.zeros(lanes, dtype=int)
    cond, turn, solver = np.ones(lanes, dtype=REAL), np.zeros(lanes, dtype=REAL), np.full(lanes, -1)
    prefer = used[g.slot]
    written = {}
    only = None  # the block that solved every lane, if one did
    for k, b in enumerate(g.blocks):
        mine = (prefer == k) & ~skip
        at = np.flatnonzero(mine)
        if not at.size:
            continue
        pick = slice(None) if at.size == lanes else at  # every lane: no copies
        state = take(a[g.first + k], pick)
        live = tuple(take(getattr(w, name), pick) for name, _ in b.reads)
        frozen = tuple(still(record[:2 * width], width) for record, (_, width) in zip(live, b.reads))
        br = tuple(np.where(s < 0, -1, 1) for s in state[b.size:b.size + b.branches])
        wb = copy.copy(w)
        ok, x, steps, jac, chains, sens = newton_lanes(b, wb, frozen, br, state[:b.size], tol, p.max_iterations, reach,
                                                       p.newton_halvings)
        its[at] = steps
        good = np.flatnonzero(ok & (chains >= p.min_chain_sigma))
        if not good.size:
            continue
        if good.size < at.size:
            x, jac, live, br, sens = (take(v, good) for v in (x, jac, live, br, sens))
        failed, cond_b, turn_b, rep, sig = rates_lanes(b, wb, live, br, x, jac, sens, order)
        whole = good.size == lanes and not failed.any()
        if whole:  # every lane solved by this block: its arrays as they are
            fine, only = slice(None), k
            settled[:], cond, turn, solver[:] = True, np.asarray(cond_b, dtype=REAL), np.asarray(turn_b, dtype=REAL), k
        else:
            fine = np.flatnonzero(~failed)
            done = at[good[fine]]
            settled[done], cond[done], turn[done], solver[done] = True, cond_b[fine], turn_b[fine], k
        for name, fields, _ in b.writes:
            record = getattr(wb, name)
            if whole:  # every lane solved by this block: its records as they are
                written[name] = record
                continue
            if name not in written:
                written[name] = tuple(np.full(lanes, NAN, dtype=REAL) for _ in range(fields))
            put(written[name], done, take(record, fine))
        for st, codes in rep:
            if whole:
                report.append((st, codes))
                continue
            full = np.zeros(lanes, dtype=int)
            full[done] = np.broadcast_to(st, failed.shape)[fine]
            report.append((full, codes))
        for n, s in sig.items():
            if whole:
                sigma[n] = s
                continue
            if isinstance(sigma[n], float):
                sigma[n] = np.full(lanes, sigma[n], dtype=REAL)
            sigma[n][done] = np.broadcast_to(s, failed.shape)[fine]
    resolved = settled & ~skip
    for name, fields, _ in g.blocks[0].writes:  # what the procedure reads after the group: nan where unsolved
        if name not in written:
            written[name] = tuple(np.full(lanes, NAN, dtype=REAL) for _ in range(fields))
    for name, record in written.items():
        setattr(w, name, record)
    if resolved.any():
        new_a, new_ad = g.lengths(w, a)
        none = np.zeros(lanes, dtype=REAL)
        for j in range(g.count):
            orient = np.where(solver == j, turn, 0.0) if only is None else turn if j == only else none
            if m.loops[g.first + j]:
                a[g.first + j] = [lanes_of(x, lanes) for x in new_a[j][:-1]] + [orient]
            elif only is None:
                mine = solver == j
                a[g.first + j] = [np.where(mine, x, NAN) for x in new_a[j][:-1]] + [orient]
            else:
                a[g.first + j] = ([lanes_of(x, lanes) for x in new_a[j][:-1]] if j == only
                                  else [np.full(lanes, NAN, dtype=REAL) for _ in new_a[j][:-1]]) + [orient]
            ad[g.first + j] = [lanes_of(x, lanes) for x in new_ad[j]]
    report.append((np.where(resolved & (cond < g.singular), 3, np.where(resolved & (cond < g.near), 4, 0)), g.codes))
    sigma[g.step] = cond
    return settled, its


def lanes_of(x, lanes):
    """x as an array of the lanes (a number or an array of them)."""
    return x if np.shape(x) == (lanes,) else np.broadcast_to(x, (lanes,))


def failed_lanes(report, lanes):
    """Lanes where a step reported so far cannot close."""
    out = np.zeros(lanes, dtype=bool)
    for st, _ in report:
        out = out | (st == 1)
    return out


def span(j1, j2):
    """The distance of two points and its rate, on lanes: link_residual of a zero length, the same
    operations (where the points coincide, the rate as they part), without its checks."""
    dx, dy = j2[0] - j1[0], j2[1] - j1[1]
    dvx, dvy = j2[2] - j1[2], j2[3] - j1[3]
    r = np.sqrt(dx * dx + dy * dy)
    rate = (dx * dvx + dy * dvy) * (1 / r)
    together = r == 0
    if np.any(together):
        rate = np.where(together, np.sqrt(dvx * dvx + dvy * dvy), rate)
    return r, rate

