"""User names against the names the generated files give a meaning to.

The mechanism name NAME names every backend's files (NAME.c, NAME.py, NAME_solve.m, ...); a
pair, point or link name is a field of the programs' outputs (``out->B.x`` in C, ``out.B.x``
in MATLAB/Octave) and text (a CSV column, a Python dict key "B.x").  Each backend
(linkgen.backends, its words module) says which names its files cannot carry and which it
writes with a trailing _ (a word of its language); here they are asked in turn.
"""

from __future__ import annotations

from .backends import backends


def mechanism_name_problem(name: str) -> str:
    """Why the generated files cannot carry this mechanism name ('' when they can)."""
    return next((p for b in backends() if (p := b.words.mechanism_problem(name))), "")


def entity_name_problem(name: str, mechanism: str) -> str:
    """Why a pair, point or link name cannot be an output of the generated programs ('' when it can)."""
    if name.startswith("_"):
        return f"starts with _, which a MATLAB struct field cannot (out.{name}) and C reserves"
    problem = next((p for b in backends() if (p := b.words.entity_problem(name, mechanism))), "")
    if problem:
        return problem
    where = [b.words.state.replace("NAME", mechanism) for b in backends() if name in b.words.state_fields]
    return f"is a field of the generated state ({', '.join(where)})" if where else ""


def spellings(name: str) -> tuple[tuple[str, str, str], ...]:
    """(language, field, why) of a pair, point or link name: how each backend whose outputs are the
    fields of a structure writes it there, and why with a trailing _ ('' when as itself)."""
    return tuple((b.language, b.words.field(name), b.words.field_word(name)) for b in backends() if b.words.state)
