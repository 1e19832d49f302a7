function ok = resolver_on_path(prev, guess, now, sizes, slack, p)
    % Whether a solved state is where the predictor pointed from prev: no block's Add-link
    % length moved from the guess by more than p.path_share of the largest predicted move
    % (plus slack); a larger correction is a jump to another assembly, or a step too long
    % for the curve.  A block that solved both and turned its orientation (the state's last
    % entry, after its sizes(k) lengths and its branches; 0 where the block did not solve)
    % has passed a singular position.  Where two assemblies pass close the nearer one can
    % lie within that share, so a turned block must be within p.turn_share: the path
    % crosses the singular position along its tangent, as a mechanism goes straight
    % through a change point.  Only the blocks with a state in prev and now are looked at (a stale
    % one, nan, has none: a row's own pass judged on its solving blocks; a continuation's on
    % every block).
    move = 0;
    share = p.path_share;
    held = cellfun(@(s) ~isnan(s(1)), prev) & cellfun(@(s) ~isnan(s(1)), now);
    for g = 1:numel(sizes)
        if held(g)
            move = max([move; abs(guess{g}(1:sizes(g)) - prev{g}(1:sizes(g)))]);
        end
        if prev{g}(end) * now{g}(end) < 0
            share = p.turn_share;
        end
    end
    ok = true;
    for g = find(held(:)')
        ok = ok && all(abs(now{g}(1:sizes(g)) - guess{g}(1:sizes(g))) <= share * move + slack);
    end
end

function a = resolver_advance(a, rate, step, sizes, loops)
    % Block states moved by step along their rates.  An Add-link length is a distance:
    % where its prediction passes zero the two pairs pass each other, so it is reflected (a
    % loop block's arc length, loops(g) 1, is an angle: it is not).
    for g = 1:numel(a)
        a{g} = a{g} + step * rate{g};
        if ~loops(g)
            a{g}(1:sizes(g)) = abs(a{g}(1:sizes(g)));
        end
    end
end

function tau = resolver_tau(warm, in)
    % How far inputs in lie from the warm row's along its input rates, in time (0 without rates).
    den = sum(warm.din .^ 2);
    tau = 0;
    if den > 0
        tau = sum((in - warm.in) .* warm.din) / den;
    end
end

function a = resolver_predict(warm, in, sizes, order, loops)
    % The path the assembly is expected on at new inputs: the warm states advanced along
    % their rates (order 1: first-order Taylor in the warm row's input direction), or along
    % the parabola with those rates that also passes through the row before them (order 2;
    % warm.back holds its inputs and block states, empty where there was none: then first
    % order).  Both need positions and rates only, and the rates exist at every order, so
    % the positions do not depend on the order computed.
    tau = resolver_tau(warm, in);
    a = resolver_advance(warm.a, warm.ad, tau, sizes, loops);
    if order < 2 || isempty(warm.back)
        return;
    end
    back = resolver_tau(warm, warm.back.in);
    if back == 0
        return;
    end
    for g = 1:numel(a)
        n = 1:sizes(g);
        bend = (warm.back.a{g}(n) - warm.a{g}(n) - back * warm.ad{g}(n)) / (back * back);
        a{g}(n) = warm.a{g}(n) + tau * warm.ad{g}(n) + tau * tau * bend;
        if ~loops(g)
            a{g}(n) = abs(a{g}(n));
        end
    end
end

function [ok, a] = resolver_continuation(run, base, a, target, m, p)
    % Follow the assembly from inputs base (solved with block states a) to target.
    % Angle inputs go the shorter way round, else the other way; where the one input is an
    % angle with a reach (the values it reaches from the sketch, modulo whole turns, from
    % m.low up; m.low is NaN without one; base and target are inside it), it goes the one
    % way round that stays inside the reach.  run(in, din, order, a) -> [ok, a, rates] is a
    % pass along the path (see resolver_walk).
    if m.periodic(1) && ~isnan(m.low)
        goal = target;
        goal(1) = base(1) + (target(1) - 2 * pi * floor((target(1) - m.low) / (2 * pi))) ...
                  - (base(1) - 2 * pi * floor((base(1) - m.low) / (2 * pi)));
        [ok, a2] = resolver_walk(run, base, a, goal, m, p);
        if ok
            a = a2;
        end
        return;
    end
    goal = target;
    other = target;
    differs = false;
    for i = 1:numel(goal)
        if m.periodic(i)
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
    [ok, a2] = resolver_walk(run, base, a, goal, m, p);
    if ~ok && differs
        [ok, a2] = resolver_walk(run, base, a, other, m, p);
    end
    if ok
        a = a2;
    end
end

function [ok, a] = resolver_walk(run, base, a, goal, m, p)
    % Continuation along the straight path from base to goal.  Each step moves no input
    % by more than its limit (m.limits) and no Add-link length, as predicted, by more than
    % p.max_move of the length scale; it starts Newton from the tangent predictor and is
    % halved where Newton fails or lands off the path (see resolver_on_path), up to
    % p.max_halvings times in a row.  Near a singular position the lengths' rates are large
    % and the steps short (the prediction holds only there); a step that makes no progress
    % cuts the path, and so do p.walk_passes passes (at once where the path needs more
    % steps than that).
    slack = p.path_slack * m.length_scale;
    reach = p.max_move * m.length_scale;
    sizes = m.sizes;
    d = goal - base;
    h_max = 1;
    for i = 1:numel(d)
        if d(i) ~= 0
            h_max = min(h_max, m.limits(i) / abs(d(i)));
        end
    end
    ok = false;
    if h_max * p.walk_passes < 1
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
        if passes == p.walk_passes
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
        guess = resolver_advance(a, rate, tt - t, sizes, m.loops);
        [closed, a2, rate2] = run(trial, d, 1, guess);
        if closed && resolver_on_path(a, guess, a2, sizes, slack, p)
            t = tt;
            a = a2;
            rate = rate2;
            h = min(2 * h, h_max);
            cuts = 0;
        else
            h = h / 2;
            cuts = cuts + 1;
            if cuts > p.max_halvings
                ok = false;
                return;
            end
        end
    end
    ok = true;
end

function [ok, a, ad] = resolver_path(run, w, in, din, order, a, used)
    % One pass of the procedure along a continuation path (rates per unit of the path, no
    % accelerations; its work is dropped): closes, the block states, their rates.
    [status, ~, a, ad] = run(w, in, din, zeros(size(in)), order, a, used, true);
    ok = status <= 0;
end

function [status, w, warm] = resolver_drive(run, w, in, din, ddin, order, past, warm, m, p)
    % Solve one row on the sketch's assembly.  run(w, in, din, ddin, order, a, used, full) ->
    % [status, w, a, ad, used] is one pass of the procedure with the block states a (and
    % their rates ad out) and the preferred blocks used (full: a continuation pass, which
    % reads every block's state; else the row's own, which reads the solving blocks').  From the warm start (the previous
    % row) when no input has moved farther than a continuation step: the resolvers start
    % where the predictor of order p.predictor points (see resolver_predict; order 0: from the
    % warm states as they were), and the row is taken when it solves on that path (see
    % resolver_on_path; order 0: the first-order one).  Else, or where that fails at a resolver or lands off the
    % path, the assembly is followed by continuation from the previous row (or, without
    % one, from the sketch) and the row solved from there; where the way is cut but the row
    % solves all the same it is on another assembly only, and gets the code m.another.  A
    % row past the reach (past) fails at once.  warm becomes this row's where it solved.
    base = m.sketch_in;
    a = m.sketch_a;
    used = zeros(1, m.groups);
    if warm.valid
        used = warm.used;
    end
    status = 0;
    solved = false;
    if past
        % past a limit position: the pass fails the row at once with the limit's code
        [status, w, a, ad, used] = run(w, in, din, ddin, order, a, used, false);
    elseif warm.valid && all(abs(in - warm.in) <= m.limits)
        % from the previous row, where the predictor points (order 0: its block states as they were)
        guess = resolver_predict(warm, in, m.sizes, p.predictor, m.loops);
        a = guess;
        if p.predictor == 0
            a = warm.a;
        end
        [status, w, a, ad, used] = run(w, in, din, ddin, order, a, used, false);
        solved = status <= 0 && resolver_on_path(warm.a, guess, a, m.sizes, p.path_slack * m.length_scale, p);
    end
    if warm.valid && ~solved
        base = warm.in;
        a = warm.a;
        used = warm.used;
    end
    if ~solved && (status <= 0 || reason_of(status) == m.not_converged)
        % the sketch's assembly, followed from the sketch (or the last row)
        prefer = used;
        [reached, a2] = resolver_continuation(@(x, d, o, s) resolver_path(run, w, x, d, o, s, prefer), base, a, in, ...
                                              m, p);
        if reached
            a = a2;
        end
        [status, w, a, ad, used] = run(w, in, din, ddin, order, a, used, true);  % every block's state read
        if ~reached && status <= 0
            status = m.another;  % another assembly only
        end
        solved = status <= 0;
    end
    if solved
        back = [];  % the second-order predictor's row before: the warm row, on the sketch's assembly
        if p.predictor == 2 && warm.valid && status ~= m.another
            back = struct('in', warm.in, 'a', {warm.a});
        end
        warm = struct('valid', true, 'in', in, 'din', din, 'a', {a}, 'ad', {ad}, 'used', used, 'back', back);
    else
        warm = struct('valid', false);
    end
end
