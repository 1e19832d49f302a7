"""linkgen.backends.np.still: a variant printed once equal to the printer's own (its bits:
tests/unit/test_backends_np_printer.py; which records a call holds still: tests/unit/test_backends_still.py)."""

from __future__ import annotations

from linkgen.backends.np.printer import numpy_function
from linkgen.backends.np.still import printed
from linkgen.backends.still import held_still
from linkgen.primitives import PRIMITIVES


def test_a_variant_is_printed_as_the_printer_prints_it():
    prim = PRIMITIVES["RRR_links"]
    want = numpy_function(held_still(prim, ("j2",))[0], 2, "", "RRR_links_still_j2")
    assert printed("RRR_links", 2, still=("j2",)) == want
    assert "def RRR_links_still_j2(" in want and printed("RRR_links", 2) == numpy_function(prim, 2, "")
    unchecked = numpy_function(held_still(prim.unchecked(), ("l1",))[0], 1, "_1", "RRR_links_still_l1")
    assert printed("RRR_links", 1, "_1", False, ("l1",)) == unchecked
