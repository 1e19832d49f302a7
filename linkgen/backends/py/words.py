"""The names Python gives a meaning to: the mechanism name NAME names the module NAME.py.

No user name becomes a Python identifier (pairs, points and links are dict keys, "B.x"), so
only the module's name can clash.
"""

from __future__ import annotations

import builtins
import keyword
import sys

from .. import Words

BUILTINS = frozenset(n for n in dir(builtins) if not n.startswith("_"))


def mechanism_problem(name: str) -> str:
    """Why NAME.py cannot carry this mechanism name ('' when it can)."""
    if keyword.iskeyword(name):
        return f"is a Python keyword, so the module {name}.py cannot be imported"
    if name in sys.stdlib_module_names:
        return f"is a module of Python's standard library, which {name}.py would hide"
    if name in BUILTINS:
        return f"is a Python built-in, which `import {name}` would hide in the importing module"
    return ""


WORDS = Words(mechanism_problem=mechanism_problem)
