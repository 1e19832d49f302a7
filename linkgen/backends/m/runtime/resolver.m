function [x, det] = solve_linear(m, b)
    % Solve m x = b by Gaussian elimination with partial pivoting; det(m) too.
    n = numel(b);
    a = [m, b(:)];
    det = 1;
    x = NaN(n, 1);
    for c = 1:n
        [~, p] = max(abs(a(c:n, c)));
        p = p + c - 1;
        if a(p, c) == 0
            det = 0;
            return;
        end
        if p ~= c
            a([c, p], :) = a([p, c], :);
            det = -det;
        end
        det = det * a(c, c);
        for r = c + 1:n
            k = a(r, c) / a(c, c);
            a(r, c:n + 1) = a(r, c:n + 1) - k * a(c, c:n + 1);
        end
    end
    for r = n:-1:1
        s = a(r, n + 1);
        for j = r + 1:n
            s = s - a(r, j) * x(j);
        end
        x(r) = s / a(r, r);
    end
end

function [ok, f, jac, w] = resolver_jacobian(group, w, a)
    % Residuals and Jacobian at a, one pass per Add-link; ok is false when a chain cannot close.
    % group(w, a, da, dda, live) -> [st, res, w] runs a group's steps with the Add-link lengths
    % a, their rates da and accelerations dda (live false zeroes the rates of what it reads
    % from outside); res has a row per residual: its value and derivatives.
    n = numel(a);
    jac = zeros(n, n);
    f = zeros(n, 1);
    zero = zeros(n, 1);
    for j = 1:n
        unit = zero;
        unit(j) = 1;
        [st, res, w] = group(w, a, unit, zero, false);
        if st
            ok = false;
            return;
        end
        f = res(:, 1);
        jac(:, j) = res(:, 2);
    end
    ok = true;
end

function [ok, a, its, jac, w] = resolver_newton(group, w, a, tol, max_iter, reach, halvings, polish)
    % Iterate the Add-link lengths until max|f| <= tol, then (polish) one step more; a step
    % that makes a chain fail to close is halved (up to halvings times; then the block fails
    % and the next block is tried).  The cap counts every step, a polishing one too.  A
    % solution farther than reach from the start is another assembly and refused.  ok is 1
    % or 0; jac the Jacobian at the returned a.
    its = 0;
    start = a;
    ok = 0;
    [closed, f, jac, w] = resolver_jacobian(group, w, a);
    if ~closed
        return;
    end
    for it = 1:max_iter
        done = all(abs(f) <= tol);  % a NaN fails every comparison (max would skip it)
        if done && ~polish
            ok = all(abs(a - start) <= reach);
            return;
        end
        its = it;
        [dx, det] = solve_linear(jac, -f);
        if det == 0
            return;
        end
        t = 1;
        for halving = 0:halvings
            trial = a + t * dx;
            [closed, f2, jac2, w] = resolver_jacobian(group, w, trial);
            if closed
                break;
            end
            t = t / 2;
        end
        if ~closed
            return;
        end
        a = trial;
        f = f2;
        jac = jac2;
        if done
            ok = all(abs(a - start) <= reach);
            return;
        end
    end
    ok = ~polish && all(abs(f) <= tol) && all(abs(a - start) <= reach);
end

function [ok, a, its, jac, w] = resolver_fixed_point(group, w, a, tol, max_iter, reach, halvings, polish)
    % The literature's iteration on the decomposed group: the group's chains run round the
    % loop from the Add-link lengths a, and a <- a - J0 \ f(a) with J0 the Jacobian at the
    % start (one pass per iteration instead of one per Add-link), until max|f| <= tol, then
    % (polish) one step more.  It converges where the map contracts: a step whose residual
    % is not smaller than the last one's (the ratio |f_k+1| / |f_k| at least 1) stops the
    % iteration, and so does the cap (every step counts, a polishing one too).  A step that
    % makes a chain fail to close is halved (up to halvings times); a NaN residual fails the
    % block.  The Jacobian at the solution is then measured for the exact rates (jac).  A
    % solution farther than reach from the start is another assembly and refused.  ok is 1,
    % 0, or -1 where the iteration does not contract.
    its = 0;
    start = a;
    ok = 0;
    jac = [];
    n = numel(a);
    zero = zeros(n, 1);
    [closed, f, j0, w] = resolver_jacobian(group, w, a);
    if ~closed
        return;
    end
    while ~all(abs(f) <= tol)
        if its == max_iter - polish
            return;
        end
        its = its + 1;
        [dx, det] = solve_linear(j0, -f);
        if det == 0
            return;
        end
        t = 1;
        for halving = 0:halvings
            trial = a + t * dx;
            [st, res, w] = group(w, trial, zero, zero, false);
            if ~st
                break;
            end
            t = t / 2;
        end
        if st || any(isnan(res(:, 1)))
            return;
        end
        if max(abs(res(:, 1))) >= max(abs(f))
            ok = -1;
            return;
        end
        a = trial;
        f = res(:, 1);
    end
    if polish
        its = its + 1;
        [dx, det] = solve_linear(j0, -f);
        if det == 0
            return;
        end
        a = a + dx;
    end
    [closed, ~, jac, w] = resolver_jacobian(group, w, a);
    ok = closed && all(abs(a - start) <= reach);
end

function [ok, a, its, jac, w] = resolver_loop(group, w, a, tol, max_iter, reach, polish)
    % The literature's iteration on a loop block (strategy loop): from the assumed angle, as
    % the leg's arc length a, the chains run round the loop and the angle that comes back is
    % the next one, a <- a + f(a), until |f| <= tol and the distance left to the fixed point,
    % |f| q / (1 - q) with q the last ratio of steps, is too, then (polish) one step more.  It converges
    % where the map contracts: the ratio of successive steps |f_k+1| / |f_k| estimates |g'|,
    % and at least 1 stops it (ok -1; the reverse loop, whose slope is the reciprocal, is the
    % next block); so do the cap and a chain that cannot close (ok 0).  The Jacobian at the
    % solution (g' - 1) gives the exact rates; a solution farther than reach from the start
    % is another assembly.
    ok = 0;
    its = 0;
    jac = [];
    start = a;
    [st, res, w] = group(w, a, 0, 0, false);
    if st
        return;
    end
    f = res(1, 1);
    q = 0;
    while ~(abs(f) <= tol && abs(f) * q <= tol * (1 - q))  % the error |f| q / (1 - q) too
        if its == max_iter - polish
            return;
        end
        its = its + 1;
        trial = a + f;
        [st, res, w] = group(w, trial, 0, 0, false);
        if st || isnan(res(1, 1))
            return;
        end
        if abs(res(1, 1)) >= abs(f)
            ok = -1;
            return;
        end
        q = abs(res(1, 1)) / abs(f);
        a = trial;
        f = res(1, 1);
    end
    if polish
        its = its + 1;
        a = a + f;
    end
    [closed, ~, jac, w] = resolver_jacobian(group, w, a);
    ok = closed && abs(a - start) <= reach;
end

function [ok, a, its, jac, w] = resolver_solve_block(group, w, a, p, scale, loop)
    % The resolver strategy's iteration on one block from its start lengths a: the one place
    % a strategy is chosen (p.strategy; loop: 1 for a loop block, which strategy loop
    % iterates by resolver_loop, its other blocks by Newton).  Returns what resolver_newton
    % and resolver_fixed_point return.
    tol = p.tolerance * scale;
    reach = p.max_move * scale;
    if strcmp(p.strategy, 'loop') && loop
        [ok, a, its, jac, w] = resolver_loop(group, w, a, tol, p.max_iterations, reach, p.polish);
    elseif strcmp(p.strategy, 'fixed-point')
        [ok, a, its, jac, w] = resolver_fixed_point(group, w, a, tol, p.max_iterations, reach, p.newton_halvings, ...
                                                    p.polish);
    else
        [ok, a, its, jac, w] = resolver_newton(group, w, a, tol, p.max_iterations, reach, p.newton_halvings, p.polish);
    end
end

function s = resolver_sensitivities(w, names)
    % The rates of the records names of w (their fields dX), one row: as a Jacobian pass
    % leaves them, the records' sensitivities to an Add-link.
    s = [];
    for i = 1:numel(names)
        r = w.(names{i});
        f = fieldnames(r);
        for k = 1:numel(f)
            if f{k}(1) == 'd' && (numel(f{k}) < 2 || f{k}(2) ~= 'd')
                s(end + 1) = r.(f{k});
            end
        end
    end
end

function w = resolver_bend(w, names, s, acc)
    % The records names of w with acc times their sensitivities s (resolver_sensitivities'
    % order) added to their accelerations (the fields ddX).
    j = 0;
    for i = 1:numel(names)
        r = w.(names{i});
        f = fieldnames(r);
        for k = 1:numel(f)
            if f{k}(1) == 'd' && (numel(f{k}) < 2 || f{k}(2) ~= 'd')
                j = j + 1;
                r.(['d', f{k}]) = r.(['d', f{k}]) + acc * s(j);
            end
        end
        w.(names{i}) = r;
    end
end

function [st, sigma, turn, w] = resolver_rates(group, w, a, jac, order, names)
    % Exact Add-link rates by the implicit-function theorem (at every order: they start
    % the next row), the accelerations at order 2.  With names (the records the block sets)
    % the pass at the rates leaves the records' positions and rates, and their accelerations
    % are that pass's plus the Add-link accelerations times the records' sensitivities, as
    % accelerations are linear in the Add-links' (Newton's last pass left the last
    % Add-link's; the others' are measured again at a: the same bits); without, or at a
    % singular J, one pass more with them.  turn is the block's orientation, sign(det J): it
    % stays the same along the assembly while the block's chains keep their branches (a
    % solution of the other sign is another assembly).
    n = numel(a);
    zero = zeros(n, 1);
    bent = order >= 2 && exist('names', 'var');
    sens = cell(n, 1);
    if bent
        sens{n} = resolver_sensitivities(w, names);
        for j = 1:n - 1
            unit = zero;
            unit(j) = 1;
            [~, ~, w] = group(w, a, unit, zero, false);
            sens{j} = resolver_sensitivities(w, names);
        end
    end
    [~, res, w] = group(w, a, zero, zero, true);
    [rates, det] = solve_linear(jac, -res(:, 2));
    prod = 1;
    for j = 1:n
        prod = prod * sqrt(sum(jac(:, j) .^ 2));
    end
    sigma = abs(det) / max(prod, 1);
    turn = sign(det);
    accs = zero;
    if order >= 2
        [st, res, w] = group(w, a, rates, zero, true);
        accs = solve_linear(jac, -res(:, 3));
        if bent && det ~= 0
            for j = 1:n
                w = resolver_bend(w, names, sens{j}, accs(j));
            end
            return;
        end
        if det == 0
            accs = NaN(n, 1);
        end
    end
    [st, ~, w] = group(w, a, rates, accs, true);
end

function [k, its, sigma, turn, w] = resolver_variants(groups, w, a, first, order, prefer, sizes, loops, p, scale, ...
                                                      writes, full)
    % The strategy's iteration (resolver_solve_block) on a group's blocks (its chosen Add-link
    % candidate, then the fallbacks), the preferred block first, the others in order.  The
    % first that converges with its chains conditioned at least p.min_chain_sigma (w.chains:
    % the worst of the last pass, from the block's lever down) is kept; else the best
    % conditioned of those that converge, a later block only when more than twice as well
    % conditioned (blocks that share a chain near a toggle tie up to rounding: the order
    % decides).  A block whose state is stale (nan, see resolver_group) is not tried; where
    % one was skipped in a row's own pass (not full), a row none of the others solves with
    % its chains so conditioned fails as not converged (the driver follows it from the last
    % row: a continuation pass, full, takes the best of the blocks it can try and reads every
    % block's state, so the others are tried along the path).
    % a{first + k} is block k's state: its sizes(k + 1) start lengths, its
    % branches, its orientation; scale is the length scale; k = -1 when no block converges
    % (-2 when the iteration of one of them did not contract); turn is the orientation of
    % block k (see resolver_rates, which gets writes{k + 1}: the records block k sets).
    its = 0;
    sigma = 0;
    turn = 0;
    best = -1;
    best_sigma = -1;
    stuck = false;
    stale = false;
    tries = [prefer, setdiff(0:numel(groups) - 1, prefer)];
    if strcmp(p.strategy, 'loop')  % the loop blocks first, the Add-link blocks after
        tries = [tries(loops(tries + 1) ~= 0), tries(loops(tries + 1) == 0)];
    end
    for k = tries
        if isnan(a{first + k}(1))  % a stale state: not read off this row's start
            stale = true;
            continue;
        end
        [ok, x, its, jac, w] = resolver_solve_block(groups{k + 1}, w, a{first + k}(1:sizes(k + 1)), p, scale, ...
                                                    loops(k + 1));
        stuck = stuck || ok < 0;
        if ok <= 0
            continue;
        end
        if w.chains < p.min_chain_sigma
            if w.chains > 2 * best_sigma
                best = k;
                best_sigma = w.chains;
            end
            continue;
        end
        [st, sigma, turn, w] = resolver_rates(groups{k + 1}, w, x, jac, order, writes{k + 1});
        if st ~= 1
            return;
        end
    end
    k = best;
    if k >= 0 && (full || ~stale)
        [ok, x, its, jac, w] = resolver_solve_block(groups{k + 1}, w, a{first + k}(1:sizes(k + 1)), p, scale, ...
                                                    loops(k + 1));
        if ok > 0
            [st, sigma, turn, w] = resolver_rates(groups{k + 1}, w, x, jac, order, writes{k + 1});
            if st ~= 1
                return;
            end
        end
    end
    k = -1 - (stuck && (full || ~stale));
end

function [ok, its, sigma, w, a, ad, used] = resolver_group(groups, lengths, w, a, ad, used, first, slot, order, m, p, ...
                                                           writes, full)
    % One resolver step: resolver_variants on the group's blocks a{first}, ... (the one that
    % solved the last row, used(slot), first); then lengths(w, a, ad) reads every block's
    % state and its rates off the solved pairs and the solving block keeps its orientation.
    % Unless full (a row's own pass) the other blocks' states, but a loop block's, are then
    % stale: nan, orientation 0 (a continuation pass, full, reads every block's, so that any
    % of them can take over along the path).  ok: 1 when a block solved, 0 when none
    % converged, -1 when the iteration of one did not contract; its: its iterations.
    [k, its, sigma, turn, w] = resolver_variants(groups, w, a, first, order, used(slot), ...
                                                 m.sizes(first:first + numel(groups) - 1), ...
                                                 m.loops(first:first + numel(groups) - 1), p, m.length_scale, ...
                                                 writes, full);
    ok = 1;
    if k < 0
        ok = -(k == -2);  % 0: none converged, -1: an iteration did not contract
        return;
    end
    used(slot) = k;
    [a, ad] = lengths(w, a, ad);
    a{first + k}(end) = turn;
    if ~full
        for j = 0:numel(groups) - 1
            if j ~= k && ~m.loops(first + j)
                a{first + j}(:) = NaN;
                a{first + j}(end) = 0;
            end
        end
    end
end
