"""The over-constraint resolver's plan (the paper's section 3.3.2).

While the Solver runs: every link it leaves unused once its pairs are known gives a
residual, and a group closes with a resolve step when it has as many residuals as
Add-links.  When extraction is done: each group becomes a ResolverGroup record with
its fallback blocks (the other usable Add-link candidates), the branch signs every
block reads off a solved configuration, and the levers that rank the blocks.
"""

from __future__ import annotations

import math
from dataclasses import replace

from ..steplog import AddLink, Arg, BranchSign, Residual, ResolverGroup, Step, Variable
from .state import Unsupported, VariantDraft, Workspace

# -- while the Solver runs -------------------------------------------------------------


def add_residual(ws: Workspace, link: str, a: str, b: str, length: str) -> None:
    """Link (or actuator, or Add-link) ``link`` joins the known a and b but was not used:
    its length is a residual of the open group (outside a group the sketch already
    satisfies the redundant constraint, as in an exact parallelogram)."""
    if not ws.group:
        return
    ws.residual_links.add(link)
    f = ws.new_var(f"f{len(ws.residuals) + 1}", "VARIABLE", "residual", link)
    ws.residuals.append(Residual(f, link, (a, b), length, 0))
    ws.groups[-1] = replace(ws.groups[-1], residuals=ws.groups[-1].residuals + (f,))
    ws.append("residual", "link_residual", [Arg("var", ws.pos[a]), Arg("var", ws.pos[b]), Arg("var", length)], [f],
              link, pairs=(a, b), links=(link,), fails=True,
              reason=f"{a} and {b} are both known, but link {link} was not used to find them: its length "
                     "must come out right, which the resolver ensures")


def close_group(ws: Workspace) -> None:
    """Close the open group with a resolve step once its residuals match its Add-links."""
    if not ws.group:
        return
    g = ws.groups[-1]
    if len(g.residuals) > len(g.add_links):
        raise Unsupported("more unused links than Add-links")
    if len(g.residuals) < len(g.add_links):
        return
    _hoist(ws, g.number, g.add_links, g.residuals)
    links = [r.link for r in ws.residuals if r.name in g.residuals]
    ws.append("resolve", "", [], list(g.add_links), f"group{g.number}", fails=True,
              reason=f"the resolver iterates on {', '.join(g.add_links)} until " + " and ".join(links)
              + (" regains its length" if len(links) == 1 else " regain their lengths"))
    ws.group = 0


def _hoist(ws: Workspace, number: int, adds: tuple[str, ...], residuals: tuple[str, ...]) -> None:
    """Move the steps of the group that do not depend on its Add-links before it."""
    start = next(i for i, s in enumerate(ws.steps) if s.group == number)
    dep = set(adds)
    before, inside = [], []
    for s in ws.steps[start:]:
        reads = {a.var for a in s.args if a.kind == "var"}
        if s.action == "add_link" or reads & dep:
            inside.append(s)
            dep |= set(s.outputs)
        else:
            before.append(replace(s, group=0))
    if any(r not in dep for r in residuals):
        raise Unsupported("a residual does not depend on the Add-links")
    ws.steps[start:] = before + inside


# -- when extraction is done -------------------------------------------------------------


def resolver_groups(ws: Workspace, steps: list[Step], variables: dict[str, Variable],
                    add_links: tuple[AddLink, ...]) -> list[ResolverGroup]:
    """The ResolverGroup record of every group, with its fallback blocks; the fallbacks'
    steps are appended to ``steps`` (numbered after the procedure) and their records to
    ``variables``."""
    groups = []
    for g in ws.groups:
        block = [s for s in steps if s.group == g.number and s.action not in ("add_link", "resolve")]
        resolve = next(s for s in steps if s.group == g.number and s.action == "resolve")
        later = {a.var for s in steps if s.number > resolve.number for a in s.args if a.kind == "var"}
        needed = {o for s in block for o in s.outputs} & (later | set(ws.pos.values()) | set(ws.angles.values())
                                                          | set(ws.slides.values()))
        variants: list[ResolverGroup] = []
        for draft in (d for d in ws.variants if d.group == g.number):
            variant = _variant(draft, len(variants) + 1, len(steps), variables, needed)
            if variant is not None:
                vsteps, vgroup = variant
                steps += vsteps
                variants.append(vgroup)
        adds = [a for a in add_links if a.name in g.add_links]
        main = replace(_block_group(g.number, 0, block, g.add_links, g.residuals, variables),
                       step=resolve.number, pairs=tuple(a.pairs for a in adds), lengths=tuple(a.length for a in adds))
        by_number = {s.number: s for s in steps}
        main, *variants = (replace(b, lever=_lever(b, by_number, variables)) for b in (main, *variants))
        groups.append(_with_branch_signs(main, variants, by_number, variables))
    return groups


def _with_branch_signs(main: ResolverGroup, variants: list[ResolverGroup], steps: dict[int, Step],
                       variables: dict[str, Variable]) -> ResolverGroup:
    """The group with its fallbacks, every block knowing how to read its chains' branches
    off a solved configuration (so that any block can take over where the assembly has
    moved: its chains' branches are those of the configuration, not of the sketch)."""
    blocks = (main, *variants)
    every = set.intersection(*(set(b.writes) for b in blocks))

    def known(name: str, block: ResolverGroup) -> bool:
        return name in every or name in block.reads or variables[name].constant

    def signs(block: ResolverGroup) -> ResolverGroup:
        out = []
        for s in (steps[n] for n in block.steps):
            sign = _branch_sign(s)
            if sign is not None and all(known(v, block) for v in (*sign.points, sign.angle) if v):
                out.append(sign)
        return replace(block, branches=tuple(out))

    return replace(signs(main), variants=tuple(signs(v) for v in variants))


def _lever(block: ResolverGroup, steps: dict[int, Step], variables: dict[str, Variable]) -> float:
    """The block's lever: placement_lever of its steps."""
    return placement_lever([steps[n] for n in block.steps], list(steps.values()), variables)


def placement_lever(block: list[Step], steps: list[Step], variables: dict[str, Variable]) -> float:
    """The worst ratio, over the block's point placements, of the base its frame angle is
    measured on (link_point: the two points it places from) to the arm of the placed point
    (at most 1).  A placement magnifies the
    angle's error by the inverse: a block that must turn a needle to place a far pair is
    a poor coordinate of the assembly, whatever its chains' conditioning."""
    producer = {o: s for s in steps for o in s.outputs}
    producer.update({o: s for s in block for o in s.outputs})  # fallback blocks write the same variables

    def base(frame: str) -> float | None:
        s = producer.get(frame)
        if s is None:
            return None
        if s.function == "offset_angle":
            return base(s.args[0].var)
        if s.function == "link_angle":
            (xa, ya), (xb, yb) = (variables[a.var].sketch[:2] for a in s.args[:2])
            return math.hypot(xb - xa, yb - ya)
        return None

    worst = 1.0
    for s in block:
        if s.function == "coupler_point":
            b = base(s.args[1].var)
            arm = math.hypot(s.args[2].value, s.args[3].value)
        elif s.function == "link_point":  # the base j1-j2 itself; the arm (gsi, eta)
            (xa, ya), (xb, yb) = (variables[a.var].sketch[:2] for a in s.args[:2])
            b, arm = math.hypot(xb - xa, yb - ya), math.hypot(s.args[2].value, s.args[3].value)
        else:
            continue
        if b is not None and arm > b:
            worst = min(worst, b / arm)
    return worst


def _branch_sign(s: Step) -> BranchSign | None:
    """How to read step s's branch off a configuration (None: it has no branch)."""
    if not s.branch:
        return None
    var = [a.var for a in s.args if a.kind == "var"]
    if s.function == "RRR_links":  # jb left of j1 -> j2
        return BranchSign(s.number, "side", (var[0], var[1], s.outputs[0]), "", s.branch)
    if s.function == "PRR_links":  # (jb - jr).u of the guide
        return BranchSign(s.number, "along", (var[0], s.outputs[2]), var[3], s.branch)
    if s.function == "RPR_links":  # (js - jg).u of the line
        return BranchSign(s.number, "along", (var[0], var[1]), s.outputs[0], s.branch)
    raise ValueError(f"no branch sign for {s.function}")


def _block_group(number: int, variant: int, block: list[Step], adds: tuple[str, ...], residuals: tuple[str, ...],
                 variables: dict[str, Variable]) -> ResolverGroup:
    """The resolver record of one block of steps (a group or one of its variants)."""
    writes = [o for s in block for o in s.outputs]
    reads: list[str] = []
    for s in block:
        for a in s.args:
            if (a.kind == "var" and a.var not in writes and a.var not in adds and a.var not in reads
                    and not variables[a.var].constant):
                reads.append(a.var)
    return ResolverGroup(number, 0, adds, residuals, tuple(s.number for s in block), tuple(reads), tuple(writes),
                         variant=variant)


def _variant(draft: VariantDraft, k: int, first: int, variables: dict[str, Variable],
             needed: set[str]) -> tuple[list[Step], ResolverGroup] | None:
    """A candidate's block as fallback k of its group: its own Add-link and residual records
    (renamed), the same records for everything the rest of the procedure reads."""
    rename = {}
    for v in draft.variables:
        same = v.name in variables and (variables[v.name].kind, variables[v.name].value) == (v.kind, v.value)
        if v.role in ("addlink", "residual") or (v.name in variables and not same):
            rename[v.name] = f"{v.name}_v{k}"
    block = [s for s in draft.steps if s.action not in ("add_link", "resolve")]
    writes = {rename.get(o, o) for s in block for o in s.outputs}
    if not needed <= writes:
        return None
    for v in draft.variables:
        name = rename.get(v.name, v.name)
        variables.setdefault(name, replace(v, name=name))
    out: list[Step] = []
    for s in block:
        args = tuple(replace(a, var=rename.get(a.var, a.var)) if a.kind == "var" else a for a in s.args)
        outputs = tuple(rename.get(o, o) for o in s.outputs)
        out.append(replace(s, number=first + len(out) + 1, args=args, outputs=outputs, group=draft.steps[0].group,
                           variant=k))
    adds = tuple(rename[v.name] for v in draft.variables if v.role == "addlink")
    residuals = tuple(rename[v.name] for v in draft.variables if v.role == "residual")
    group = replace(_block_group(draft.group, k, out, adds, residuals, variables), pairs=draft.pairs,
                    lengths=draft.lengths)
    return out, group
