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

function [ok, a, its, jac, w] = resolver_newton(group, w, a, tol, max_iter, reach, halvings)
    % Iterate the Add-link lengths until max|f| <= tol, then one step more; a step that
    % makes a chain fail to close is halved (up to halvings times; then the block fails
    % and the next block is tried).  A solution farther than reach from the start is
    % another assembly and refused.
    its = 0;
    start = a;
    [ok, f, jac, w] = resolver_jacobian(group, w, a);
    if ~ok
        return;
    end
    for it = 1:max_iter
        its = it;
        [dx, det] = solve_linear(jac, -f);
        ok = false;
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
        done = all(abs(f) <= tol);  % a NaN fails every comparison (max would skip it)
        a = trial;
        f = f2;
        jac = jac2;
        if done
            ok = all(abs(a - start) <= reach);
            return;
        end
    end
end

function [st, sigma, turn, w] = resolver_rates(group, w, a, jac, order)
    % Exact Add-link rates by the implicit-function theorem (at every order: they start
    % the next row), the accelerations at order 2, then the final pass with them.  turn is
    % the block's orientation, sign(det J): it stays the same along the assembly while the
    % block's chains keep their branches (a solution of the other sign is another assembly).
    n = numel(a);
    zero = zeros(n, 1);
    [~, res, w] = group(w, a, zero, zero, true);
    [rates, det] = solve_linear(jac, -res(:, 2));
    accs = zero;
    if order >= 2
        [~, res, w] = group(w, a, rates, zero, true);
        accs = solve_linear(jac, -res(:, 3));
        if det == 0
            accs = NaN(n, 1);
        end
    end
    prod = 1;
    for j = 1:n
        prod = prod * sqrt(sum(jac(:, j) .^ 2));
    end
    sigma = abs(det) / max(prod, 1);
    turn = sign(det);
    [st, ~, w] = group(w, a, rates, accs, true);
end

function [k, its, sigma, turn, w] = resolver_variants(groups, w, a, first, order, prefer, sizes, p, scale)
    % Newton on a group's blocks (its chosen Add-link candidate, then the fallbacks), the
    % preferred block first, the others in order.  The first that converges with its
    % chains conditioned at least p.min_chain_sigma (w.chains: the worst of the last pass,
    % from the block's lever down) is kept; else the best conditioned of those that
    % converge, a later block only when more than twice as well conditioned (blocks that
    % share a chain near a toggle tie up to rounding: the order decides).  a{first + k} is
    % block k's state: its sizes(k + 1) start lengths, its branches, its orientation; scale
    % is the length scale; k = -1 when no block converges; turn is the orientation of
    % block k (see resolver_rates).
    its = 0;
    sigma = 0;
    turn = 0;
    best = -1;
    best_sigma = -1;
    tol = p.tolerance * scale;
    reach = p.max_move * scale;
    tries = [prefer, setdiff(0:numel(groups) - 1, prefer)];
    for k = tries
        [ok, x, its, jac, w] = resolver_newton(groups{k + 1}, w, a{first + k}(1:sizes(k + 1)), tol, p.max_iterations, ...
                                               reach, p.newton_halvings);
        if ~ok
            continue;
        end
        if w.chains < p.min_chain_sigma
            if w.chains > 2 * best_sigma
                best = k;
                best_sigma = w.chains;
            end
            continue;
        end
        [st, sigma, turn, w] = resolver_rates(groups{k + 1}, w, x, jac, order);
        if st ~= 1
            return;
        end
    end
    k = best;
    if k >= 0
        [ok, x, its, jac, w] = resolver_newton(groups{k + 1}, w, a{first + k}(1:sizes(k + 1)), tol, p.max_iterations, ...
                                               reach, p.newton_halvings);
        if ok
            [st, sigma, turn, w] = resolver_rates(groups{k + 1}, w, x, jac, order);
            if st ~= 1
                return;
            end
        end
    end
    k = -1;
end

function [ok, its, sigma, w, a, ad, used] = resolver_group(groups, lengths, w, a, ad, used, first, slot, order, m, p)
    % One resolver step: resolver_variants on the group's blocks a{first}, ... (the one that
    % solved the last row, used(slot), first); then lengths(w, a, ad) reads every block's
    % state and its rates off the solved pairs (so any of them can start the next row) and
    % the solving block keeps its orientation.  ok: a block solved; its: its Newton steps.
    [k, its, sigma, turn, w] = resolver_variants(groups, w, a, first, order, used(slot), ...
                                                 m.sizes(first:first + numel(groups) - 1), p, m.length_scale);
    ok = k >= 0;
    if ~ok
        return;
    end
    used(slot) = k;
    [a, ad] = lengths(w, a, ad);
    a{first + k}(end) = turn;
end
