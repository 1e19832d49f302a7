function r = reason_of(code)
    % The reason of a status code (linkgen/status.py): the last digit of a positive code
    % (1: a chain cannot close, 2: the Add-link iteration did not converge, 3: a singular position);
    % 0 for status 0 and the negative codes of rows computed near a singular position.
    r = 0;
    if code > 0
        r = mod(code, 10);
    end
end
