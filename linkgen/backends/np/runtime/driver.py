# The row driver of the vectorised kernel: the inputs, rates and accelerations of a call (their
# last axis the inputs) and its design parameters broadcast together and flattened into rows,
# solved a block of rows at a time so that every array a block makes stays in the cache.
# m holds the module's data (name, n_inputs, n_steps, reads, max_input, levels, columns,
# failed, singular, bad_input, params, checks).

BLOCK = 16384  # rows a block (measured: 20% faster than 4096, as fast as 32768)
# A call's new columns are the rows of arrays of up to SHARED bytes: large enough for the
# allocator's huge pages (a first touch once per 2 MB, not per 4 kB), small enough to come back
# from the heap on the next call (measured, CPU time, on 51 and 110 columns of 1e5 and 1e6 rows:
# as fast as an array a column to 1.8x faster; one array for all, above 64 MB, 2x to 9x slower).
SHARED = 32 * 2**20


def design(params, m):
    """The design parameters: the sketch's (m.params) with those given in place, each a number
    or an array."""
    c = dict(m.params)
    for name, value in (params or {}).items():
        if name not in c:
            raise ValueError(f"{m.name}.solve: {name!r} is not a design parameter (see PARAMS)")
        value = np.asarray(value, dtype=REAL)
        c[name] = REAL(value) if value.ndim == 0 else value
    return c


def rows_of(inputs, d_inputs, dd_inputs, c, m):
    """The broadcast shape of the rows and, flattened to it, the columns of the three arrays
    and the design parameters (one that is the same on every row stays a number)."""
    columns = []
    for what, a in (("inputs", inputs), ("d_inputs", d_inputs), ("dd_inputs", dd_inputs)):
        a = np.asarray(a, dtype=REAL)
        if a.ndim == 0 or a.shape[-1] != m.n_inputs:
            raise ValueError(f"{m.name}.solve: the last axis of {what} must hold the {m.n_inputs} inputs, "
                             f"not shape {a.shape}")
        columns.append([a[..., k] for k in range(m.n_inputs)])
    shape = np.broadcast_shapes(*(x.shape for col in columns for x in col), *(np.shape(v) for v in c.values()))

    def flat(x):
        x = np.asarray(x)
        return REAL(x.reshape(-1)[0]) if x.size == 1 else np.broadcast_to(x, shape).reshape(-1)

    return shape, [[flat(x) for x in col] for col in columns], {k: flat(v) for k, v in c.items()}


def refused(columns, m):
    """Rows with an input the procedure reads (the first m.reads arrays) not finite or larger
    than m.max_input in size."""
    bad = False
    for col in columns[: m.reads]:
        for x in col:
            fine = np.abs(x) <= m.max_input
            if not fine.all():
                bad = bad | ~fine
    return bad


def block(x, s, e):
    """Rows s to e of a flattened column (a number is the same on every row)."""
    return x[s:e] if isinstance(x, np.ndarray) else x


def filled(out, shape, order, m, ones=True):
    """The flat arrays a call fills (its columns up to order, status, sigma): those of out, a
    dict an earlier call returned for rows of this shape, else new ones, the columns the rows
    of arrays of up to SHARED bytes (see there).  sigma holds 1.0 where ones, else whatever
    the memory held."""
    n = int(np.prod(shape))
    names = [name for name, level in zip(m.columns, m.levels) if level <= order]
    if out is None:
        per = max(1, SHARED // max(1, n * np.dtype(REAL).itemsize))  # columns an array
        reals = [x for k in range(0, len(names), per) for x in np.empty((min(per, len(names) - k), n), dtype=REAL)]
        sigma = np.empty((m.n_steps + 1, n), dtype=REAL)
        if ones:
            sigma.fill(1.0)
        return dict(zip(names, reals)), np.empty(n, dtype=int), sigma
    wanted = [(name, shape, REAL) for name in names] + [("status", shape, int)]
    if m.checks:
        wanted.append(("sigma", (m.n_steps + 1, *shape), REAL))
    flat = {}
    for name, like, dtype in wanted:
        a = out.get(name)
        if not (isinstance(a, np.ndarray) and a.shape == like and a.dtype == dtype and a.flags.c_contiguous):
            raise ValueError(f"{m.name}.solve: out has no {np.dtype(dtype).name} array of shape {like} for {name!r}")
        flat[name] = a.reshape(-1) if name != "sigma" else a.reshape(m.n_steps + 1, n)
    if "sigma" not in flat:  # the call's own where it gives no conditioning
        flat["sigma"] = np.empty((m.n_steps + 1, n), dtype=REAL)
    if ones:
        flat["sigma"].fill(1.0)
    return {name: flat[name] for name in names}, flat["status"], flat["sigma"]


def solve_rows(run, publish, inputs, d_inputs, dd_inputs, order, params, m, out=None):
    """Every row of a call, a block at a time: run(x, dx, ddx, c) solves a block (its records,
    the rows' status codes and each step's conditioning), publish(w, c) gives its columns,
    written into new arrays or those of out (see filled), the programs' rules applied to the
    block while it is in the cache (see lose).  Returns shaped's dict.  A row that fails is
    nan by design: numpy does not warn of it."""
    shape, columns, c = rows_of(inputs, d_inputs, dd_inputs, design(params, m), m)
    n = int(np.prod(shape))
    out, status, sigma = filled(out, shape, order, m, ones=False)
    with np.errstate(all="ignore"):
        for s in range(0, n, BLOCK):
            e = min(s + BLOCK, n)
            x, dx, ddx = ([block(v, s, e) for v in col] for col in columns)
            cb = {k: block(v, s, e) for k, v in c.items()}
            w, status[s:e], steps = run(x, dx, ddx, cb)
            cols = {}
            for name, value in zip(m.columns, publish(w, cb)):
                if name in out:
                    cols[name] = out[name][s:e]
                    cols[name][...] = value
            if m.checks:
                for k, value in enumerate(steps):
                    sigma[k, s:e] = value
            lose(cols, status[s:e], sigma[:, s:e] if m.checks else None, refused((x, dx, ddx), m), m)
    return shaped(out, status, sigma, shape, m)


def solve_each(solve, inputs, d_inputs, dd_inputs, order, params, m, out=None):
    """Every row of a call in turn through a solve of one row (the standard-library module's,
    whose resolver starts each row from the last; state: its warm start), written into new
    arrays or those of out (see filled).  Returns finish's dict."""
    if params:
        raise ValueError(f"{m.name}.solve: design parameters need a mechanism without resolver groups")
    shape, columns, _ = rows_of(inputs, d_inputs, dd_inputs, {}, m)
    n = int(np.prod(shape))
    bad = np.broadcast_to(refused(columns, m), (n,))
    out, status, sigma = filled(out, shape, order, m)
    state = {}
    for r in np.flatnonzero(~bad):
        x, dx, ddx = ([float(v if np.ndim(v) == 0 else v[r]) for v in col] for col in columns)
        row = solve(x, dx, ddx, order, state)
        for name in out:
            out[name][r] = row[name]
        status[r] = row["status"]
        if m.checks:
            sigma[:, r] = row["sigma"]
    return finish(out, status, sigma, bad, shape, m)


def finish(out, status, sigma, bad, shape, m):
    """The columns, "status" and "sigma" (sigma[n]: step n's conditioning), each of the rows'
    shape, with the programs' rules (see lose)."""
    lose(out, status, sigma, bad, m)
    return shaped(out, status, sigma, shape, m)


def lose(out, status, sigma, bad, m):
    """The programs' rules on the flat arrays of some rows: a refused row (bad) has status
    m.bad_input and nan everywhere, a failed one nan outputs, one at a singular position nan
    derivatives (sigma None: no conditioning kept)."""
    if np.any(bad):
        bad = np.broadcast_to(bad, status.shape)
        status[bad] = m.bad_input
        if sigma is not None:
            sigma[:, bad] = np.nan
    elif not (status > 0).any():  # every row solved (a positive code is a failure's)
        return
    reason = reason_of(status)
    failed = bad
    for code in m.failed:
        failed = failed | (reason == code)
    singular = failed | (reason == m.singular)
    for name, level in zip(m.columns, m.levels):
        lost = failed if level == 0 else singular
        if name in out and lost.any():
            out[name][lost] = np.nan


def shaped(out, status, sigma, shape, m):
    """The dict a call returns: the flat arrays in the rows' shape (sigma with the checks)."""
    result = {name: x.reshape(shape) for name, x in out.items()}
    result["status"] = status.reshape(shape)
    if m.checks:
        result["sigma"] = sigma.reshape((m.n_steps + 1, *shape))
    return result
