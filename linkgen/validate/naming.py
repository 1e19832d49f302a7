"""Names against the generated programs (linkgen.names): the mechanism's name, which names files and
functions, and the pairs, points and links, which are fields of the programs' outputs."""

from __future__ import annotations

from ..loader import IDENTIFIER, Node
from ..model import Joint, Link, Where
from ..names import entity_name_problem, mechanism_name_problem, spellings
from .sheet import Sheet


def program_name(sheet: Sheet, name: str, node: Node) -> None:
    """The mechanism's name names files, a module, a script and functions (linkgen.names)."""
    problem = mechanism_name_problem(name)
    if problem:
        better = next((n for n in (name.lstrip("_"), f"{name}_linkage", f"{name[:40]}_linkage")
                       if n and n != name and IDENTIFIER.fullmatch(n) and not mechanism_name_problem(n)), "")
        raise sheet.error(node, f"{name} {problem}; choose another name for the mechanism"
                          + (f", such as {better}" if better else ""))


def entity_names(sheet: Sheet, joints: tuple[Joint, ...], links: tuple[Link, ...], mechanism: str) -> None:
    """Pairs, points and links are fields of the programs' outputs (linkgen.names), whether outputs
    lists them or not: a name a program cannot carry is refused, and so are two names a program
    would write alike (end and end_ in MATLAB, where the keyword end is written end_)."""
    entities: list[tuple[str, Where, str]] = [(j.name, j.where, "pair") for j in joints]
    entities += [(lk.name, lk.where, "link") for lk in links]
    entities += [(p.name, p.where, "point") for lk in links for p in lk.points]
    written: dict[tuple[str, str], str] = {}
    for name, where, what in sorted(entities, key=lambda e: e[1].line):
        problem = entity_name_problem(name, mechanism)
        for lang, spelling, why in spellings(name):
            other = written.setdefault((lang, spelling), name)
            if other != name and not problem:
                word, why = (name, why) if why else (other, next(w for g, _, w in spellings(other) if g == lang))
                problem = (f"is written {spelling} in the generated {lang} program, as is {other} (line "
                           f"{sheet.names[other].line}), because {word} is {why} and gets a trailing _ there")
        if problem:
            base = "_".join(filter(None, name.split("_")))
            better = next((n for n in (base, f"{base}_{what}", f"{what}_{base}")
                           if IDENTIFIER.fullmatch(n) and n not in sheet.names
                           and not entity_name_problem(n, mechanism)), "")
            advice = f"call the {what} {better} or similar" if better else f"choose another name for the {what}"
            raise sheet.error_at(where, f"{name} {problem}; {advice}")
