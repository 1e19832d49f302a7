def row_status(report):
    """The status code of every row from the steps' reports, in the order the steps ran: each
    is (status, codes), codes the step's (status, code) pairs in the order they prevail (a
    chain that cannot close, a singular position, a near-singular one).  A row takes the code
    of the first step with the prevailing status it has; 0 where every step is fine."""
    code = 0
    report = [(st, codes) for st, codes in report if np.any(st)]  # most steps are fine on every row
    for k in reversed(range(max((len(codes) for _, codes in report), default=0))):
        for st, codes in reversed(report):
            if k < len(codes):
                code = np.where(st == codes[k][0], codes[k][1], code)
    return code


def reason_of(code):
    """The reason of every row's status code (linkgen/status.py): the last digit of a positive
    code, 0 for status 0 and the negative codes of rows computed near a singular position."""
    return np.where(code > 0, code % 10, 0)
