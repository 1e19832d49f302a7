"""docs/performance.md, written a section at a time by the bench groups (scaling, reals)."""

from __future__ import annotations

from pathlib import Path

DOC = Path(__file__).resolve().parents[1] / "docs" / "performance.md"


def write_section(title: str, text: str, doc: Path = DOC) -> None:
    """Replace the section '## title' of doc (up to the next '## ') with text, or append it."""
    old = doc.read_text(encoding="utf-8") if doc.exists() else "# Performance\n\n"
    start = old.find(f"## {title}\n")
    body = text.rstrip("\n") + "\n"
    if start < 0:
        new = old.rstrip("\n") + "\n\n" + body
    else:
        end = old.find("\n## ", start + 1)
        new = old[:start] + body + ("\n" + old[end + 1:] if end >= 0 else "")
    doc.write_text(new, encoding="utf-8")
