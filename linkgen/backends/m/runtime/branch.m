function b = branch_at(theta, b0, theta0, points, periodic)
    % Branch of a two-link chain that passes change points (where its two assemblies
    % cross, as a parallelogram four-bar with all pivots in line): the sketch's branch
    % b0, flipped at every change point between the sketch's input value theta0 and theta.
    n = 0;
    for k = 1:numel(points)
        if periodic
            n = n + floor((theta - points(k)) / (2 * pi)) - floor((theta0 - points(k)) / (2 * pi));
        else
            n = n + (theta >= points(k)) - (theta0 >= points(k));
        end
    end
    if mod(n, 2) == 0
        b = b0;
    else
        b = -b0;
    end
end
