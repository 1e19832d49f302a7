"""Command line: linkgen build | run | check | lj | candidates | procedure | assemblies | ic (flags.py: the
flags several commands share)."""

from __future__ import annotations

import contextlib
import gc
import json
import os
import sys
from collections.abc import Callable
from typing import Any, TypeVar

import click

from . import __version__, flags
from .errors import FileSystemError, LinkgenError, os_reason
from .policy import GOOD_LEVER

USAGE_ERROR = 2  # exit status of a wrong command line; 1 is every other failure
ANY_PATH = click.Path(readable=False)  # a path click does not check: its faults are linkgen's, exit 1


def _report(message: str, status: int) -> None:
    """Print ``linkgen: error: message`` on one line of stderr and exit with status."""
    click.echo("linkgen: error: " + " ".join(message.splitlines()), err=True)
    sys.exit(status)


class _Linkgen(click.Group):
    """The command group; every failure is reported as ``linkgen: error: ...``."""

    def main(self, *args: Any, **kwargs: Any) -> Any:
        if not kwargs.setdefault("standalone_mode", True):
            return super().main(*args, **kwargs)
        kwargs["standalone_mode"] = False
        try:
            status = super().main(*args, **kwargs)
        except LinkgenError as exc:
            _report(str(exc), 1)
        except click.UsageError as exc:
            message = exc.format_message()
            end = "" if message.endswith((".", "?")) else "."
            command = exc.ctx.command_path if exc.ctx else "linkgen"
            _report(f"{message[:1].lower()}{message[1:]}{end} See '{command} --help'.", USAGE_ERROR)
        except click.ClickException as exc:
            _report(exc.format_message(), exc.exit_code)
        except click.Abort:
            _report("interrupted", 1)
        except OSError as exc:  # writing to standard output: a full disk, ...
            _report(f"{exc.filename or 'standard output'}: {os_reason(exc)}", 1)
        sys.exit(status if isinstance(status, int) else 0)


@click.group("linkgen", cls=_Linkgen, invoke_without_command=True, subcommand_metavar="COMMAND [ARGS]...",
             context_settings={"help_option_names": ["-h", "--help"]})
@click.version_option(__version__, prog_name="linkgen")
@click.pass_context
def cli(ctx: click.Context) -> None:
    """Systematic kinematic analysis of closed-loop planar linkages.

    Reads a mechanism file (pairs at their sketch positions, links, the fixed
    link, the inputs) and extracts the analysis procedure of two-link chains.

    \b
    Examples:
      linkgen check samples/fourbar/fourbar.yaml
      linkgen build samples/fourbar/fourbar.yaml -o out
      linkgen run samples/fourbar/fourbar.yaml --samples 13
      linkgen COMMAND --help
    """
    if ctx.invoked_subcommand is None:
        raise click.UsageError(f"missing command: one of {', '.join(sorted(cli.commands))}.", ctx)


@cli.command()
@click.argument("mechanism", type=ANY_PATH)
@click.option("-o", "--outdir", type=ANY_PATH, help="Output folder (default: build/NAME).")
@click.option("--check", is_flag=True, help="Rebuild in memory; exit 1 with a diff if any file on disk differs.")
@click.option("--outputs", help="Comma-separated outputs, e.g. P,rocker (default: the file's outputs).")
@click.option("--order", type=click.IntRange(0, 2), help="Derivatives: 0, 1 or 2 (default: the file's order).")
@flags.settings
def build(mechanism: str, outdir: str | None, check: bool, outputs: str | None, order: int | None,
          **settings: Any) -> None:
    """Write the step log (NAME.json) and the generated files.

    With --outputs or --order (or outputs/order in the file) the programs compute only
    the steps and derivatives those outputs need; the manual says what was left out.
    The settings flags (--real, --strategy, ..., --angles) override the file's options; every
    file states the settings it was built with in its first line.  The file names go to
    stdout; a one-line summary (rows that fail, the least transmission angle) to stderr, with
    a warning when most rows fail.

    \b
    Examples:
      linkgen build samples/fourbar/fourbar.yaml
      linkgen build samples/fourbar/fourbar.yaml -o out --outputs P,rocker --order 1
      linkgen build samples/sixbar_fig14/sixbar_fig14.yaml --real float --check -o out
    """
    from .api import Mechanism
    from .summary.text import one_line
    from .writer import differences, write_all

    m = Mechanism(mechanism, flags.outputs(outputs), order, flags.given(settings))
    files = m.files()
    target = outdir or os.path.join("build", m.name)
    if check:
        diffs = differences(files, target)
        for d in diffs:
            click.echo(d, nl=False)
        sys.exit(1 if diffs else 0)
    for path in write_all(files, target):
        click.echo(path)
    summary = m.check()
    click.echo(f"linkgen: {m.name}: {one_line(summary)}", err=True)
    if 2 * summary.failed > summary.rows:
        click.echo(f"linkgen: warning: {summary.failed} of {summary.rows} rows of {m.name} fail: "
                   "the mechanism does not assemble over most of its sweep (see `linkgen check`)", err=True)


@cli.command()
@click.argument("mechanism", type=ANY_PATH)
@click.option("--samples", type=click.IntRange(min=2),
              help="Rows in the sweep, or each input's values with sweep: grid (default: the file's samples).")
@click.option("--order", type=click.IntRange(0, 2), help="Derivatives: 0, 1 or 2 (default: the file's order).")
@click.option("--outputs", help="Comma-separated outputs (default: the file's outputs).")
@click.option("-o", "--output", type=ANY_PATH, help="Write the CSV here instead of stdout.")
@flags.settings
def run(mechanism: str, samples: int | None, order: int | None, outputs: str | None, output: str | None,
        **settings: Any) -> None:
    """Evaluate the sweep in-process and print it as CSV.

    A progress bar goes to stderr on long sweeps where stderr is a terminal (never into a
    file or pipe: the output stays the same bytes).

    \b
    Examples:
      linkgen run samples/fourbar/fourbar.yaml --samples 13
      linkgen run samples/slider_crank/slider_crank.yaml --outputs S --order 1 -o sweep.csv
    """
    from .api import CHUNK, Mechanism, csv_text
    from .validate.header import MAX_SAMPLES
    from .writer import write_all

    m = Mechanism(mechanism, flags.outputs(outputs), order, flags.given(settings))
    each = samples or m.log.samples
    rows = each ** len(m.log.inputs) if m.log.sweep == "grid" else each
    if rows > MAX_SAMPLES:
        raise click.BadParameter(f"a grid over {len(m.log.inputs)} inputs of {each} samples each has {rows} rows; "
                                 f"at most {MAX_SAMPLES}", param_hint="'--samples'")
    if rows > CHUNK and sys.stderr.isatty():
        with click.progressbar(length=rows, label="rows", file=sys.stderr) as bar:
            table = m.sweep(each, progress=bar.update)
    else:
        table = m.sweep(each)
    text = csv_text(m, table)
    if output:
        directory, name = os.path.split(output)
        if not name:
            raise FileSystemError("names a directory; give the file to write the CSV to", output)
        write_all({name: text.encode()}, directory)
    else:
        click.echo(text, nl=False)


LJ_LEGEND = ("# Rows are pairs, columns links (then Add-links).  0: the pair is not on the link;\n"
             "# 1 (2): an unknown revolute (prismatic) pair on it; -1 (-2): a known one.\n"
             "# A step turns the entries of the pairs it finds negative.\n")


@cli.command()
@click.argument("mechanism", type=ANY_PATH)
@click.option("--step", "at", type=int, help="Print only the state after this step (0: before step 1).")
def lj(mechanism: str, at: int | None) -> None:
    """Print the LJ-matrix before the first step and after each step.

    \b
    Examples:
      linkgen lj samples/fourbar/fourbar.yaml
      linkgen lj samples/sixbar_fig14/sixbar_fig14.yaml --step 3
    """
    from .api import load
    from .ljmatrix import states, text

    log = load(mechanism).log
    chosen = states(log)
    if at is not None:
        if not 0 <= at < len(chosen):
            raise click.BadParameter(f"{at} is not a step: give 0 (before step 1) to {len(chosen) - 1}",
                                     param_hint="'--step'")
        chosen = [chosen[at]]
    blocks = []
    for state in chosen:
        title = "before step 1" if state.step == 0 else f"after step {state.step}: {log.step(state.step).reason}"
        blocks.append(f"# LJ-matrix {title}\n" + text(state))
    click.echo(LJ_LEGEND + "\n" + "\n".join(blocks), nl=False)


@cli.command()
@click.argument("mechanism", type=ANY_PATH)
@click.option("--json", "as_json", is_flag=True, help="Print a JSON array of {pairs, norm, usable, lever}, ranked.")
def candidates(mechanism: str, as_json: bool) -> None:
    """List the Add-link candidates where the Solver first stops, ranked by the norm of f
    (those whose lever is below {good_lever} after the others).

    \b
    Examples:
      linkgen candidates samples/sixbar_fig14/sixbar_fig14.yaml
      linkgen candidates samples/sixbar_fig14/sixbar_fig14.yaml --json
    """
    from .api import load

    log = load(mechanism).log
    if not log.add_links:
        if as_json:
            click.echo("[]")
        else:
            click.echo("The Solver completes without an Add-link: every step is a computable two-link chain.")
        return
    for k, add in enumerate(log.add_links):
        rows = [{"pairs": list(c.pairs), "norm": c.norm, "usable": c.usable, "lever": c.lever}
                | ({"with": [list(p) for p in c.also]} if c.also else {}) for c in add.candidates]
        if as_json:
            if k == 0:
                click.echo(json.dumps(rows, indent=2))
            continue
        click.echo(f"Add-link {add.name} (step {add.step}): {len(rows)} candidates, ranked by |f| at the probe input "
                   f"(a lever below {GOOD_LEVER:g} last)")
        for rank, c in enumerate(add.candidates, 1):
            norm = "cannot close" if c.norm is None else f"{c.norm:.6g}"
            lever = "" if c.lever is None else f"  lever {c.lever:.3g}"
            combo = (c.pairs, *c.also)
            mark = "  <- chosen" if c.pairs == add.pairs and (rank == 1 or not c.also) else ""  # the best is installed
            click.echo(f"  {rank}. {', '.join(f'{a}-{b}' for a, b in combo)}  |f| = {norm}{lever}{mark}")


candidates.help = (candidates.help or "").replace("{good_lever}", f"{GOOD_LEVER:g}")  # the number, not its name


@cli.command()
@click.argument("mechanism", type=ANY_PATH)
@click.option("--outputs", help="Comma-separated outputs: only the steps they need (default: the file's outputs).")
def procedure(mechanism: str, outputs: str | None) -> None:
    """Print the numbered procedure, one call per step, then each resolver's fallback blocks
    under a heading of their own.

    \b
    Examples:
      linkgen procedure samples/fourbar/fourbar.yaml
      linkgen procedure samples/sixbar_fig14/sixbar_fig14.yaml --outputs J5
    """
    from .api import Mechanism

    log = Mechanism(mechanism, flags.outputs(outputs)).log
    variant = 0
    for s in log.steps:
        if s.variant != variant:
            variant = s.variant
            block = next(b for g in log.groups for b in g.variants if b.variant == variant and s.number in b.steps)
            group = next(g for g in log.groups if block in g.variants)
            click.echo(f"# fallback block {variant} of the resolver of step {group.step}: steps "
                       f"{block.steps[0]}-{block.steps[-1]}, tried in turn where the block before cannot solve a row "
                       f"(Add-link{'s' if len(block.pairs) > 1 else ''} "
                       f"{', '.join(f'{a}-{b}' for a, b in block.pairs)})")
        click.echo(f"{s.number:3d}  {s.function or s.action:<14} {s.target:<10} {s.reason}")
    if log.omitted:
        click.echo(f"# Steps {', '.join(str(o.number) for o in log.omitted)} of the whole procedure are left out: the "
                   f"outputs {', '.join(log.outputs)} do not need them (the steps keep their numbers, as in the "
                   "programs and their status codes).")


@cli.command()
@click.argument("mechanism", type=ANY_PATH)
@click.option("--at", "at", callback=flags.values,
              help="The inputs' values, comma-separated, in the file's units (default: the sketch's).")
@click.option("--json", "as_json", is_flag=True, help="Print the census as JSON instead of a table.")
@click.option("-o", "--outdir", type=ANY_PATH, help="Write one SVG per assembly here (NAME_assembly_K.svg).")
@click.option("--loops", is_flag=True, help="Then the loop strategy's loops: per class-III group and branch "
              "combination, the fixed points of the map it iterates and |g'| there.")
def assemblies(mechanism: str, at: tuple[float, ...] | None, as_json: bool, outdir: str | None, loops: bool) -> None:
    """Every assembly of the mechanism at one input, the count certified.

    Both branches of every two-link chain are tried; every class-III group is reduced to
    its characteristic polynomial, whose real roots are isolated exactly; a class-IV group of two
    links on four-bars tied by two couplers to one eliminant by resultants (a minute or two), whose
    real roots are isolated exactly and back-substituted.  The sketch's
    assembly (the one the programs follow) is marked.

    \b
    Examples:
      linkgen assemblies samples/fourbar/fourbar.yaml --at 90
      linkgen assemblies samples/double_triad/double_triad.yaml --json -o figures
      linkgen assemblies samples/sixbar_fig14/sixbar_fig14.yaml --at 30 --loops
    """
    from .api import Mechanism
    from .writer import write_all

    found = _counted(lambda: Mechanism(mechanism).assemblies(at))
    figures = found.figures() if outdir else {}
    written = write_all(figures, outdir) if outdir and figures else []
    if as_json:
        click.echo(found.json(), nl=False)
        return
    click.echo(found.text(), nl=False)
    for path in written:
        click.echo(path)
    if loops:
        from . import loopmap
        from .pipeline import build_log
        from .units import from_file

        log = build_log(mechanism, order=0, sweep=False, options={"strategy": "loop", "assembly": 0})
        click.echo(loopmap.text(log, list(from_file(log, at) if at else (i.sketch for i in log.inputs))), nl=False)


@cli.command()
@click.argument("mechanism", type=ANY_PATH)
@click.option("--json", "as_json", is_flag=True, help="Print the summary's records as JSON.")
def check(mechanism: str, as_json: bool) -> None:
    """Print the engineering summary; no file is written.

    Mobility, the four-bar loops and their Grashof class, the input range that assembles,
    limit positions and change points, the transmission angle of each chain (sigma is its
    sine) with its least value and where, the stroke or swing of every output, time ratios,
    and the rows that fail and why: in the file's units (degrees where it gives degrees).

    \b
    Examples:
      linkgen check samples/fourbar/fourbar.yaml
      linkgen check samples/slider_crank/slider_crank.yaml --json
    """
    from .api import load
    from .summary.text import text, to_json

    summary = load(mechanism).check()
    click.echo(to_json(summary) if as_json else text(summary), nl=False)


@cli.command(name="ic")
@click.argument("mechanism", type=ANY_PATH)
@click.option("--at", "at", callback=flags.values,
              help="The inputs' values, comma-separated, in the file's units (default: the sketch's).")
@click.option("--rates", "rates", callback=flags.values,
              help="The inputs' rates, comma-separated, in the file's units per second (default: their speeds).")
@click.option("--json", "as_json", is_flag=True, help="Print the centres as JSON instead of a table.")
def instant_centres(mechanism: str, at: tuple[float, ...] | None, rates: tuple[float, ...] | None,
                    as_json: bool) -> None:
    """Every instant centre of the mechanism at one row: its class and its place.

    The class (first, secondary, third A, third B) comes from the topology, the place from the
    links' exact velocities at the inputs and rates given (with several inputs, their ratio).

    \b
    Examples:
      linkgen ic samples/fourbar/fourbar.yaml
      linkgen ic samples/fourbar/fourbar.yaml --at 90 --json
      linkgen ic samples/fivebar/fivebar.yaml --rates 1,2
    """
    from .api import Mechanism

    found = _counted(lambda: Mechanism(mechanism).centres(at, rates))
    click.echo(found.json() if as_json else found.text(), nl=False)


_T = TypeVar("_T")


def _counted(call: Callable[[], _T]) -> _T:
    """The API's result; values given for the inputs that are not one per input are a usage
    error of the option they were given with (--at, --rates)."""
    from .api import InputCountError

    try:
        return call()
    except InputCountError as exc:
        raise click.BadParameter(str(exc), param_hint=f"'--{exc.argument}'") from None


def main() -> None:
    """The console command: cli, then the process ends at once, its standard streams flushed
    (os._exit): the interpreter's teardown of every module and object took 40 ms of each command
    (a sixth of a build) and does nothing a command needs (linkgen registers no atexit handler,
    starts no thread and closes every file it writes).  The cyclic garbage collector is off for the
    command: its passes over the young objects and the full pass over every object the imports made
    took 10-50 ms of each build, to free the few thousand objects in cycles a build leaves (5,300 for
    double_triad, 12,000 for a chain of 100 dyads: 2 MB more at most; everything else is freed as
    its last reference goes)."""
    gc.disable()
    try:
        cli(prog_name="linkgen")
        code = 0
    except SystemExit as exc:
        if isinstance(exc.code, str):
            print(exc.code, file=sys.stderr)
        code = exc.code if isinstance(exc.code, int) else int(exc.code is not None)
    for stream in (sys.stdout, sys.stderr):
        with contextlib.suppress(OSError, ValueError):  # a closed pipe: what was written is all there is
            stream.flush()
    os._exit(code)
