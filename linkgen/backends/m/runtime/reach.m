function side = reach_at(theta, low, high, periodic)
    % Whether a mechanism with one input reaches an input value from the sketch: the
    % values between the middles of the nearest gaps where a chain cannot close, an angle
    % modulo whole turns.  Past a gap a chain can close again, on another circuit of the
    % mechanism.  0 where theta is reached, -1 past the gap below, 1 past the gap above
    % (for an angle, the nearer of the two); a NaN bound: no gap on that side.
    side = 0;
    if periodic
        t = theta - 2 * pi * floor((theta - low) / (2 * pi));
        if t >= high
            if t - high <= low + 2 * pi - t
                side = 1;
            else
                side = -1;
            end
        end
    elseif theta <= low
        side = -1;
    elseif theta >= high
        side = 1;
    end
end
