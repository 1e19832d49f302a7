"""The stages in order: file -> Mechanism -> Topology -> Procedure -> StepLog."""

from __future__ import annotations

from collections.abc import Mapping
from dataclasses import replace

from . import __version__
from .analysis import motion_facts, with_facts
from .census import Assemblies
from .columns import plan
from .directions import unit_directions
from .errors import InputError, and_list
from .extraction import Procedure, extract
from .instant.names import centre_problem, is_centre
from .instant.steps import centre_records, with_centres
from .instant.table import at_sketch, centre_outputs
from .model import Mechanism
from .options import overridden, policy_for
from .prune import prune
from .render.view import CENTRE_LINKS
from .steplog import CentreAt, Draft, InputInfo, LinkInfo, PairInfo, StepLog
from .summary.compute import summarize
from .topology import Topology, analyse
from .validate import read_mechanism


def draft(topo: Topology, proc: Procedure, outputs: tuple[str, ...] | None = None,
          order: int | None = None, options: Mapping[str, object] | None = None) -> Draft:
    """The step log of the whole procedure without its motion facts, with the columns of the
    outputs and order asked for (default: the file's) and the file's options, those in
    ``options`` replaced (linkgen.options.Options' fields)."""
    m = topo.mechanism
    opts = overridden(m.options, options or {})
    if opts.strategy == "closure" and proc.groups:
        proc = _closed(proc, m, "strategy" in (options or {}))
    if opts.strategy == "loop":  # the strategies' own extraction: imported where one is chosen
        from .extraction.loops import LOOP_ITERATIONS, with_loops
    if opts.strategy == "loop" and "iterations" not in m.options_where and "iterations" not in (options or {}):
        opts = replace(opts, iterations=LOOP_ITERATIONS)  # the loop converges linearly (|g'| per step)
    if opts.strategy == "loop" and proc.groups:  # the loop blocks of every class-III group (extraction.loops)
        steps, variables, groups, _ = with_loops(m, proc.steps, proc.variables, proc.groups)
        proc = replace(proc, steps=steps, variables=variables, groups=groups)
    order = m.order if order is None else order
    outputs = m.outputs if outputs is None else outputs
    input_vars = [v.name for v in proc.variables if v.role == "input"]
    pairs = tuple(
        PairInfo(j.name, j.kind, j.x, j.y, j.axis, tuple(lk.name for lk in m.links_of(j.name)),
                 "" if j.revolute else m.prismatic_of(j.name).guide,
                 "" if j.revolute else m.prismatic_of(j.name).slider)
        for j in m.joints
    )
    members: dict[str, list[tuple[str, str, float]]] = {lk.name: [] for lk in m.links}
    for mb in topo.members:
        if mb.b:
            members[mb.link].append((mb.a, mb.b, mb.length))
    links = tuple(
        LinkInfo(lk.name, lk.fixed, lk.joints, tuple(p.name for p in lk.points), tuple(members[lk.name]),
                 (topo.direction(lk.name).origin, topo.direction(lk.name).target or topo.direction(lk.name).axis_of),
                 topo.direction(lk.name).angle)
        for lk in m.links
    )
    inputs = tuple(
        InputInfo(i.index, i.kind, i.column, i.joint, i.link, i.relative_to, i.between, i.start, i.stop, i.speed,
                  s, v)
        for i, s, v in zip(m.inputs, topo.sketch_inputs, input_vars)
    )
    centres = centre_records(proc, tuple(o for o in outputs if is_centre(o)))
    if centres and order == 0:
        _no_velocities(m, next(iter(centres)), outputs is m.outputs)
    columns = plan(m, order, outputs, proc.positions, proc.angles, proc.slides, input_vars, centres)
    proc = with_centres(proc, m, centres)  # before the directions: a centre reads its links' angles
    if opts.angles == "unit":
        proc, columns = unit_directions(proc, columns, len(inputs))
    return Draft(StepLog(
        __version__, m.name, m.title, m.source, m.length_unit, m.angle_unit, topo.length_scale, topo.origin,
        topo.grubler, topo.mobility, topo.redundant, order, m.samples, m.sweep, pairs, links, inputs, proc.variables,
        proc.steps, proc.lj, proc.add_links, proc.residuals, proc.groups, columns, policy_for(opts),
        outputs=tuple(outputs), options=opts,
    ))


def _no_velocities(m: Mechanism, centre: str, in_file: bool) -> None:
    """An instant centre is known from velocities: at order 0 it is an error where the outputs were given."""
    given = m.outputs_where if in_file else None
    where = (m.path, given.line, "outputs") if given else ("command line", 0, "--outputs")
    raise InputError(f"the instant centre {centre} is found from the links' velocities, and the order is 0 "
                     f"(displacements only): build with order 1 or 2 (--order 1)", *where)


def _closed(proc: Procedure, m: Mechanism, flag: bool) -> Procedure:
    """The procedure with its groups' loop-closure equations (strategy closure); a group it cannot
    write them for is an error where the strategy was asked for (the flag, else the file's key)."""
    from .extraction.closure import ClosureRefused, with_closures

    try:
        steps, groups = with_closures(proc.steps, proc.variables, proc.groups)
    except ClosureRefused as exc:
        given = m.options_where.get("strategy")
        where = ("command line", 0, "--strategy") if flag else (m.path, given.line if given else 0, "options.strategy")
        raise InputError(f"the closure strategy cannot resolve this mechanism: {exc}; use strategy newton",
                         *where) from None
    return replace(proc, steps=steps, groups=groups)


def analyse_file(path: str) -> tuple[Mechanism, Topology, Procedure]:
    m = read_mechanism(path)
    topo = analyse(m)
    return m, topo, extract(topo)


def _check_outputs(m: Mechanism, outputs: tuple[str, ...]) -> None:
    """Outputs given on the command line name pairs, points or links of the mechanism."""
    names = [j.name for j in m.joints] + [p.name for p in m.points] + [lk.name for lk in m.links]
    links = [lk.name for lk in m.links]
    for name in outputs:
        if is_centre(name) and (problem := centre_problem(name, links, names)):
            raise InputError(problem, "command line", 0, "--outputs")
        if name not in names and not is_centre(name):
            raise InputError(f"{name} is not a pair, point or link of {m.name} (they are {and_list(names)})",
                             "command line", 0, "--outputs")
        if outputs.count(name) > 1:
            raise InputError(f"the output {name} is listed twice", "command line", 0, "--outputs")


def build_log(path: str, outputs: tuple[str, ...] | None = None, order: int | None = None,
              sweep: bool = True, options: Mapping[str, object] | None = None) -> StepLog:
    """The step log of a mechanism file for the outputs, order and options asked for (default: the
    file's; see draft), cut to the steps they need: made once from the draft of the whole procedure
    and its motion facts (with ``sweep``, the conditioning over the sweep and every instant centre
    at the sketch too, for the manual: it takes a sweep and root finding), then pruned; with
    ``sweep`` the engineering summary of the pruned log too (linkgen.summary)."""
    m, topo, proc = analyse_file(path)
    if outputs is not None:
        _check_outputs(m, outputs)
    m, found = _assembly(m, topo, proc, options or {})
    if m is not topo.mechanism:
        topo = analyse(m)
        proc = extract(topo)
    whole = draft(topo, proc, outputs, order, options)
    log = with_facts(whole, motion_facts(whole, sweep))
    if sweep:  # the manual's instant centres
        log = replace(log, centres=_sketch_centres(topo, proc, options))
    log = replace(prune(log), assemblies=found)
    return replace(log, summary=summarize(log)) if sweep else log


def _assembly(m: Mechanism, topo: Topology, proc: Procedure, options: Mapping[str, object]) -> tuple[Mechanism,
                                                                                                      Assemblies]:
    """Every assembly at the sketch's inputs, and the mechanism drawn in the one the programs
    follow (options.assembly; unchanged for the sketch's)."""
    from .assemblies.follow import chosen, listing, moved

    census_log = draft(topo, proc, (), 0, {**options, "strategy": "newton", "angles": "angle"})
    k = overridden(m.options, options).assembly
    too_many = _too_many(census_log)
    found = Assemblies(tuple(i.sketch for i in census_log.inputs), False, 0, (too_many,), ()) if too_many else listing(
        census_log, k)
    if not k:
        return m, found
    return moved(m, census_log, chosen(m, k, found, "assembly" in options)), found


LISTED = 1024  # assemblies a census walks at most: beyond, the build lists none (the walk doubles with every chain)
ROOTS = 6  # real roots of a triad's characteristic polynomial at most: the assemblies a resolver group adds


def _too_many(log: StepLog) -> str:
    """Why the census is not walked where the assemblies the log can have (both branches of every
    chain, every root of every group) exceed LISTED; "" where they do not.  A chain of N dyads has
    up to 2^N: the walk over them takes seconds at 14 and cannot end at 1000."""
    inside = {n for g in log.groups for b in (g, *g.variants) for n in b.steps}
    chains = sum(1 for s in log.steps if s.branch and s.number not in inside and not s.variant)
    if 2 ** chains * ROOTS ** len(log.groups) <= LISTED:
        return ""
    n = len(log.groups)
    groups, roots = (f" and {n} resolver groups", f" x {ROOTS}^{n}") if n else ("", "")
    return (f"linkgen does not count the assemblies of this mechanism: its {chains} two-link chains (two branches "
            f"each){groups} allow up to 2^{chains}{roots} of them, more than the {LISTED} a build walks")


def _sketch_centres(topo: Topology, proc: Procedure, options: Mapping[str, object] | None) -> tuple[CentreAt, ...]:
    """Every instant centre at the sketch (the manual's); none where a link has no record to compute
    its centres from."""
    m = topo.mechanism
    if len(m.links) > CENTRE_LINKS:  # n(n-1)/2 centres, each a step of the log below: the manual says why none
        return ()
    try:
        log = draft(topo, proc, centre_outputs(m), 1, options)
    except InputError:
        return ()
    return at_sketch(log, m)
