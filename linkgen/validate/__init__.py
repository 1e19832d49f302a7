"""Stage 2: node tree -> validated Mechanism (format version 1).

Checks everything that can be checked on the file alone, one concern a module: the file's own keys
(header), the pairs and links (parts), the inputs (inputs) and the names the generated programs
carry (naming), all read through one Sheet (sheet).  Mobility and whether the inputs determine the
sketch are checked by ``topology``.
"""

from __future__ import annotations

from ..loader import Mapping, load
from ..model import Mechanism, Where
from . import header, inputs, naming, parts
from .header import file_label
from .sheet import Sheet

__all__ = ["file_label", "read_mechanism", "validate"]


def validate(root: Mapping, path: str) -> Mechanism:
    """Check a parsed file against format version 1 and build the Mechanism."""
    sheet = Sheet(root, path)
    name, title, length_unit, angle_unit = header.header(sheet)
    joints = parts.joints(sheet)
    by_name = {j.name: j for j in joints}
    links = parts.links(sheet, by_name)
    naming.entity_names(sheet, joints, links, name)
    parts.pair_usage(sheet, joints, links)
    given = inputs.inputs(sheet, by_name, links)
    inputs.input_columns(sheet, given)
    parts.single_pair_links(sheet, links, given)
    parts.connected(sheet, links)
    prismatic = inputs.prismatic(joints, links, given)
    given = inputs.resolve_prismatic(given, prismatic)
    outputs, outputs_where = header.outputs(sheet, [lk.name for lk in links])
    order, samples = header.scalars(sheet)
    options, options_where = header.options(sheet)
    return Mechanism(
        name, title, file_label(path), path, length_unit, angle_unit, joints, links,
        given, prismatic, outputs, outputs_where, order, samples, Where(1, ""), header.key_where(sheet, "inputs"),
        options, options_where, header.sweep(sheet, samples, len(given)),
    )


def read_mechanism(path: str) -> Mechanism:
    return validate(load(path), path)
