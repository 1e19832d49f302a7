"""extraction.addlink: candidates (paper 3.3.1), the norm of f at the probe, the ranking (section 6)."""

from __future__ import annotations

import math
from pathlib import Path

import mpmath

from linkgen.extraction import addlink, rank, stuck
from linkgen.extraction.solver import solve
from linkgen.extraction.state import Workspace
from linkgen.topology import analyse
from linkgen.validate import read_mechanism

ROOT = Path(__file__).resolve().parents[2]
FIG14 = ROOT / "samples" / "sixbar_fig14" / "sixbar_fig14.yaml"


def _circles(c1, r1, c2, r2, side):
    """The intersection of two circles on the given side of c1 -> c2, in 40 digits."""
    mp = mpmath.mp.clone()
    mp.dps = 40
    (x1, y1), (x2, y2) = [mp.mpf(v) for v in c1], [mp.mpf(v) for v in c2]
    dx, dy = x2 - x1, y2 - y1
    q = mp.sqrt(dx * dx + dy * dy)
    a = (r1 * r1 - r2 * r2 + q * q) / (2 * q)
    h = mp.sqrt(r1 * r1 - a * a)
    return x1 + (a * dx - side * h * dy) / q, y1 + (a * dy + side * h * dx) / q


def test_norm_of_f_at_the_probe_matches_an_independent_construction():
    """Fig. 14 with the Add-link J6-J4 at its sketch length, the crank turned 5 degrees: J4 from
    J3 and J6, J2 from J1 and J4, J5 fixed on the ternary link; f = |J6 J5| - |coupler|."""
    topo = analyse(read_mechanism(str(FIG14)))
    m = topo.mechanism
    xy = {j.name: (j.x, j.y) for j in m.joints}

    def dist(a, b):
        return math.hypot(xy[a][0] - xy[b][0], xy[a][1] - xy[b][1])

    theta = math.atan2(xy["J6"][1] - xy["J7"][1], xy["J6"][0] - xy["J7"][0]) + math.radians(5)
    j6 = (xy["J7"][0] + 20 * math.cos(theta), xy["J7"][1] + 20 * math.sin(theta))
    j4 = _circles(xy["J3"], dist("J3", "J4"), j6, dist("J6", "J4"), -1)
    j2 = _circles(xy["J1"], dist("J1", "J2"), j4, dist("J2", "J4"), 1)
    # J5 keeps its sketch coordinates in the frame of J2 -> J4
    (ax, ay), (bx, by), (px, py) = xy["J2"], xy["J4"], xy["J5"]
    u0 = complex(bx - ax, by - ay)
    local = complex(px - ax, py - ay) / u0
    z = complex(j2[0], j2[1]) + local * complex(j4[0] - j2[0], j4[1] - j2[1])
    want = abs(math.hypot(z.real - j6[0], z.imag - j6[1]) - dist("J6", "J5"))

    state = stuck(topo)
    ws = Workspace.thaw(state)
    addlink.install(ws, "J6", "J4")
    solve(ws, stop_at_close=True)
    got = addlink.residual_norm(ws, addlink.probe(topo))
    assert want > 1e-4 and abs(got - want) <= 1e-11 * topo.length_scale


def test_every_usable_candidate_closes_at_the_sketch():
    """At the sketch's input every Add-link keeps its sketch length and every residual is zero."""
    topo = analyse(read_mechanism(str(FIG14)))
    state = stuck(topo)
    for k, u in addlink.candidates(state):
        ws = Workspace.thaw(state)
        addlink.install(ws, k, u)
        solve(ws, stop_at_close=True)
        norm = addlink.residual_norm(ws, topo.sketch_inputs)
        assert norm is not None and norm <= 1e-12 * topo.length_scale, (k, u, norm)


def test_ranking_leaves_the_stuck_state_untouched():
    """Candidates are probed from the frozen state: ranking them changes nothing in it."""
    topo = analyse(read_mechanism(str(FIG14)))
    state = stuck(topo)
    before = (state.steps, dict(state.variables), dict(state.pos))
    chosen = rank(state)
    assert (state.steps, dict(state.variables), dict(state.pos)) == before
    assert len(chosen.steps) > len(state.steps)
    assert chosen.add_links[0].pairs == ("J6", "J4")
    assert [c.norm for c in chosen.add_links[0].candidates] == sorted(c.norm for c in chosen.add_links[0].candidates)


def test_rounded_norms_tie_at_every_power_of_two_scale():
    for norm in (0.1, 1 / 3, 1.707416214980185, 1e-300):
        base = addlink._rounded(norm)
        for k in (-40, -3, 5, 60):
            assert addlink._rounded(math.ldexp(norm, k)) == math.ldexp(base, k)
