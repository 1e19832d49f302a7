"""Render the step log into files: {relative path: bytes}, nothing touches disk."""

from __future__ import annotations

from ..steplog import StepLog


def render_all(log: StepLog) -> dict[str, bytes]:
    return {f"{log.name}.json": log.to_json().encode("utf-8")}
