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
    """The flat arrays a call fills (its columns up to order, status, sigma), the names of the
    columns whose arrays are new and the arrays it made (see fresh, keep_spare): those of out, a
    dict an earlier call returned for rows of this shape, else new ones, the columns the rows
    of arrays of up to SHARED bytes (see there; a column never written costs no memory).  A
    read-only column of out (one number on every row, see keep_same) gets a new array.  sigma
    holds 1.0 where ones, else whatever the memory held."""
    n = int(np.prod(shape))
    names = [name for name, level in zip(m.columns, m.levels) if level <= order]
    flat = {}
    if out is not None:
        wanted = [(name, shape, REAL) for name in names] + [("status", shape, int)]
        if m.checks:
            wanted.append(("sigma", (m.n_steps + 1, *shape), REAL))
        for name, like, dtype in wanted:
            a = out.get(name)
            if not (isinstance(a, np.ndarray) and a.shape == like and a.dtype == dtype
                    and (a.flags.c_contiguous or not a.flags.writeable)):
                raise ValueError(f"{m.name}.solve: out has no {np.dtype(dtype).name} array of shape {like} "
                                 f"for {name!r}")
            if a.flags.writeable:
                flat[name] = a.reshape(-1) if name != "sigma" else a.reshape(m.n_steps + 1, n)
    new = [name for name in names if name not in flat]
    per = max(1, SHARED // max(1, n * np.dtype(REAL).itemsize))  # columns an array
    made = [fresh((min(per, len(new) - k), n), REAL) for k in range(0, len(new), per)]
    flat.update(zip(new, (x for a in made for x in a)))
    if "status" not in flat:
        made.append(fresh((n,), int))
        flat["status"] = made[-1]
    if "sigma" not in flat:  # new, or the call's own where it gives no conditioning
        made.append(fresh((m.n_steps + 1, n), REAL))
        flat["sigma"] = made[-1]
    if ones:
        flat["sigma"].fill(1.0)
    return {name: flat[name] for name in names}, flat["status"], flat["sigma"], set(new), made


# The arrays of the last call's new outputs, by (shape, dtype): the next call takes those that
# nothing else holds any longer instead of new memory (the system's fresh memory costs its first
# touch: measured 25-30 ns a row of the four-bar at 1e6 rows, a third of its time; the allocator
# hands a call's 32 MB arrays back to the system when they are freed).  SPARE.clear() frees them.
SPARE = {}


def _held_by_one():
    a = np.empty(0)
    return sys.getrefcount(a)


HELD_BY_ONE = _held_by_one()  # sys.getrefcount of an array only one local name holds


def _raise_thresholds():
    """Free one 16 MB array (never touched): glibc's malloc then serves blocks up to that size from
    its heap and keeps up to twice it there.  It does so at the first large array a process frees;
    with SPARE a process may free none, and then gives the heap of a block's temporaries back to
    the system and takes it again at every block (measured: the four-bar 1.5x slower at 1e5 rows)."""
    a = np.empty(2**21)
    del a


_raise_thresholds()


def fresh(shape, dtype):
    """A new array for a call's outputs: a spare one (see SPARE) that only this function holds
    now, else np.empty."""
    spare = SPARE.get((shape, np.dtype(dtype).str))
    while spare:
        try:
            a = spare.pop()
        except IndexError:  # another thread took the last one
            break
        if sys.getrefcount(a) == HELD_BY_ONE:  # no result, view or buffer of a caller holds it
            return a
    return np.empty(shape, dtype=dtype)


def keep_spare(made):
    """The arrays a call made become SPARE, in place of the last call's (a call that made none,
    into the arrays of out, leaves SPARE as it is)."""
    if not made:
        return
    spare = {}
    for a in made:
        spare.setdefault((a.shape, a.dtype.str), []).append(a)
    SPARE.clear()
    SPARE.update(spare)


def keep_same(cols, same, new, status, m):
    """The columns of constant records (same: column -> the one number of every row) into cols,
    the call's flat arrays, after the other columns: a read-only view of the number (no memory
    written) where the column's array is new (in new) and no row has lost it, else the number
    filled in, the rows that lose it nan (see lose; a refused row's status is m.bad_input)."""
    lost = bool((status > 0).any())
    written = {}
    for name, value in same.items():
        if name in new and not lost:
            cols[name] = np.broadcast_to(np.asarray(value, dtype=REAL), status.shape)
        else:
            cols[name].fill(value)
            written[name] = cols[name]
    if lost and written:
        lose(written, status, None, status == m.bad_input, m)


def is_same(value, known):
    """Whether a block's value of a column is the number known, bit for bit (or both nan)."""
    if value is known:
        return True
    if np.ndim(value):
        return False
    a, b = np.asarray(value, dtype=REAL), np.asarray(known, dtype=REAL)
    return a.tobytes() == b.tobytes() or bool(np.isnan(a) and np.isnan(b))


def solve_rows(run, publish, inputs, d_inputs, dd_inputs, order, params, m, out=None):
    """Every row of a call, a block at a time: run(x, dx, ddx, c) solves a block (its records,
    the rows' status codes and each step's conditioning), publish(w, c) gives its columns,
    written into new arrays or those of out (see filled), the programs' rules applied to the
    block while it is in the cache (see lose).  A column that is one number on every row (a
    constant record's) is not written row by row but put in at the end (see keep_same).
    Returns shaped's dict.  A row that fails is nan by design: numpy does not warn of it."""
    shape, columns, c = rows_of(inputs, d_inputs, dd_inputs, design(params, m), m)
    n = int(np.prod(shape))
    out, status, sigma, new, made = filled(out, shape, order, m, ones=False)
    same = {}  # column -> the number every row so far has (none written yet)
    with np.errstate(all="ignore"):
        for s in range(0, n, BLOCK):
            e = min(s + BLOCK, n)
            x, dx, ddx = ([block(v, s, e) for v in col] for col in columns)
            cb = {k: block(v, s, e) for k, v in c.items()}
            w, status[s:e], steps = run(x, dx, ddx, cb)
            cols = {}
            for name, value in zip(m.columns, publish(w, cb)):
                if name not in out:
                    continue
                if s == 0 and not np.ndim(value):
                    same[name] = value
                    continue
                if name in same:
                    if is_same(value, same[name]):
                        continue
                    out[name][:s] = same.pop(name)  # no longer one number: the rows before written
                    lose({name: out[name][:s]}, status[:s], None, status[:s] == m.bad_input, m)
                cols[name] = out[name][s:e]
                cols[name][...] = value
            if m.checks:
                for k, value in enumerate(steps):
                    sigma[k, s:e] = value
            lose(cols, status[s:e], sigma[:, s:e] if m.checks else None, refused((x, dx, ddx), m), m)
    keep_same(out, same, new, status, m)
    keep_spare(made)
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
    out, status, sigma, _, made = filled(out, shape, order, m)
    state = {}
    for r in np.flatnonzero(~bad):
        x, dx, ddx = ([float(v if np.ndim(v) == 0 else v[r]) for v in col] for col in columns)
        row = solve(x, dx, ddx, order, state)
        for name in out:
            out[name][r] = row[name]
        status[r] = row["status"]
        if m.checks:
            sigma[:, r] = row["sigma"]
    keep_spare(made)
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
