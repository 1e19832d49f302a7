# The rows of a mechanism with resolvers, in order, each from the last (the Python runtime's row
# driver, drive(), on lanes).  A state holds, per lane, what a solved row leaves for the next
# one: its inputs and rates, every block's state (Add-link lengths, branches, orientation) and
# their rates, the block each group used, and whether the row solved (ok); for the second-order
# predictor the row before it (back_ok where there is one: its inputs and Add-link lengths).
#
# The rows are cut into chunks solved side by side, one row of every chunk a pass (a lane per
# chunk): the first row of a chunk starts from a seed, the state of the row before it as the
# chunks' last rows solved by themselves (the same sweep over every L-th row, one level up)
# give it.  Where a chunk's seed is not the state the chunk before it ends in, the chunk is
# solved again from that end, until every seed is.  A row the lanes cannot solve as the Python
# runtime would (no warm start, continuation, another block) is solved by the standard-library
# module's solve() from its lane's state.  k holds the kernel: run, publish, rows (the
# standard-library module), m (its MECHANISM), p (its POLICY), order, c, the columns x, dx, ddx
# of every row, out, status, sigma, its (the arrays a call fills) or None, and same (the columns
# of constant records, the same on every row: filled once, not carried through the passes).
# The chunks of the call's rows hold STEPS rows; a seeding sweep's SEED_STEPS (its passes are
# narrow, so their fixed cost counts most).

LANES = 16384  # rows solved side by side at most (measured: 7% faster than 8192 at 1e6 rows)
STEPS = 16  # rows of a chunk of the call's rows (fewer: one row at a time)
SEED_STEPS = 4  # rows of a chunk of a seeding sweep (narrow passes: their fixed cost dominates)
RATES_AGREE = 1e-6  # two states' rates agree to this share
ALONE = 48  # a sweep of no more rows is solved by the standard-library module, row after row


def state_of(s, idx):
    """The lanes idx of a state (a slice: views of its arrays)."""
    def pick(x):
        return [v[idx] for v in x]

    return SimpleNamespace(inputs=pick(s.inputs), rates=pick(s.rates), a=[pick(b) for b in s.a],
                           ad=[pick(b) for b in s.ad], used=pick(s.used), ok=s.ok[idx],
                           back_inputs=pick(s.back_inputs), back_a=[pick(b) for b in s.back_a],
                           back_ok=s.back_ok[idx])


def state_put(s, idx, t):
    """Lanes idx of state s (its arrays) set to those of state t."""
    for x, y in zip(s.inputs + s.rates + s.used + [s.ok] + s.back_inputs + [s.back_ok],
                    t.inputs + t.rates + t.used + [t.ok] + t.back_inputs + [t.back_ok]):
        x[idx] = y
    for b, c in zip(s.a + s.ad + s.back_a, t.a + t.ad + t.back_a):
        put(b, idx, c)


def state_cat(states):
    """One state of the lanes of several, in order."""
    def cat(arrays):
        return np.concatenate([np.atleast_1d(x) for x in arrays])

    s = states[0]
    return SimpleNamespace(inputs=[cat(x) for x in zip(*(t.inputs for t in states))],
                           rates=[cat(x) for x in zip(*(t.rates for t in states))],
                           a=[[cat(x) for x in zip(*b)] for b in zip(*(t.a for t in states))],
                           ad=[[cat(x) for x in zip(*b)] for b in zip(*(t.ad for t in states))],
                           used=[cat(x) for x in zip(*(t.used for t in states))],
                           ok=cat([t.ok for t in states]),
                           back_inputs=[cat(x) for x in zip(*(t.back_inputs for t in states))],
                           back_a=[[cat(x) for x in zip(*b)] for b in zip(*(t.back_a for t in states))],
                           back_ok=cat([t.back_ok for t in states])) if len(states) > 1 else s


def empty_state(k, lanes):
    """A state of lanes with no solved row (the sketch starts them)."""
    m, n = k.m, len(k.x)
    return SimpleNamespace(inputs=[np.zeros(lanes, dtype=REAL) for _ in range(n)],
                           rates=[np.zeros(lanes, dtype=REAL) for _ in range(n)],
                           a=[[np.full(lanes, v, dtype=REAL) for v in b] for b in m.sketch_a],
                           ad=[[np.zeros(lanes, dtype=REAL) for _ in b] for b in m.sketch_a],
                           used=[np.zeros(lanes, dtype=int) for _ in range(m.groups)], ok=np.zeros(lanes, dtype=bool),
                           back_inputs=[np.zeros(lanes, dtype=REAL) for _ in range(n)],
                           back_a=[[np.zeros(lanes, dtype=REAL) for _ in range(size)] for size in m.sizes],
                           back_ok=np.zeros(lanes, dtype=bool))


def agree(s, t, k, backs):
    """Lanes where two states of the same rows would start the next row alike: both failed, or
    both solved with the same blocks, branches and orientations (the signs of the entries past
    the lengths: a branch is held as a measure, see _lengths_N), lengths within the resolver's
    tolerance and rates within a millionth; with backs, the same row before (the second-order
    predictor's) with its lengths within the tolerance."""
    tol = k.p.tolerance * k.m.length_scale
    same = s.ok == t.ok
    for u, v in zip(s.used, t.used):
        same = same & (u == v)
    for b, c, n in zip(s.a, t.a, k.m.sizes):
        for i, (x, y) in enumerate(zip(b, c)):
            same = same & (_close(x, y, tol) if i < n else ((np.sign(x) == np.sign(y)) | (np.isnan(x) & np.isnan(y))))
    for b, c in zip(s.ad, t.ad):
        for x, y in zip(b, c):
            same = same & _close(x, y, RATES_AGREE * np.maximum(np.abs(x), np.abs(y)) + tol)
    if not backs:
        return same | ~(s.ok | t.ok)
    same = same & (s.back_ok == t.back_ok)
    for x, y in zip(s.back_inputs, t.back_inputs):
        same = same & (~s.back_ok | (x == y))
    for b, c in zip(s.back_a, t.back_a):
        for x, y in zip(b, c):
            same = same & (~s.back_ok | _close(x, y, tol))
    return same | ~(s.ok | t.ok)


def _close(x, y, bound):
    """Where x and y are within bound, or both nan."""
    return (np.abs(x - y) <= bound) | (x == y) | (np.isnan(x) & np.isnan(y))


def _tau(prev, x):
    """The Python runtime's _tau on every lane: how far inputs x lie from prev's along its rates."""
    den, num = 0.0, 0.0
    for r in prev.rates:
        den = den + r * r
    for xi, yi, r in zip(x, prev.inputs, prev.rates):
        num = num + (xi - yi) * r
    return np.where(den > 0, num / np.where(den > 0, den, 1.0), 0.0)


def predict_lanes(prev, x, sizes, order):
    """The Python runtime's predict on every lane: the block states along their rates to x (a
    chain's sign measure too, so its branch flips where it passes zero; an orientation has no
    rate); at order 2 the Add-link lengths along the parabola that also passes through the row
    before (where a lane has one at a distance other than 0: else along the rates)."""
    tau = _tau(prev, x)
    along = [[v + tau * r for v, r in zip(b, br)] for b, br in zip(prev.a, prev.ad)]
    out = [[np.abs(u) if i < n else u for i, u in enumerate(b)] for b, n in zip(along, sizes)]
    if order < 2 or not prev.back_ok.any():
        return out
    back = np.where(prev.back_ok, _tau(prev, prev.back_inputs), 0.0)
    curved = back != 0.0
    every = curved.all()  # the usual pass: no lane without a row before
    back2, tau2 = (back * back if every else np.where(curved, back * back, 1.0)), tau * tau
    for g, u, b, br, bb, n in zip(out, along, prev.a, prev.ad, prev.back_a, sizes):
        for i in range(n):  # v + tau r + tau^2 (b - v - back r) / back^2, as the runtime's order of operations
            ahead = np.abs(u[i] + tau2 * ((bb[i] - b[i] - back * br[i]) / back2))
            g[i] = ahead if every else np.where(curved, ahead, g[i])
    return out


def on_path_lanes(prev, guess, new, sizes, slack, p):
    """The Python runtime's on_path on every lane (a block looked at where its states in prev and new are not stale)."""
    move, turned = 0.0, False
    held = [~np.isnan(b[0]) & ~np.isnan(x[0]) for b, x in zip(prev, new)]
    for b, g, n, h in zip(prev, guess, sizes, held):
        for i in range(n):
            move = np.maximum(move, np.where(h, np.abs(g[i] - b[i]), 0.0))
    for b, x in zip(prev, new):
        turned = turned | (b[-1] * x[-1] < 0)
    bound = np.where(turned, p.turn_share, p.path_share) * move + slack
    fine = True
    for g, x, n, h in zip(guess, new, sizes, held):
        for i in range(n):
            fine = fine & (~h | (np.abs(x[i] - g[i]) <= bound))
    return fine


def advance(k, prev, rows, sink=None, spot=None):
    """Solve one row per lane (rows: their indices) from the lanes' last rows; returns the new
    state.  With a sink the rows are the call's own, solved as the Python runtime solves them,
    and their outputs go to the sink at spot (a pass and the lanes' chunks); without one they
    seed a finer sweep: a lane whose last row solved starts from it whatever the distance, and
    keeps what its resolvers find, as long as its block is the one that solved the last row.
    A lane the pass cannot settle is solved by the standard-library module."""
    m, p = k.m, k.p
    lanes = len(rows)
    x, dx, ddx = ([np.full(lanes, v, dtype=REAL) if np.ndim(v) == 0 else v[rows] for v in col]
                  for col in (k.x, k.dx, k.ddx))
    near = prev.ok.copy()
    if sink is not None:
        for xi, yi, lim in zip(x, prev.inputs, m.limits):
            near = near & (np.abs(xi - yi) <= lim)
    guess = predict_lanes(prev, x, m.sizes, p.predictor if sink is not None else 1)  # a seed: along the rates
    a, ad, used = [list(b) for b in guess], [list(b) for b in prev.ad], [u.copy() for u in prev.used]
    w, code, sigma, its, settled, past = k.run(x, dx, ddx, k.c, a, ad, used, k.order, ~near, m, p)
    code = np.broadcast_to(code, (lanes,))
    solved = code <= 0
    if sink is not None:
        solved = solved & on_path_lanes(prev.a, guess, a, m.sizes, p.path_slack * m.length_scale, p)
    followed = ~solved & ((code <= 0) | (reason_of(code) == m.not_converged))  # the runtime continues there
    alone = np.flatnonzero(~past & (~near | ~settled | followed))
    new = SimpleNamespace(inputs=x, rates=dx, a=a, ad=ad, used=used, ok=solved, back_inputs=prev.inputs,
                          back_a=[b[:n] for b, n in zip(prev.a, m.sizes)],
                          back_ok=solved & prev.ok if p.predictor == 2 else np.zeros(lanes, dtype=bool))
    if sink is not None:
        j, at = spot
        for name, value in zip(k.columns, k.publish(w, k.c)):
            if name not in sink.cols:
                continue
            if np.ndim(value):
                if name in k.same:
                    raise RuntimeError(f"column {name}: a number on some rows, an array on others")
                sink.cols[name][j, at] = value
            else:  # a constant record's field: the same on every row, filled once (see solve_sweep)
                k.same[name] = value
        sink.status[j, at] = code
        for n, value in enumerate(sigma):
            if not isinstance(value, float):
                sink_sigma(k, sink, n)[j, at] = value
        for g, value in enumerate(its):
            sink.its[g, j, at] = value
    if alone.size:
        new = state_of(new, np.arange(lanes))  # copies to write the lanes solved alone into
        for lane in alone:
            out, one = alone_row(k, state_of(prev, [lane]), rows[lane])
            state_put(new, [lane], one)
            if sink is not None:
                c = np.arange(sink.status.shape[1])[spot[1]][lane]  # the lane's place in the sink
                for name in sink.cols:
                    sink.cols[name][spot[0], c] = out[name]
                sink.status[spot[0], c], sink.its[:, spot[0], c] = out["status"], out["iterations"]
                for n, value in enumerate(out.get("sigma", ())):  # none without the checks
                    if value != 1.0 or n in sink.sigma:
                        sink_sigma(k, sink, n)[spot[0], c] = value
    return new


def alone_row(k, prev, row):
    """One row solved by the standard-library module from a one-lane state; returns its outputs
    and its state.  The module's warm start (its drive()'s) holds the inputs, rates, block states,
    their rates and the blocks used, then the row before them (its inputs and block states, of
    which the second-order predictor reads the Add-link lengths; None where there is none)."""
    warm = None
    if prev.ok[0]:
        back = ([float(v[0]) for v in prev.back_inputs], [[float(v[0]) for v in b] for b in prev.back_a]) \
            if prev.back_ok[0] else None
        warm = ([float(v[0]) for v in prev.inputs], [float(v[0]) for v in prev.rates],
                [[float(v[0]) for v in b] for b in prev.a], [[float(v[0]) for v in b] for b in prev.ad],
                [int(u[0]) for u in prev.used], back)
    state = {"warm": warm}
    x, dx, ddx = ([float(v if np.ndim(v) == 0 else v[row]) for v in col] for col in (k.x, k.dx, k.ddx))
    out = k.rows.solve(x, dx, ddx, k.order, state)
    new = empty_state(k, 1)
    warm = state["warm"]
    if warm is not None:
        ins, rates, a, ad, used, back = warm
        new.inputs, new.rates = [np.array([v], dtype=REAL) for v in ins], [np.array([v], dtype=REAL) for v in rates]
        new.a = [[np.array([v], dtype=REAL) for v in b] for b in a]
        new.ad = [[np.array([v], dtype=REAL) for v in b] for b in ad]
        new.used, new.ok = [np.array([u]) for u in used], np.array([True])
        if back is not None:
            new.back_inputs = [np.array([v], dtype=REAL) for v in back[0]]
            new.back_a = [[np.array([v], dtype=REAL) for v in b[:n]] for b, n in zip(back[1], k.m.sizes)]
            new.back_ok = np.array([True])
    return out, new


def layout(n, steps):
    """(rows a chunk, chunks) of a sweep of n rows in chunks of steps rows: one chunk where n is small."""
    return (max(n, 1), 1) if n <= steps else (steps, -(-n // steps))


def new_sink(k, steps, lanes):
    """Arrays for the outputs of lanes' rows over steps passes, each indexed [pass, lane]; the
    same arrays for every tile of a call (fresh memory is slow to touch)."""
    key = (steps, lanes)
    if key not in k.sinks:
        k.sinks[key] = SimpleNamespace(cols={name: made(k, key, REAL) for name in k.out}, status=made(k, key, int),
                                       sigma={}, its=made(k, (k.its.shape[0], *key), int))
    sink = k.sinks[key]
    for value in sink.sigma.values():
        value.fill(1.0)
    return sink


def made(k, shape, dtype):
    """A new array for the call's sinks (a spare one where there is one, see fresh), kept as
    spare for the next call."""
    k.made.append(fresh(shape, dtype))
    return k.made[-1]


def sink_sigma(k, sink, n):
    """The sink's array of step n's conditioning (made at its first value; 1 where none came)."""
    if n not in sink.sigma:
        sink.sigma[n] = made(k, sink.status.shape, REAL)
        sink.sigma[n].fill(1.0)
    return sink.sigma[n]


def flush(k, sink, rows, lengths):
    """The sink's outputs into the call's arrays: pass j of lane i is row rows[i, j] where j is
    below the lane's length.  Whole chunks of consecutive rows are copied straight into a view of
    the arrays (one strided copy a column), the rest through a mask."""
    lanes, steps = rows.shape
    whole = lanes - int(lengths[-1] < steps)  # the leading chunks all of whose rows are there
    first = int(rows[0, 0])
    if not (whole and (lengths[:whole] == steps).all() and rows[whole - 1, -1] - first == whole * steps - 1):
        whole = 0  # not consecutive rows: all through the mask
    if whole:
        at = slice(first, first + whole * steps)

        def copy(into, value):
            np.copyto(into[at].reshape(whole, steps), value[:, :whole].T)

        copy_all(k, sink, copy)
    if whole < lanes:
        mask = np.arange(steps) < lengths[whole:, None]
        at = rows[whole:][mask]

        def copy(into, value):
            into[at] = value[:, whole:].T[mask]

        copy_all(k, sink, copy)


def copy_all(k, sink, copy):
    """copy(the call's array, the sink's) for every output, status, conditioning and Newton steps."""
    for name, value in sink.cols.items():
        if name not in k.same:
            copy(k.out[name], value)
    copy(k.status, sink.status)
    for n, value in sink.sigma.items():
        copy(k.sigma[n], value)
    for g in range(k.its.shape[0]):
        copy(k.its[g], sink.its[g])


def sweep(k, seq, prev, emit=False, keep=False):
    """Solve the rows seq (their indices, in order) from prev (a one-lane state of the row before),
    their outputs into the call's arrays (emit; see advance); returns the state after every row
    (keep) or None."""
    n = len(seq)
    kept = empty_state(k, n) if keep else None
    if n <= ALONE or not k.lanes:  # few rows: one by one, faster than passes of a lane or two
        for j, row in enumerate(seq):
            out, prev = alone_row(k, prev, row)
            if emit:
                for name in k.out:
                    k.out[name][row] = out[name]
                k.status[row], k.sigma[:, row], k.its[:, row] = out["status"], out.get("sigma", 1.0), out["iterations"]
            if keep:
                state_put(kept, [j], prev)
        return kept
    steps, chunks = layout(n, STEPS if emit else SEED_STEPS)
    starts = np.arange(chunks) * steps
    first = prev if chunks == 1 else state_cat([prev, seeds(k, seq, starts[1:], prev, emit)])
    ends = run_tiles(k, seq, starts, steps, np.arange(chunks), first, emit, kept)
    fixing = False
    while True:  # a chunk whose seed is not where the chunk before it ends is solved again from there
        wrong = np.flatnonzero(~agree(state_of(first, slice(1, None)), state_of(ends, slice(None, -1)), k, emit))
        if not wrong.size:
            return kept
        if not fixing:  # copies to write into (a pass's states hold views)
            first, ends, fixing = state_of(first, np.arange(chunks)), state_of(ends, np.arange(chunks)), True
        again = state_of(ends, wrong)
        state_put(first, wrong + 1, again)
        state_put(ends, wrong + 1, run_tiles(k, seq, starts, steps, wrong + 1, again, emit, kept))


def seeds(k, seq, starts, prev, emit):
    """The states of the rows before starts (positions in seq), from a sweep over them one level up
    from prev.  Seeding the call's own rows (emit) at the second-order predictor, the sweep is over
    the rows two before, and one pass of lanes goes on from each to the row after it, so a seed
    holds the row before it as the one-by-one rows do (a seeding sweep's lanes predict along the
    rates, and its seeds are checked without the rows before)."""
    if k.p.predictor != 2 or not emit:
        return sweep(k, seq[starts - 1], prev, False, True)
    before = sweep(k, seq[starts - 2], prev, False, True)
    return state_cat([advance(k, state_of(before, slice(t, t + LANES)), seq[starts[t:t + LANES] - 1])
                      for t in range(0, len(starts), LANES)])


def run_tiles(k, seq, starts, steps, chunks, prev, emit, kept):
    """Solve the chunks given (their indices), LANES of them side by side at a time, each from
    its lane of prev (the state before its first row); returns the state after each one's last row."""
    if len(chunks) <= LANES:
        return run_chunks(k, seq, starts, steps, chunks, prev, emit, kept)
    return state_cat([run_chunks(k, seq, starts, steps, chunks[t:t + LANES], state_of(prev, slice(t, t + LANES)), emit,
                                 kept) for t in range(0, len(chunks), LANES)])


def run_chunks(k, seq, starts, steps, chunks, prev, emit, kept):
    """Solve the chunks given (their indices) side by side, each from its lane of prev; returns
    the state after each one's last row."""
    lengths = np.minimum(starts[chunks] + steps, len(seq)) - starts[chunks]
    ends, order = [], []  # the states of the chunks' last rows, and their places in chunks
    lanes = np.arange(len(chunks))  # the chunks still running, by their place in chunks
    sink = new_sink(k, steps, len(chunks)) if emit else None
    for j in range(int(lengths.max())):
        running = lengths[lanes] > j
        if not running.all():
            lanes, prev = lanes[running], state_of(prev, np.flatnonzero(running))
        at = starts[chunks[lanes]] + j
        prev = advance(k, prev, seq[at], sink, (j, slice(None) if lanes.size == len(chunks) else lanes))
        if kept is not None:
            state_put(kept, at, prev)
        last = lengths[lanes] == j + 1
        if last.all():
            ends.append(prev)
            order.append(lanes)
        elif last.any():
            ends.append(state_of(prev, np.flatnonzero(last)))
            order.append(lanes[last])
    if emit:
        flush(k, sink, seq[np.minimum(starts[chunks][:, None] + np.arange(steps), len(seq) - 1)], lengths)
    order = np.concatenate(order)
    ends = state_cat(ends)
    return ends if (order == np.arange(len(chunks))).all() else state_of(ends, np.argsort(order))


def solve_sweep(run, publish, rows, inputs, d_inputs, dd_inputs, order, params, m, out=None):
    """Every row of a call in the order of the flattened rows, each from the last as the
    standard-library module (rows) solves them, written into new arrays or those of out (see
    filled).  Returns finish's dict with "iterations" (Newton steps per group and row)."""
    if params:
        raise ValueError(f"{m.name}.solve: design parameters need a mechanism without resolver groups")
    shape, columns, c = rows_of(inputs, d_inputs, dd_inputs, design(None, m), m)
    n = int(np.prod(shape))
    bad = np.broadcast_to(refused(columns, m), (n,))
    out, status, sigma, new, fresh_arrays = filled(out, shape, order, m)
    its = np.zeros((rows.N_GROUPS, n), dtype=int)
    p = SimpleNamespace(**{**vars(rows.POLICY), "tolerance": m.tolerance, "path_slack": m.path_slack})
    k = SimpleNamespace(run=run, publish=publish, rows=rows, m=rows.MECHANISM, p=p, order=order, c=c,
                        x=columns[0], dx=columns[1], ddx=columns[2], out=out, status=status, sigma=sigma, its=its,
                        columns=m.columns, sinks={}, lanes=m.lanes, same={}, made=fresh_arrays)
    with np.errstate(all="ignore"):
        sweep(k, np.flatnonzero(~bad), empty_state(k, 1), True)
    lose({name: x for name, x in out.items() if name not in k.same}, status, sigma, bad, m)
    keep_same(out, k.same, new, status, m)  # the columns of constant records, the lanes' value on every row
    keep_spare(k.made)
    result = shaped(out, status, sigma, shape, m)
    result["iterations"] = its.reshape((rows.N_GROUPS, *shape))
    return result
