# The closure strategy (options: strategy closure): Newton on all loop-closure equations of a
# resolver group at once, in the positions the group places, from where the first block that
# closes at its state puts them, then (polish) one step more; then every block's state is read off
# the solution and the resolver finishes the row from there (resolve_group, without a polishing
# step of its own: the block's Add-link residuals meet the tolerance at once; exact rates,
# conditioning, orientation).  c is the
# group's closure: c.place() the positions of the last pass, c.equations(x) -> (g, jac) the
# residuals (length units) and their Jacobian at positions x, c.adopt(x, a) puts x into the work
# and reads every block's state off it (lengths, branches).


def closure_newton(c, x, tol, max_iter, reach, polish):
    """Newton on the closure equations from positions x until max|g| <= tol, then (polish) one
    step more; at most max_iter steps, a polishing one too.  A solution farther than reach from
    the start is another assembly: refused.  Returns (ok, x, steps)."""
    start, its = x, 0
    while True:
        g, jac = c.equations(x)
        done = all(abs(v) <= tol for v in g)  # a nan fails every comparison
        if (done and not polish) or its == max_iter:
            break
        dx, det = solve_linear(jac, [-v for v in g])
        if det == 0.0:
            return False, x, its
        x = [u + d for u, d in zip(x, dx)]
        its += 1
        if done:
            break
    return done and all(abs(u - v) <= reach for u, v in zip(x, start)), x, its


def resolve_closure(c, groups, lengths, a, ad, first, slot, used, its, order, chains, m, p, records=None, full=True):
    """One resolver step by the closure strategy (resolve_group's arguments and result, c the
    group's closure): the positions start where the first block that closes at its state
    puts them (the one that solved the last row first, the others in order), Newton on the
    closure equations, every block's state read off the solution, then resolve_group from
    there (no polishing step there: the closure took it).  its[slot] gets the closure's Newton
    steps and the resolver's."""
    sizes = m.sizes[first:first + len(groups)]
    zero = [0.0] * max(sizes)
    tries = [k for k in [used[slot]] + [k for k in range(len(groups)) if k != used[slot]]
             if a[first + k][0] == a[first + k][0]]  # a stale state (nan) is not tried
    its[slot] = 0
    if not any(groups[k](a[first + k][:sizes[k]], zero, zero, False)[0] == 0 for k in tries):
        return False, 0.0
    ok, x, steps = closure_newton(c, c.place(), p.tolerance * m.length_scale, p.max_iterations,
                                  p.max_move * m.length_scale, p.polish)
    its[slot] = steps
    if not ok:
        return False, 0.0
    c.adopt(x, a)
    polished = type(p)(**{**vars(p), "polish": False})  # the closure's own step was the polishing one
    solved, sigma = resolve_group(groups, lengths, a, ad, first, slot, used, its, order, chains, m, polished, records,
                                  full)
    its[slot] += steps
    return solved, sigma
