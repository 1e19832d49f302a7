"""The knob settings the bench measures (linkgen/options.py Options), not their full cross product:
the default, each knob turned alone from it, then the fastest and the most accurate combinations
(each knob at its measured fastest, or most accurate, single setting where that beat the default).
"""

from __future__ import annotations

from collections.abc import Callable

from linkgen.options import Options

Setting = dict[str, object]  # Options field -> value, passed to build_log(options=...)

DEFAULT = Options()
EVERY = [{"real": "float"}, {"real": "long double"}, {"checks": False}, {"angles": "unit"}]
# the resolver's knobs: only where the mechanism has Add-links
RESOLVER = [{"strategy": "fixed-point"}, {"strategy": "closure"}, {"strategy": "loop"}, {"polish": False},
            {"predictor": 0},
            {"predictor": 1}, {"tolerance": 1e-6}]


def singles(resolver: bool) -> list[Setting]:
    """The default ({}) and each knob turned alone."""
    return [{}, *EVERY, *(RESOLVER if resolver else [])]


def label(setting: Setting) -> str:
    """How the tables name a setting: 'default', 'real float', 'checks off', 'polish off, predictor 2'."""
    words = []
    for key, value in setting.items():
        if isinstance(value, bool):
            words.append(f"{key} {'on' if value else 'off'}")
        else:
            words.append(f"{key} {value:g}" if isinstance(value, float) else f"{key} {value}")
    return ", ".join(words) or "default"


def best(measured: list[tuple[Setting, float]], better: Callable[[float, float], bool]) -> Setting:
    """Each knob at the single setting whose number beat the default's by ``better`` the most
    (the default's own value where none did): a combination to measure."""
    default = next(v for s, v in measured if not s)
    out: Setting = {}
    for key in dict.fromkeys(k for s, _ in measured for k in s):
        alone = [(s[key], v) for s, v in measured if list(s) == [key] and better(v, default)]
        winner = None
        for value, number in alone:
            if winner is None or better(number, winner[1]):
                winner = (value, number)
        if winner is not None:
            out[key] = winner[0]
    return out
