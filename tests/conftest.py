"""Session hooks: the hypothesis profiles of the test tiers, one xdist worker per mechanism and module, and
the table of worst errors measured by tests/test_properties.py (gathered from every xdist worker).

Tiers (Makefile): `make test` runs the profile "test" (the default: derandomized, no example database, the
property tests at a fifth of their long counts), `make test-long` the profile "long" (derandomized, full
counts) and `make explore` the profile "explore" (random, more examples, the seed printed).  No profile
stores examples: a failure is kept as an explicit @example or regression test, never in `.hypothesis/`.
"""

from __future__ import annotations

import os
import sys

import pytest
from hypothesis import HealthCheck, settings

_COMMON = {"deadline": None, "database": None, "print_blob": True,
           "suppress_health_check": [HealthCheck.too_slow, HealthCheck.filter_too_much, HealthCheck.data_too_large]}
settings.register_profile("test", derandomize=True, **_COMMON)
settings.register_profile("long", derandomize=True, **_COMMON)
settings.register_profile("explore", derandomize=False, **_COMMON)
settings.load_profile("test")  # `--hypothesis-profile NAME` loads another

@pytest.hookimpl(optionalhook=True)
def pytest_xdist_make_scheduler(config, log):
    """`--dist loadgroup` (Makefile): tests of one module with the same parameters (a mechanism, a kind, or none)
    are one work unit on one worker, so they share the module's fixtures and caches (test_programs' built and
    sources, test_accuracy's sweep).  An xdist_group mark still groups as documented where xdist can read it
    (pytest 9.2 hides it: pytest-xdist issue 1386, which is why the grouping is done here)."""
    if config.getvalue("dist") != "loadgroup":
        return None
    from xdist.scheduler import LoadGroupScheduling

    class ByParameters(LoadGroupScheduling):
        def _split_scope(self, nodeid: str) -> str:
            scope = super()._split_scope(nodeid)  # the group of an xdist_group mark, else the nodeid
            module, _, test = nodeid.partition("::")
            return f"{module}[{test.partition('[')[2]}" if scope == nodeid else scope

    return ByParameters(config, log)


def pytest_sessionfinish(session):
    """An xdist worker hands its worst errors to the controller."""
    out = getattr(session.config, "workeroutput", None)
    sketches = sys.modules.get("sketches")
    if out is not None and sketches is not None:
        out["worst"] = sketches.rows()


@pytest.hookimpl(optionalhook=True)
def pytest_testnodedown(node, error):
    """The controller merges a finished worker's worst errors into its own table."""
    rows = getattr(node, "workeroutput", {}).get("worst")
    if rows:
        import sketches

        sketches.merge(rows)


def pytest_terminal_summary(terminalreporter):
    sketches = sys.modules.get("sketches")
    if sketches is None or not sketches.WORST:
        return
    table = sketches.summary()
    terminalreporter.section("worst errors measured by the property tests")
    terminalreporter.write_line(table)
    path = os.environ.get("LINKGEN_PROPERTY_REPORT")
    if path:
        with open(path, "w", encoding="utf-8") as f:
            f.write(table + "\n")
