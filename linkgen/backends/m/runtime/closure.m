function [ok, x, its] = closure_newton(c, w, x, tol, max_iter, reach, polish)
    % The closure strategy (options: strategy closure): Newton on all loop-closure equations
    % of a resolver group at once, in the positions it places.  c is the group's closure:
    % c.place(w) the positions of the last pass, c.equations(w, x) -> [g, jac] the residuals
    % (length units) and their Jacobian at positions x, c.adopt(w, x, a) -> [w, a] puts x into
    % the work and reads every block's state off it (lengths, branches).  Newton from positions
    % x until max|g| <= tol, then (polish) one step more; at most max_iter steps, a polishing
    % one too; a solution farther than reach from the start is another assembly and refused.
    start = x;
    its = 0;
    ok = false;
    while true
        [g, jac] = c.equations(w, x);
        done = all(abs(g) <= tol);  % a NaN fails every comparison (max would skip it)
        if (done && ~polish) || its == max_iter
            break;
        end
        [dx, det] = solve_linear(jac, -g);
        if det == 0
            return;
        end
        x = x + dx;
        its = its + 1;
        if done
            break;
        end
    end
    ok = done && all(abs(x - start) <= reach);
end

function [ok, its, sigma, w, a, ad, used] = resolver_closure(c, groups, lengths, w, a, ad, used, first, slot, order, ...
                                                             m, p, writes, full)
    % One resolver step by the closure strategy (resolver_group's arguments and results, c the
    % group's closure): the positions start where the first block that closes at its state
    % puts them (the one that solved the last row, used(slot), first; the others in order),
    % Newton on the closure equations, every block's state read off the solution, then
    % resolver_group from there (no polishing step there: the closure took it).  its: the
    % closure's Newton steps and the resolver's.
    sizes = m.sizes(first:first + numel(groups) - 1);
    ok = false;
    its = 0;
    sigma = 0;
    for k = [used(slot), setdiff(0:numel(groups) - 1, used(slot))]
        n = sizes(k + 1);
        if isnan(a{first + k}(1))  % a stale state (nan) is not tried
            continue;
        end
        [st, ~, w] = groups{k + 1}(w, a{first + k}(1:n), zeros(n, 1), zeros(n, 1), false);
        ok = st == 0;
        if ok
            break;
        end
    end
    if ~ok
        return;
    end
    [ok, x, steps] = closure_newton(c, w, c.place(w), p.tolerance * m.length_scale, p.max_iterations, ...
                                    p.max_move * m.length_scale, p.polish);
    its = steps;
    if ~ok
        return;
    end
    [w, a] = c.adopt(w, x, a);
    p.polish = false;  % the closure's own step was the polishing one
    [ok, its, sigma, w, a, ad, used] = resolver_group(groups, lengths, w, a, ad, used, first, slot, order, m, p, writes, ...
                                                     full);
    its = its + steps;
end
