"""The engineering summary: mobility, four-bar loops and their Grashof class, the input range
that assembles, limit positions and change points, transmission angles, strokes, swings and
time ratios, and the rows that fail, all in the file's units (``summarize``), as plain records
(``records``) and as text, Markdown or JSON (``text``)."""

from .compute import summarize
from .records import Summary

__all__ = ["Summary", "summarize"]
