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
    n = numel(a);
    jac = zeros(n, n);
    f = zeros(n, 1);
    for j = 1:n
        rec = struct('v', num2cell(a(:)'), 'dv', num2cell(double((1:n) == j)));
% if order >= 2
        [rec.ddv] = deal(0);
% endif
        [st, res, w] = group(w, rec, false);
        if st
            ok = false;
            return;
        end
        f = [res.v]';
        jac(:, j) = [res.dv]';
    end
    ok = true;
end

function [ok, a, its, jac, w] = resolver_newton(group, w, a, tol, max_iter, reach)
    % Iterate the Add-link lengths until max|f| <= tol, then one step more; a step that
    % makes a chain fail to close is halved (up to 3 times; then the block fails and
    % the next block is tried).  A solution farther than reach from the start is
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
        for halving = 1:4
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
    rec = struct('v', num2cell(a(:)'), 'dv', 0);
% if order >= 2
    [rec.ddv] = deal(0);
% endif
    [~, res, w] = group(w, rec, true);
    [rates, det] = solve_linear(jac, -[res.dv]');
    rates = num2cell(rates');
    [rec.dv] = deal(rates{:});
% if order >= 2
    if order >= 2
        [~, res, w] = group(w, rec, true);
        accs = solve_linear(jac, -[res.ddv]');
        if det == 0
            accs = NaN(n, 1);
        end
        accs = num2cell(accs');
        [rec.ddv] = deal(accs{:});
    end
% endif
    prod = 1;
    for j = 1:n
        prod = prod * sqrt(sum(jac(:, j) .^ 2));
    end
    sigma = abs(det) / max(prod, 1);
    turn = sign(det);
    [st, ~, w] = group(w, rec, true);
end

function [k, its, sigma, turn, w] = resolver_variants(groups, w, a, first, tol, max_iter, reach, order, prefer, ...
                                                sizes, min_sigma)
    % Newton on a group's blocks (its chosen Add-link candidate, then the fallbacks), the
    % preferred block first, the others in order.  The first that converges with its
    % chains conditioned at least min_sigma (w.chains: the worst of the last pass, from
    % the block's lever down) is kept; else the best conditioned of those that converge,
    % a later block only when more than twice as well conditioned (blocks that share a
    % chain near a toggle tie up to rounding: the order decides).  The caller then
    % measures every block's state on the solved pairs.  a{first + k} is block k's state: its
    % sizes(k + 1) start lengths, its branches, its orientation; k = -1 when no block
    % converges; turn is the orientation of block k (see resolver_rates).
    its = 0;
    sigma = 0;
    turn = 0;
    best = -1;
    best_sigma = -1;
    tries = [prefer, setdiff(0:numel(groups) - 1, prefer)];
    for k = tries
        [ok, x, its, jac, w] = resolver_newton(groups{k + 1}, w, a{first + k}(1:sizes(k + 1)), tol, max_iter, reach);
        if ~ok
            continue;
        end
        if w.chains < min_sigma
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
        [ok, x, its, jac, w] = resolver_newton(groups{k + 1}, w, a{first + k}(1:sizes(k + 1)), tol, max_iter, reach);
        if ok
            [st, sigma, turn, w] = resolver_rates(groups{k + 1}, w, x, jac, order);
            if st ~= 1
                return;
            end
        end
    end
    k = -1;
end

function ok = resolver_on_path(prev, guess, now, sizes, slack)
    % Whether a solved state is where the predictor pointed from prev: no block's Add-link
    % length moved from the guess by more than a tenth of the largest predicted move (plus
    % slack); a larger correction is a jump to another assembly, or a step too long for
    % the curve.  A block that solved both and turned its orientation (the state's last
    % entry, after its sizes(k) lengths and its branches; 0 where the block did not solve)
    % has passed a singular position.  Where two assemblies pass close the nearer one can
    % lie within the tenth, so a turned block must be within a hundredth: the path crosses
    % the singular position along its tangent, as a mechanism goes straight through a
    % change point.
    move = 0;
    share = 0.1;
    for g = 1:numel(sizes)
        move = max([move; abs(guess{g}(1:sizes(g)) - prev{g}(1:sizes(g)))]);
        if prev{g}(end) * now{g}(end) < 0
            share = 0.01;
        end
    end
    ok = true;
    for g = 1:numel(sizes)
        ok = ok && all(abs(now{g}(1:sizes(g)) - guess{g}(1:sizes(g))) <= share * move + slack);
    end
end

function a = resolver_advance(a, rate, step, sizes)
    % Block states moved by step along their rates.  An Add-link length is a distance:
    % where its prediction passes zero the two pairs pass each other, so it is reflected.
    for g = 1:numel(a)
        a{g} = a{g} + step * rate{g};
        a{g}(1:sizes(g)) = abs(a{g}(1:sizes(g)));
    end
end

function a = resolver_predict(warm, in, sizes)
    % Resolver start values for new inputs: the warm states advanced along their rates
    % (first-order Taylor in the warm row's input direction; the rates exist at every
    % order, so the positions do not depend on the order computed).
    den = sum(warm.din .^ 2);
    tau = 0;
    if den > 0
        tau = sum((in - warm.in) .* warm.din) / den;
    end
    a = resolver_advance(warm.a, warm.ad, tau, sizes);
end

function [ok, a] = resolver_continuation(run, base, a, target, limits, periodic, halvings, sizes, slack, reach, low)
    % Follow the assembly from inputs base (solved with block states a) to target.
    % Angle inputs go the shorter way round, else the other way; where the one input is an
    % angle with a reach (the values it reaches from the sketch, modulo whole turns, from
    % low up; low is NaN without one; base and target are inside it), it goes the one way
    % round that stays inside the reach.  A step moves no input by more than its limit and
    % no Add-link length, as predicted, by more than reach; it starts Newton from the
    % tangent predictor and is halved where Newton fails or lands off the path (see
    % resolver_on_path), up to halvings times in a row.
    if periodic(1) && ~isnan(low)
        goal = target;
        goal(1) = base(1) + (target(1) - 2 * pi * floor((target(1) - low) / (2 * pi))) ...
                  - (base(1) - 2 * pi * floor((base(1) - low) / (2 * pi)));
        [ok, a2] = resolver_walk(run, base, a, goal, limits, halvings, sizes, slack, reach);
        if ok
            a = a2;
        end
        return;
    end
    goal = target;
    other = target;
    differs = false;
    for i = 1:numel(goal)
        if periodic(i)
            goal(i) = target(i) - 2 * pi * floor((target(i) - base(i)) / (2 * pi) + 0.5);
            other(i) = goal(i);
            if goal(i) > base(i)
                other(i) = goal(i) - 2 * pi;
                differs = true;
            elseif goal(i) < base(i)
                other(i) = goal(i) + 2 * pi;
                differs = true;
            end
        end
    end
    [ok, a2] = resolver_walk(run, base, a, goal, limits, halvings, sizes, slack, reach);
    if ~ok && differs
        [ok, a2] = resolver_walk(run, base, a, other, limits, halvings, sizes, slack, reach);
    end
    if ok
        a = a2;
    end
end

function [ok, a] = resolver_walk(run, base, a, goal, limits, halvings, sizes, slack, reach)
    % Continuation along the straight path from base to goal (see resolver_continuation).
    % Near a singular position the lengths' rates are large and the steps short (the
    % prediction holds only there); a step that makes no progress cuts the path, and so
    % do max_passes passes (at once where the path needs more steps than that).
    max_passes = 1000;
    d = goal - base;
    h_max = 1;
    for i = 1:numel(d)
        if d(i) ~= 0
            h_max = min(h_max, limits(i) / abs(d(i)));
        end
    end
    ok = false;
    if h_max * max_passes < 1
        return;
    end
    [ok, a, rate] = run(base, d, 1, a);
    if ~ok
        return;
    end
    t = 0;
    h = h_max;
    cuts = 0;
    passes = 1;
    while t < 1
        if passes == max_passes
            ok = false;
            return;
        end
        passes = passes + 1;
        fast = 0;
        for g = 1:numel(sizes)
            fast = max([fast; abs(rate{g}(1:sizes(g)))]);
        end
        if fast * h > reach
            h = reach / fast;
        end
        tt = min(1, t + h);
        if tt == t
            ok = false;
            return;
        end
        if tt < 1
            trial = base + tt * d;
        else
            trial = goal;
        end
        guess = resolver_advance(a, rate, tt - t, sizes);
        [closed, a2, rate2] = run(trial, d, 1, guess);
        if closed && resolver_on_path(a, guess, a2, sizes, slack)
            t = tt;
            a = a2;
            rate = rate2;
            h = min(2 * h, h_max);
            cuts = 0;
        else
            h = h / 2;
            cuts = cuts + 1;
            if cuts > halvings
                ok = false;
                return;
            end
        end
    end
    ok = true;
end
