"""Test ladders: N 3R dyads hung one on the next, driven by one crank, as mechanism files.

    ladder(n)             # the chain: each dyad hangs on the two links of the one before
    ladder(n, "frame")    # every rocker pivoted on the frame (the ladder issue 19 measured)

The chain (used for scaling): the crank O-X0 and the frame pivot Y0 carry dyad 1; dyad k
is the ternary links upper_k = [X(k-1), Ak, Xk] and lower_k = [Y(k-1), Ak, Yk] (the last
dyad binary), so dyad k+1 hangs on Xk and Yk, one on each link of dyad k.  Every cell is
the same, mirror-symmetric: Ak midway between X(k-1) and Y(k-1), 20 off their line, each 3R
chain at a right angle in the sketch and each ternary link a right-angled V.  As the crank
turns, the angle at Ak is a in one cell and 180 - a in the next (the arms of each V keep
their right angle), so every chain has the first one's sigma, sin a: above 0.96 over the
input range of +-10 degrees, whatever n.  Every link has at most three pairs, so the
mechanism, its truss and its LJ-matrix's columns grow linearly with n.

The frame ladder hangs dyad k on A(k-1) and a frame pivot Gk: the frame carries n + 1 pairs,
and rule (i) makes it a truss of n(n+1)/2 members (the LJ-matrix and the step log grow as
n^2), which is why scaling is measured on the chain.
"""

from __future__ import annotations

from pathlib import Path

PITCH = 40  # between cells along x
HALF = 20  # half the height of a cell


def _chain(n: int) -> tuple[list[str], list[str], str]:
    joints = ["O: [-30, 20]", f"X0: [0, {HALF}]", f"Y0: [0, {-HALF}]"]
    links = ["frame: {joints: [O, Y0], fixed: true}", "crank: [O, X0]"]
    for k in range(1, n + 1):
        joints.append(f"A{k}: [{PITCH * k - HALF}, 0]")
        upper, lower = [f"X{k - 1}", f"A{k}"], [f"Y{k - 1}", f"A{k}"]
        if k < n:
            joints += [f"X{k}: [{PITCH * k}, {HALF}]", f"Y{k}: [{PITCH * k}, {-HALF}]"]
            upper.append(f"X{k}")
            lower.append(f"Y{k}")
        links += [f"upper{k}: [{', '.join(upper)}]", f"lower{k}: [{', '.join(lower)}]"]
    return joints, links, "{joint: O, link: crank, relative_to: frame, range: [-10, 10]}"


def _frame(n: int) -> tuple[list[str], list[str], str]:
    joints = ["G0: [0, 0]", "A0: [10, 10]"]
    links = [f"frame: {{joints: [{', '.join(f'G{k}' for k in range(n + 1))}], fixed: true}}", "crank: [G0, A0]"]
    for k in range(1, n + 1):
        joints += [f"G{k}: [{PITCH * k}, 0]", f"A{k}: [{PITCH * k + 5}, {30 + 3 * (k % 2)}]"]
        links += [f"coupler{k}: [A{k - 1}, A{k}]", f"rocker{k}: [G{k}, A{k}]"]
    return joints, links, "{joint: G0, link: crank, relative_to: frame, range: [40, 50]}"


KINDS = {"chain": _chain, "frame": _frame}


def ladder(n: int, kind: str = "chain") -> str:
    """The mechanism file (YAML text) of a ladder of n dyads, named ladder<n> (frame_ladder<n>)."""
    if n < 1:
        raise ValueError("a ladder has at least one dyad")
    joints, links, crank = KINDS[kind](n)
    name = f"ladder{n}" if kind == "chain" else f"{kind}_ladder{n}"
    lines = ["linkgen: 1", f"name: {name}", f"title: A {kind} of {n} 3R dyads driven by one crank",
             "units: {length: mm, angle: deg}", "joints:", *(f"  {j}" for j in joints),
             "links:", *(f"  {lk}" for lk in links), "inputs:", f"  - {crank}"]
    return "\n".join(lines) + "\n"


def write_ladder(n: int, folder: Path, kind: str = "chain") -> Path:
    """Write ladder(n, kind) into folder; returns its path."""
    text = ladder(n, kind)
    path = folder / f"{text.split('name: ')[1].split()[0]}.yaml"
    path.write_text(text, encoding="utf-8")
    return path
