"""Reserved words of the target languages: user names that would clash with them."""

C_RESERVED = frozenset("""
    auto break case char const continue default do double else enum extern float for goto if inline int long
    register restrict return short signed sizeof static struct switch typedef union unsigned void volatile while
    _Bool _Complex _Imaginary NAN INFINITY main errno assert""".split())
M_RESERVED = frozenset("""
    break case catch classdef continue else elseif end for function global if otherwise parfor persistent return
    spmd switch try while ans eps pi NaN Inf i j""".split())
