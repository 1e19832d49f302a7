# The row driver: one row of a sweep solved on the sketch's assembly, from the previous
# row where it can (Taylor-predicted start), else by continuation from the previous row or
# from the sketch.  run(inputs, rates, accs, order, a, used, row) is one pass of the
# procedure with the block states a and the preferred blocks used (both updated in place to
# the solution); it returns (status code, the block states' rates); row says whether the
# pass is the row's own (else a pass along a continuation path).  m holds the mechanism's
# resolver data (length_scale, sketch_inputs, sketch_a, sizes, limits, periodic, low,
# groups, another, not_converged), p the resolver policy (the step log's).


def advance(a, rates, step, sizes, loops):
    """Block states moved by step along their rates.  An Add-link length is a distance:
    where its prediction passes zero the two pairs pass each other, so it is reflected (a
    loop block's arc length, loops[k] 1, is an angle: it is not).  A
    branch's measure moves too: where it passes zero the chain passes its fold and goes on
    on its other branch, as a chain outside the groups does at a change point."""
    return [[abs(v + step * r) if i < n and not loop else v + step * r for i, (v, r) in enumerate(zip(g, gr))]
            for g, gr, n, loop in zip(a, rates, sizes, loops)]


def predict(warm, inputs, sizes, order, loops):
    """The path the assembly is expected on at new inputs: the warm states advanced along
    their rates (order 1: first-order Taylor in the warm row's input direction), or along
    the parabola with those rates that also passes through the row before them (order 2;
    warm[5] holds its inputs and states, None where there was none: then first order).
    Both need positions and rates only, and rates exist at every order, so a program gives
    the same positions whatever order it computes."""
    w_in, w_rates, a, ad = warm[:4]
    tau = _tau(w_in, w_rates, inputs)
    back = _tau(w_in, w_rates, warm[5][0]) if order == 2 and warm[5] is not None else 0.0
    if back == 0.0:
        return advance(a, ad, tau, sizes, loops)
    out = []
    tt, bb = tau * tau, back * back
    for g, gr, gb, n, loop in zip(a, ad, warm[5][1], sizes, loops):
        ahead = [v + tau * r for v, r in zip(g, gr)]  # the lengths bend along the parabola, the rest go straight
        for i in range(n):
            x = ahead[i] + tt * ((gb[i] - g[i] - back * gr[i]) / bb)
            ahead[i] = x if loop else abs(x)
        out.append(ahead)
    return out


def _tau(w_in, w_rates, inputs):
    """How far inputs lie from w_in along the rates w_rates, in time (0 without rates)."""
    den = sum(r * r for r in w_rates)
    return sum((x - y) * r for x, y, r in zip(inputs, w_in, w_rates)) / den if den > 0 else 0.0


def within(inputs, last, limits):
    """Whether no input moved farther from the last row than a continuation step."""
    return all(abs(x - y) <= lim for x, y, lim in zip(inputs, last, limits))


def on_path(prev, guess, new, sizes, slack, p):
    """Whether a solved state new is where the predictor guess pointed from prev: no
    block's Add-link length moved from the guess by more than p.path_share of the largest
    predicted move (plus slack); a larger correction is a jump to another assembly, or a step
    too long for the curve.  A block that solved both and turned its orientation (the last
    entry of a block's state, after its sizes[k] lengths and its branches; 0 where it did not
    solve) has passed a singular position.  Where two assemblies pass close the nearer one can
    lie within that share, so a turned block must be within p.turn_share: the path crosses the
    singular position along its tangent, as a mechanism goes straight through a change point.
    Only the blocks with a state in prev and new are looked at (a stale one, nan, has none: a
    row's own pass judged on its solving blocks; a continuation's on every block)."""
    held = [(p_, g, x, n) for p_, g, x, n in zip(prev, guess, new, sizes) if p_[0] == p_[0] and x[0] == x[0]]
    move = max((abs(g[i] - p_[i]) for p_, g, _, n in held for i in range(n)), default=0.0)
    share = p.turn_share if any(p_[-1] * x[-1] < 0.0 for p_, x in zip(prev, new)) else p.path_share
    return all(abs(x[i] - g[i]) <= share * move + slack for _, g, x, n in held for i in range(n))


def continuation(run, base, a, target, m, p):
    """Follow the assembly from inputs base (solved with block states a) to target.

    Angle inputs go the shorter way round, else the other way; where the one input is an
    angle with a reach (the values it reaches from the sketch, modulo whole turns, from m.low
    up; m.low is nan without one; base and target are inside it), it goes the one way round
    that stays inside the reach.  run(inputs, rates, order, a) -> (ok, a, rates) solves with
    input rates per unit of the path (see walk).  Returns the block states at target, or
    None when the way (both ways without a reach) is cut.
    """
    if m.periodic[0] and m.low == m.low:
        turns = [x - 2 * PI * floor((x - m.low) / (2 * PI)) for x in (base[0], target[0])]
        return walk(run, base, a, [base[0] + turns[1] - turns[0]], m, p)
    goal = [t - 2 * PI * floor((t - b) / (2 * PI) + 0.5) if q else t for t, b, q in zip(target, base, m.periodic)]
    reached = walk(run, base, a, goal, m, p)
    other = [(g - 2 * PI if g > b else g + 2 * PI if g < b else g) if q else g
             for g, b, q in zip(goal, base, m.periodic)]
    if reached is None and other != goal:
        reached = walk(run, base, a, other, m, p)
    return reached


def walk(run, base, a, goal, m, p):
    """Continuation along the straight path from base to goal.  Each step moves no input
    by more than its limit (m.limits) and no Add-link length, as predicted, by more than
    p.max_move of the length scale; it starts Newton from the tangent predictor and is
    halved where Newton fails or lands off the path (see on_path), up to p.max_halvings
    times in a row.  Near a singular position the lengths' rates are large and the steps
    short (the prediction holds only there); a step that makes no progress in floating
    point cuts the path, and so do p.walk_passes passes (at once where the path needs more
    steps than that).  Returns the block states at goal, or None where the path is cut."""
    slack, reach, sizes = p.path_slack * m.length_scale, p.max_move * m.length_scale, m.sizes
    d = [g - b for g, b in zip(goal, base)]
    h_max = min([1.0] + [lim / abs(x) for lim, x in zip(m.limits, d) if x != 0.0])
    if h_max * p.walk_passes < 1.0:
        return None
    ok, a, rate = run(base, d, 1, a)
    if not ok:
        return None
    t, h, cuts, passes = 0.0, h_max, 0, 1
    while t < 1.0:
        if passes == p.walk_passes:
            return None
        passes += 1
        fast = max((abs(r[i]) for r, n in zip(rate, sizes) for i in range(n) if r[i] == r[i]), default=0.0)
        if fast * h > reach:
            h = reach / fast
        tt = min(1.0, t + h)
        if tt == t:
            return None
        trial = [b + tt * x for b, x in zip(base, d)] if tt < 1.0 else goal
        guess = advance(a, rate, tt - t, sizes, m.loops)
        ok, a2, rate2 = run(trial, d, 1, guess)
        if ok and on_path(a, guess, a2, sizes, slack, p):
            t, a, rate, h, cuts = tt, a2, rate2, min(2 * h, h_max), 0
        else:
            h, cuts = h / 2, cuts + 1
            if cuts > p.max_halvings:
                return None
    return a


def drive(run, warm, inputs, rates, accs, order, past, m, p):
    """Solve one row on the sketch's assembly.  From the previous row's warm start
    (inputs, rates, block states, their rates, the blocks used, the row before it) when no
    input has moved farther than a continuation step: the resolvers start where the
    predictor of order p.predictor points (see predict; order 0: from the warm states as
    they were), and the row is taken when it solves on that path (see on_path; order 0: the
    first-order one).  Else, or where the warm start fails at a resolver or lands off the
    path, the assembly is followed by continuation from the previous row (or, without one,
    from the sketch) and the row solved from there; where the way is cut but the row solves
    all the same it is on another assembly only, and gets the code m.another.  A row past
    the reach (past) fails at once.  Returns (status code, the warm start for the next row,
    None where it failed).
    """
    base, a = m.sketch_inputs, [list(g) for g in m.sketch_a]
    used = list(warm[4]) if warm else [0] * m.groups
    code, ad, solved = 0, None, False
    if past:  # past a limit position: the pass fails the row at once with the limit's code
        code, ad = run(inputs, rates, accs, order, a, used, True)
    elif warm and within(inputs, warm[0], m.limits):
        guess = predict(warm, inputs, m.sizes, max(p.predictor, 1), m.loops)
        a = [list(g) for g in (guess if p.predictor else warm[2])]  # order 0: the warm states as they were
        code, ad = run(inputs, rates, accs, order, a, used, True)
        solved = code <= 0 and on_path(warm[2], guess, a, m.sizes, p.path_slack * m.length_scale, p)
    if warm and not solved:
        base, a, used = list(warm[0]), [list(g) for g in warm[2]], list(warm[4])
    if not solved and (code <= 0 or reason_of(code) == m.not_converged):
        prefer = list(used)

        def path(x, d, o, s):
            s = [list(g) for g in s]
            st, sd = run(x, d, [0.0] * len(x), o, s, list(prefer), False)
            return st <= 0, s, sd

        reached = continuation(path, base, a, list(inputs), m, p)
        if reached is not None:
            a = reached
        code, ad = run(inputs, rates, accs, order, a, used, 2)  # every block's state read: the next row tries any
        if reached is None and code <= 0:
            code = m.another  # another assembly only
        solved = code <= 0
    if not solved:
        return code, None
    back = (warm[0], warm[2]) if warm and p.predictor == 2 and code != m.another else None
    return code, (list(inputs), list(rates), a, ad, used, back)
