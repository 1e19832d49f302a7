"""The runtime primitives proved against sympy, geometry and hand calculation.

Random configurations are built as *motions*: every free quantity of an
assembled chain (point coordinates, angles, slider displacements) is drawn with
its first and second time derivative (a 2-jet), and the primitive's inputs are
derived from the configuration with jet arithmetic (product and chain rule on
50-digit mpmath numbers).  So every input is consistent to 50 digits, every
branch sign is known, and the expected outputs, rates included, are known
without reading the primitive.

(a) each rate field equals sympy's time derivative of the field below it and
    of the displacement field (sympy_oracle), at 50 digits;
(b) the outputs satisfy the chain's constraints and reproduce the sampled motion;
(c) the math and numpy backends agree bit for bit, at every order, and lower
    orders are the leading fields of order 2; both agree with the 50-digit value
    of the same DSL on the same float inputs;
(e) status and sigma discipline over the library.

The hand-calculated cases of each primitive are in tests/unit/test_primitives_library.py and
test_primitives_dyads.py (with the two-link chains' toggles and failures).
"""

from __future__ import annotations

import dataclasses
import functools
import math
import random
import struct
from collections.abc import Callable
from dataclasses import dataclass

import mpmath
import numpy as np
import pytest
import sympy as sp
from primitive_calls import MOTIONS, PI, all_outputs, args_of, call_python, field_level, named, special_inputs
from sympy_oracle import (
    NAN,
    RECORD_FIELDS,
    Prim,
    numeric,
    oracle_rates,
    program,
    time_derivative,
    to_sympy,
)

from linkgen.primitives import PRIMITIVES, dsl, numpy_backend
from linkgen.primitives.dsl import Let, Primitive, record_fields

DPS = 50
TOL = mpmath.mpf("1e-30")  # relative, at 50 digits
SAMPLES = 12  # per primitive and branch sign
MIN_CONDITION = 0.05  # samples closer than this to a singular position are redrawn
mpf = mpmath.mpf


# --------------------------------------------------------------------------- 2-jets


def _lib(x):
    """math for floats (the quick samples of the backend tests), mpmath otherwise."""
    return math if isinstance(x, float) else mpmath


class Jet:
    """A quantity with its first and second time derivative (mpmath numbers, or floats)."""

    __slots__ = ("v", "d", "dd")

    def __init__(self, v, d=0, dd=0):
        self.v, self.d, self.dd = v, d, dd

    @staticmethod
    def of(x) -> Jet:
        return x if isinstance(x, Jet) else Jet(x)

    def __add__(self, o):
        o = Jet.of(o)
        return Jet(self.v + o.v, self.d + o.d, self.dd + o.dd)

    __radd__ = __add__

    def __neg__(self):
        return Jet(-self.v, -self.d, -self.dd)

    def __sub__(self, o):
        return self + (-Jet.of(o))

    def __rsub__(self, o):
        return Jet.of(o) - self

    def __mul__(self, o):
        o = Jet.of(o)
        return Jet(self.v * o.v, self.d * o.v + self.v * o.d, self.dd * o.v + 2 * self.d * o.d + self.v * o.dd)

    __rmul__ = __mul__


def jcos(a: Jet) -> Jet:
    c, s = _lib(a.v).cos(a.v), _lib(a.v).sin(a.v)
    return Jet(c, -s * a.d, -c * a.d**2 - s * a.dd)


def jsin(a: Jet) -> Jet:
    c, s = _lib(a.v).cos(a.v), _lib(a.v).sin(a.v)
    return Jet(s, c * a.d, -s * a.d**2 + c * a.dd)


def jsqrt(a: Jet) -> Jet:
    r = _lib(a.v).sqrt(a.v)
    d = a.d / (2 * r)
    return Jet(r, d, (a.dd - 2 * d * d) / (2 * r))  # (r^2)'' = 2 r r'' + 2 r'^2


def vadd(*vs):
    return tuple(sum(c, Jet(0)) for c in zip(*vs))


def vsub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def vscale(k, a):
    return (k * a[0], k * a[1])


def vdot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def vcross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def direction(angle):
    return (jcos(angle), jsin(angle))


def normal(u):
    return (-u[1], u[0])


def local(u, gsi, eta):
    """gsi * u + eta * n."""
    return vadd(vscale(gsi, u), vscale(eta, normal(u)))


def wrap(angle):
    """Into (-pi, pi]."""
    pi = _lib(angle).pi
    while angle > pi:
        angle -= 2 * pi
    while angle <= -pi:
        angle += 2 * pi
    return angle


# --------------------------------------------------------------------------- sampled motions


@dataclass
class Sample:
    inputs: dict[str, object]  # record params: Jet or (Jet, Jet); scalars: mpf or int
    expected: dict[str, object]  # outputs: Jet or (Jet, Jet)
    name: str = ""

    def values(self) -> dict[str, object]:
        """Every parameter field as a number (the sympy symbols' names)."""
        out: dict[str, object] = {}
        for p in PRIMITIVES[self.name].params:
            value = self.inputs[p.name]
            if not p.is_record:
                out[p.name] = value
                continue
            jets = value if isinstance(value, tuple) else (value,)
            for level, names in enumerate(RECORD_FIELDS[p.kind]):
                for jet, n in zip(jets, names):
                    out[f"{p.name}_{n}"] = (jet.v, jet.d, jet.dd)[level]
        return out

    def scale(self) -> mpf:
        with mpmath.workdps(DPS):
            return max(abs(mpf(v)) for v in self.values().values())


class Draw:
    """Seeded random numbers; each is a double, taken exactly into mpmath when ``exact``."""

    def __init__(self, seed: str, exact: bool = True):
        self.rng = random.Random(seed)
        self.size = 1.0
        self.exact = exact

    def num(self, lo=-1.0, hi=1.0):
        x = self.rng.uniform(lo, hi)
        return mpf(x) if self.exact else x

    def length(self):
        return self.num(-2 * self.size, 2 * self.size)

    def jet(self, lo, hi, rate):
        return Jet(self.num(lo, hi), self.num(-rate, rate), self.num(-rate, rate))

    def point(self):
        s = self.size
        return (self.jet(-2 * s, 2 * s, 2 * s), self.jet(-2 * s, 2 * s, 2 * s))

    def angle(self):
        return self.jet(-3.1, 3.1, 2.0)

    def variable(self, lo=-2.0, hi=2.0):
        s = self.size
        return self.jet(s * lo, s * hi, 2 * s)


def sign(x) -> int:
    return 1 if x > 0 else -1


def sample_crank_input(r: Draw, branch: int):
    j1, ln, theta, phi = r.point(), r.length(), r.angle(), r.angle()
    j2 = vadd(j1, vscale(ln, direction(theta + phi)))
    return Sample({"j1": j1, "l": ln, "theta": theta, "phi": phi}, {"j2": j2})


def sample_coupler_point(r: Draw, branch: int):
    j0, phi, gsi, eta = r.point(), r.angle(), r.length(), r.length()
    jc = vadd(j0, local(direction(phi), gsi, eta))
    return Sample({"j0": j0, "phi": phi, "gsi": gsi, "eta": eta}, {"jc": jc})


def sample_link_point(r: Draw, branch: int):
    j1, rad, phi, gsi, eta = r.point(), r.variable(0.2, 2), r.angle(), r.length(), r.length()
    j2 = vadd(j1, vscale(rad, direction(phi)))  # the base may stretch: only its direction places the point
    jc = vadd(j1, local(direction(phi), gsi, eta))
    return Sample({"j1": j1, "j2": j2, "gsi": gsi, "eta": eta}, {"jc": jc})


def sample_pair_point(r: Draw, branch: int):
    j1, rad, phi, along, across = r.point(), r.variable(0.2, 2), r.angle(), r.length(), r.length()
    j2 = vadd(j1, vscale(rad, direction(phi)))  # a base that stretches: the point stretches with it
    jc = vadd(j1, local(vsub(j2, j1), along, across))
    return Sample({"j1": j1, "j2": j2, "along": along, "across": across}, {"jc": jc})


def sample_slider_input(r: Draw, branch: int):
    pg, psig, s, gsi, eta = r.point(), r.angle(), r.variable(), r.length(), r.length()
    u = direction(psig)
    jp = vadd(pg, vscale(s, u))
    jc = vadd(jp, local(u, gsi, eta))
    return Sample({"pg": pg, "psig": psig, "s": s, "gsi": gsi, "eta": eta}, {"jp": jp, "jc": jc})


def _offset(r: Draw, phi: Jet):
    """An offset in (-pi, pi] putting phi + off above pi, inside (-pi, pi] or below -pi in turn."""
    lo, hi = ((3.2, 6.2), (-3.1, 3.1), (-6.2, -3.2))[r.rng.randrange(3)]
    off = r.num(lo, hi) - phi.v
    return off if -3.1 < off < 3.1 else None


def sample_link_angle(r: Draw, branch: int):
    j1, rad, phi = r.point(), r.variable(0.2, 2), r.angle()
    off = _offset(r, phi)
    if off is None:
        return None
    j2 = vadd(j1, vscale(rad, direction(phi)))
    return Sample({"j1": j1, "j2": j2, "off": off}, {"angle": Jet(wrap(phi.v + off), phi.d, phi.dd)})


def sample_offset_angle(r: Draw, branch: int):
    phi = r.angle()
    off = _offset(r, phi)
    if off is None:
        return None
    return Sample({"phi": phi, "off": off}, {"angle": Jet(wrap(phi.v + off), phi.d, phi.dd)})


def sample_crank_angle(r: Draw, branch: int):
    """An input angle theta and a root angle phi (theta some whole turns away, now and then: the atan2 wrap)."""
    theta, phi = r.angle(), r.angle()
    turns = r.rng.choice((0, 0, 0, 3, -5))
    theta = Jet(theta.v + turns * 2 * _lib(theta.v).pi, theta.d, theta.dd)
    total = theta + phi
    off = _offset(r, Jet(wrap(total.v)))
    if off is None:
        return None
    return Sample({"theta": theta, "phi": phi, "off": off}, {"angle": Jet(wrap(total.v + off), total.d, total.dd)})


def sample_link_direction(r: Draw, branch: int):
    """A link turning through phi + off (any angle: a direction needs no wrap), seen from two of its points."""
    j1, rad, phi, off = r.point(), r.variable(0.2, 2), r.angle(), r.num(-3.1, 3.1)
    j2 = vadd(j1, vscale(rad, direction(phi)))
    c, s = _lib(off).cos(off), _lib(off).sin(off)
    return Sample({"j1": j1, "j2": j2, "c": c, "s": s}, {"u": direction(phi + off)})


def sample_angle_direction(r: Draw, branch: int):
    phi = r.angle()
    return Sample({"phi": phi}, {"u": direction(phi)})


def sample_link_residual(r: Draw, branch: int):
    j1, rad, phi, ln = r.point(), r.variable(0.2, 2), r.angle(), r.variable()
    j2 = vadd(j1, vscale(rad, direction(phi)))
    return Sample({"j1": j1, "j2": j2, "l": ln}, {"f": rad - ln})


def sample_rrr(r: Draw, branch: int):
    j1, j2, jb = r.point(), r.point(), r.point()
    e1, e2 = vsub(jb, j1), vsub(jb, j2)
    l1, l2 = jsqrt(vdot(e1, e1)), jsqrt(vdot(e2, e2))
    q = jsqrt(vdot(vsub(j2, j1), vsub(j2, j1))).v
    if sign(vcross(vsub(j2, j1), e1).v) != branch or min(l1.v, l2.v, q) < MIN_CONDITION * r.size:
        return None
    if abs(vcross(e1, e2).v) / (l1.v * l2.v) < MIN_CONDITION:  # sine of the angle at jb
        return None
    return Sample({"j1": j1, "j2": j2, "l1": l1, "l2": l2, "minv": branch}, {"jb": jb})


def sample_prr(r: Draw, branch: int):
    jr, pg, psig, s, gsi, eta = r.point(), r.point(), r.angle(), r.variable(), r.length(), r.length()
    u = direction(psig)
    jp = vadd(pg, vscale(s, u))
    jb = vadd(jp, local(u, gsi, eta))
    e = vsub(jb, jr)
    ln = jsqrt(vdot(e, e))
    eu = vdot(e, u).v
    if sign(eu) != branch or abs(eu) < MIN_CONDITION * ln.v or ln.v < MIN_CONDITION * r.size:
        return None
    inputs = {"jr": jr, "l": ln, "pg": pg, "psig": psig, "gsi": gsi, "eta": eta, "minv": branch}
    return Sample(inputs, {"s": s, "jp": jp, "jb": jb})


def sample_prp(r: Draw, branch: int):
    pg1, psig1, s1, gsi1, eta1 = r.point(), r.angle(), r.variable(), r.length(), r.length()
    psig2, s2, gsi2, eta2 = r.angle(), r.variable(), r.length(), r.length()
    u1, u2 = direction(psig1), direction(psig2)
    if abs(vcross(u1, u2).v) < MIN_CONDITION:
        return None
    jp1 = vadd(pg1, vscale(s1, u1))
    jb = vadd(jp1, local(u1, gsi1, eta1))
    jp2 = vsub(jb, local(u2, gsi2, eta2))
    pg2 = vsub(jp2, vscale(s2, u2))
    inputs = {"pg1": pg1, "psig1": psig1, "gsi1": gsi1, "eta1": eta1,
              "pg2": pg2, "psig2": psig2, "gsi2": gsi2, "eta2": eta2}
    return Sample(inputs, {"s1": s1, "jp1": jp1, "s2": s2, "jp2": jp2, "jb": jb})


def sample_rpr(r: Draw, branch: int):
    jg, psi, s = r.point(), r.angle(), r.variable()
    ag, bg, as_, bs = r.length(), r.length(), r.length(), r.length()
    u = direction(psi)
    along = s + (ag - as_)  # (js - jg).u
    js = vadd(jg, vscale(along, u), vscale(bg - bs, normal(u)))
    q = _lib(along.v).sqrt(along.v**2 + (bg - bs) ** 2)
    if sign(along.v) != branch or abs(along.v) < MIN_CONDITION * q or q < MIN_CONDITION * r.size:
        return None
    jp = vadd(js, local(u, as_, bs))
    inputs = {"jg": jg, "js": js, "ag": ag, "bg": bg, "as_": as_, "bs": bs, "minv": branch}
    return Sample(inputs, {"psi": psi, "s": s, "jp": jp})


def sample_ppr(r: Draw, branch: int):
    pg, psig, s1, sx = r.point(), r.angle(), r.variable(), r.variable()
    xa, ya, xb, yb, cx = r.length(), r.length(), r.length(), r.length(), r.num(-3.1, 3.1)
    if abs(_lib(cx).sin(cx)) < MIN_CONDITION:
        return None
    u1, ux = direction(psig), direction(psig + cx)
    jp1 = vadd(pg, vscale(s1, u1))
    pb = vadd(jp1, local(u1, xb, yb))  # b's copy of the second pair's point
    pa = vadd(pb, vscale(branch * sx, ux))  # a's copy: (pa - pb).ux = sgn * sx
    jr = vsub(pa, local(u1, xa, ya))
    inputs = {"jr": jr, "pg": pg, "psig": psig, "xa": xa, "ya": ya, "xb": xb, "yb": yb, "cx": cx, "sgn": branch}
    return Sample(inputs, {"s1": s1, "jp1": jp1, "sx": sx, "jpx": pa if branch > 0 else pb})


def sample_loop_point(r: Draw, branch: int):
    """A leg of constant length l turning through theta (some whole turns away, now and then), its angle carried
    as the arc length s = l theta."""
    j1, ln, theta = r.point(), r.variable(0.2, 2).v, r.angle()
    theta = Jet(theta.v + r.rng.choice((0, 0, 0, 2, -3)) * 2 * _lib(theta.v).pi, theta.d, theta.dd)
    j2 = vadd(j1, vscale(ln, direction(theta)))
    return Sample({"j1": j1, "l": Jet(ln), "s": ln * theta}, {"j2": j2})


def sample_loop_residual(r: Draw, branch: int):
    """j2 at the angle phi from j1 (the angle that came back round the loop), the assumed angle theta = phi - m
    a whole turn away now and then, so that phi - theta leaves (-pi, pi] on either side: f = l m.  (The wrap
    takes one turn off: theta more than a turn away from (-pi, pi] is outside what the primitive answers.)"""
    j1, rad, phi, ln = r.point(), r.variable(0.2, 2), r.angle(), r.variable(0.2, 2).v
    j2 = vadd(j1, vscale(rad, direction(phi)))
    m, turns = r.num(-3.1, 3.1), r.rng.choice((0, 0, 1, -1))
    theta = Jet(phi.v - m - turns * 2 * _lib(m).pi, r.num(-2, 2), r.num(-2, 2))
    f = Jet(ln * m, ln * (phi.d - theta.d), ln * (phi.dd - theta.dd))
    return Sample({"j1": j1, "j2": j2, "l": Jet(ln), "s": ln * theta}, {"f": f})


def sample_loop_turn(r: Draw, branch: int):
    """A body's three points, drawn turned the way ``branch`` says (well away from collinear)."""
    j1, j2, j3 = r.point(), r.point(), r.point()
    u, w = vsub(j2, j1), vsub(j3, j1)
    c = vcross(u, w)
    if sign(c.v) != branch or abs(c.v) < MIN_CONDITION * jsqrt(vdot(u, u)).v * jsqrt(vdot(w, w)).v:
        return None
    return Sample({"j1": j1, "j2": j2, "j3": j3, "turn": branch}, {"c": c})


SAMPLERS: dict[str, Callable] = {
    "crank_input": sample_crank_input,
    "slider_input": sample_slider_input,
    "link_angle": sample_link_angle,
    "offset_angle": sample_offset_angle,
    "crank_angle": sample_crank_angle,
    "coupler_point": sample_coupler_point,
    "link_point": sample_link_point,
    "pair_point": sample_pair_point,
    "RRR_links": sample_rrr,
    "PRR_links": sample_prr,
    "PRP_links": sample_prp,
    "RPR_links": sample_rpr,
    "PPR_links": sample_ppr,
    "link_residual": sample_link_residual,
    "link_direction": sample_link_direction,
    "angle_direction": sample_angle_direction,
    "loop_point": sample_loop_point,
    "loop_residual": sample_loop_residual,
    "loop_turn": sample_loop_turn,
}
BRANCHED = {"RRR_links", "PRR_links", "RPR_links", "PPR_links", "loop_turn"}
CASES = [(n, b) for n in MOTIONS for b in ((1, -1) if n in BRANCHED else (1,))]
CASE_IDS = [f"{n}{'' if n not in BRANCHED else ('+' if b > 0 else '-')}" for n, b in CASES]


def test_every_primitive_is_sampled():
    assert set(SAMPLERS) == set(MOTIONS)


@functools.cache
def samples(name: str, branch: int, count: int = SAMPLES, exact: bool = True) -> tuple[Sample, ...]:
    """Assembled motions, seeded by primitive and branch; 50-digit, or floats when not ``exact``."""
    draw = Draw(f"{name} {branch} {exact}", exact)
    out = []
    with mpmath.workdps(DPS):
        while len(out) < count:
            draw.size = 2.0 ** draw.rng.randint(-6, 6)  # scale: lengths from 1e-2 to 1e2
            s = SAMPLERS[name](draw, branch)
            if s is not None:
                s.name = name
                out.append(s)
    return tuple(out)


# --------------------------------------------------------------------------- 50-digit evaluation


@dataclass(frozen=True)
class Evaluated:
    fields: dict[tuple[str, str], mpf]  # (output, field) -> value
    status: object
    sigma: object
    rates: list[tuple[object, mpf, mpf, mpf]]  # (Rate, dsl, from_lower, from_displacement)


@functools.cache
def _compiled(p: Prim):
    prog = program(p)
    rates = oracle_rates(p)
    keys = [(o.name, f) for o in prog.prim.outputs for f in record_fields(o.kind, 2)]
    exprs = [prog.results[o][f] for o, f in keys]
    exprs += [prog.status if prog.status is not None else sp.Integer(0)]
    exprs += [prog.sigma if prog.sigma is not None else sp.Integer(1)]
    for r in rates:
        exprs += [r.dsl, r.from_lower, r.from_displacement]
    return keys, rates, prog.compile(exprs)


def evaluate(p: Prim, values: dict[str, object]) -> Evaluated:
    """Outputs, status, sigma and every rate with its two sympy oracles, at 50 digits."""
    keys, rates, fn = _compiled(p)
    with mpmath.workdps(DPS):
        out = fn(values)
    n = len(keys)
    fields = dict(zip(keys, out[:n]))
    rest = out[n + 2:]
    triples = [(r, *rest[3 * i: 3 * i + 3]) for i, r in enumerate(rates)]
    return Evaluated(fields, out[n], out[n + 1], triples)


def discrepancy(a, b, scale) -> mpf:
    """|a - b| relative to |b| plus the sample's scale, at 50 digits; nan counts as infinitely wrong."""
    with mpmath.workdps(DPS):
        a, b = mpf(a), mpf(b)
        if mpmath.isnan(a) or mpmath.isnan(b):
            return mpmath.inf
        return abs(a - b) / (abs(b) + scale)


def jet_fields(kind: str, value) -> dict[str, mpf]:
    jets = value if isinstance(value, tuple) else (value,)
    return {
        n: (jet.v, jet.d, jet.dd)[level]
        for level, names in enumerate(RECORD_FIELDS[kind])
        for jet, n in zip(jets, names)
    }


# --------------------------------------------------------------------------- (a) rates are derivatives


def rate_errors(p: Prim, smps) -> dict[tuple[str, str, str], mpf]:
    """Worst relative difference of each rate field from each sympy derivative, over the samples."""
    worst: dict[tuple[str, str, str], mpf] = {}
    for smp in smps:
        ev = evaluate(p, smp.values())
        scale = smp.scale()
        for rate, own, from_lower, from_disp in ev.rates:
            for route, oracle in (("d/dt of lower field", from_lower), ("d/dt of displacement", from_disp)):
                key = (rate.output, rate.field, route)
                worst[key] = max(worst.get(key, mpf(0)), discrepancy(own, oracle, scale))
    return worst


@pytest.mark.parametrize(("name", "branch"), CASES, ids=CASE_IDS)
def test_rates_are_sympy_time_derivatives(name, branch):
    worst = rate_errors(name, samples(name, branch))
    assert len(worst) == 2 * sum(len(RECORD_FIELDS[o.kind][1]) * 2 for o in PRIMITIVES[name].outputs)
    bad = {k: mpmath.nstr(v, 3) for k, v in worst.items() if not v <= TOL}
    assert not bad, f"{name}: rate fields differ from sympy's time derivative: {bad}"


def _mutant(name: str, let_name: str, expr) -> Primitive:
    prim = PRIMITIVES[name]
    assert let_name in [let.name for let in prim.body]
    body = tuple(Let(let.name, expr, let.order) if let.name == let_name else let for let in prim.body)
    return dataclasses.replace(prim, body=body)


def _s(n):
    return dsl.Sym(n)


@pytest.mark.parametrize(
    ("name", "let_name", "wrong", "field"),
    [
        # angular acceleration without its Coriolis-like term -2 om (d.dv)/r^2
        ("link_angle", "al", (_s("dx") * _s("day") - _s("dy") * _s("dax")) * _s("ir2"), "ddthe"),
        # the 3R chain's normal acceleration with a and a2 swapped in the 2x2 solve
        ("RRR_links", "bna", (_s("a") * _s("r1a") + _s("a2") * _s("r2a")) * _s("ihq"), "ddx"),
        # the slider velocity without the guide's rotation
        ("PRR_links", "ds", (_s("l_v") * _s("l_dv") - (_s("ex") * _s("relvx") + _s("ey") * _s("relvy")))
         * _s("ieu"), "dv"),
    ],
)
def test_the_oracle_catches_a_planted_bug(name, let_name, wrong, field):
    worst = rate_errors(_mutant(name, let_name, wrong), samples(name, 1)[:4])
    caught = {k for k, v in worst.items() if v > mpf("1e-6")}
    assert any(k[1] == field for k in caught), worst
    right = rate_errors(name, samples(name, 1)[:4])
    assert all(v <= TOL for v in right.values())


# --------------------------------------------------------------------------- (b) constraints and motion


def _pt(fields, out):
    return (fields[(out, "x")], fields[(out, "y")])


def _dir(a):
    return (mpmath.cos(a), mpmath.sin(a))


def _sub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def _add(*vs):
    return tuple(sum(c) for c in zip(*vs))


def _dot(a, b):
    return a[0] * b[0] + a[1] * b[1]


def _cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def _norm(a):
    return mpmath.sqrt(_dot(a, a))


def _local(u, gsi, eta):
    return (gsi * u[0] - eta * u[1], gsi * u[1] + eta * u[0])


def constraints(name: str, v: dict, f: dict) -> tuple[list, list]:
    """Residuals that vanish on the chain (lengths) and conditions that must hold (sides).

    Written from the geometry each primitive's docstring states, not from its formulas.
    """

    def p(n):
        return (v[f"{n}_x"], v[f"{n}_y"])

    if name == "crank_input":
        d, u = _sub(_pt(f, "j2"), p("j1")), _dir(v["theta_the"] + v["phi_the"])
        return [_cross(d, u), _dot(d, u) - v["l"]], []
    if name == "coupler_point":
        d, u = _sub(_pt(f, "jc"), p("j0")), _dir(v["phi_the"])
        return [_dot(d, u) - v["gsi"], _cross(u, d) - v["eta"]], []
    if name == "link_point":  # jc - j1 = gsi e + eta n, e = d / |d| (d = j2 - j1) and n = e turned a quarter left
        d, r = _sub(p("j2"), p("j1")), _sub(_pt(f, "jc"), p("j1"))
        return [_dot(r, d) - v["gsi"] * _norm(d), _cross(d, r) - v["eta"] * _norm(d)], []
    if name == "pair_point":  # jc - j1 = along d + across n(d), d = j2 - j1 and n(d) it turned a quarter left
        d, r = _sub(p("j2"), p("j1")), _sub(_pt(f, "jc"), p("j1"))
        return [_dot(r, d) - v["along"] * _dot(d, d), _cross(d, r) - v["across"] * _dot(d, d)], []
    if name == "slider_input":
        u = _dir(v["psig_the"])
        jp, jc = _pt(f, "jp"), _pt(f, "jc")
        res = [_cross(_sub(jp, p("pg")), u), _dot(_sub(jp, p("pg")), u) - v["s_v"]]
        return res + [_dot(_sub(jc, jp), u) - v["gsi"], _cross(u, _sub(jc, jp)) - v["eta"]], []
    if name in ("link_angle", "offset_angle", "crank_angle"):
        th = f[("angle", "the")]
        base = v["phi_the"] if name == "offset_angle" else v["theta_the"] + v["phi_the"] if name == "crank_angle" \
            else mpmath.atan2(*reversed(_sub(p("j2"), p("j1"))))
        diff = th - base - v["off"]
        return [mpmath.sin(diff), 1 - mpmath.cos(diff)], [-mpmath.pi < th <= mpmath.pi]
    if name == "link_residual":
        return [f[("f", "v")] - (_norm(_sub(p("j2"), p("j1"))) - v["l_v"])], []
    if name in ("link_direction", "angle_direction"):  # u is the unit vector at the link's angle
        u = _pt(f, "u")
        if name == "angle_direction":
            return list(_sub(u, _dir(v["phi_the"]))), []
        d, turn = _sub(p("j2"), p("j1")), (v["c"], v["s"])
        e = (_dot(u, turn), _cross(turn, u))  # u turned back by the offset: along d
        return [_dot(u, u) - 1, _cross(d, e), _dot(turn, turn) - 1], [_dot(d, e) > 0]
    if name == "RRR_links":
        jb = _pt(f, "jb")
        res = [_norm(_sub(jb, p("j1"))) - v["l1_v"], _norm(_sub(jb, p("j2"))) - v["l2_v"]]
        return res, [sign(_cross(_sub(p("j2"), p("j1")), _sub(jb, p("j1")))) == v["minv"]]
    if name == "PRR_links":
        u = _dir(v["psig_the"])
        jp, jb = _pt(f, "jp"), _pt(f, "jb")
        res = [_norm(_sub(jb, p("jr"))) - v["l_v"], _cross(_sub(jp, p("pg")), u)]
        res += [_dot(_sub(jp, p("pg")), u) - f[("s", "v")]]
        res += list(_sub(_sub(jb, jp), _local(u, v["gsi"], v["eta"])))
        return res, [sign(_dot(_sub(jb, p("jr")), u)) == v["minv"]]
    if name == "PRP_links":
        jb, res = _pt(f, "jb"), []
        for i in (1, 2):
            u, jp = _dir(v[f"psig{i}_the"]), _pt(f, f"jp{i}")
            res += [_cross(_sub(jp, p(f"pg{i}")), u), _dot(_sub(jp, p(f"pg{i}")), u) - f[(f"s{i}", "v")]]
            res += list(_sub(_sub(jb, jp), _local(u, v[f"gsi{i}"], v[f"eta{i}"])))
        return res, []
    if name == "RPR_links":
        u = _dir(f[("psi", "the")])
        jp = _pt(f, "jp")
        res = list(_sub(_sub(jp, p("js")), _local(u, v["as_"], v["bs"])))  # the slider's copy
        rel = _sub(jp, p("jg"))  # ... on the guide's line, at s from the guide's reference point
        res += [_cross(u, rel) - v["bg"], _dot(rel, u) - (v["ag"] + f[("s", "v")])]
        return res, [sign(_dot(_sub(p("js"), p("jg")), u)) == v["minv"]]
    if name == "PPR_links":
        u1, ux = _dir(v["psig_the"]), _dir(v["psig_the"] + v["cx"])
        jp1 = _pt(f, "jp1")
        res = [_cross(_sub(jp1, p("pg")), u1), _dot(_sub(jp1, p("pg")), u1) - f[("s1", "v")]]
        pa = _add(p("jr"), _local(u1, v["xa"], v["ya"]))
        pb = _add(jp1, _local(u1, v["xb"], v["yb"]))
        res += [_cross(_sub(pa, pb), ux), f[("sx", "v")] - v["sgn"] * _dot(_sub(pa, pb), ux)]
        res += list(_sub(_pt(f, "jpx"), pa if v["sgn"] > 0 else pb))
        return res, []
    if name == "loop_point":  # j2 at the distance l from j1, at the angle s / l
        d, u = _sub(_pt(f, "j2"), p("j1")), _dir(v["s_v"] / v["l_v"])
        return [_cross(d, u), _dot(d, u) - v["l_v"]], []
    if name == "loop_residual":  # f / l is the angle of j2 - j1 less s / l, up to whole turns, in (-pi, pi]
        ln, fv = v["l_v"], f[("f", "v")]
        diff = fv / ln - (mpmath.atan2(*reversed(_sub(p("j2"), p("j1")))) - v["s_v"] / ln)
        return [ln * mpmath.sin(diff), ln * (1 - mpmath.cos(diff))], [-mpmath.pi * ln < fv <= mpmath.pi * ln]
    if name == "loop_turn":  # c = (j2 - j1) x (j3 - j1), of the sign turn
        c = f[("c", "v")]
        return [c - _cross(_sub(p("j2"), p("j1")), _sub(p("j3"), p("j1")))], [sign(c) == v["turn"]]
    raise KeyError(name)


@pytest.mark.parametrize(("name", "branch"), CASES, ids=CASE_IDS)
def test_outputs_satisfy_constraints_and_reproduce_the_motion(name, branch):
    prim = PRIMITIVES[name]
    for smp in samples(name, branch):
        values = smp.values()
        ev = evaluate(name, values)
        scale = smp.scale()
        with mpmath.workdps(DPS):
            residuals, conditions = constraints(name, values, ev.fields)
        for i, r in enumerate(residuals):
            assert abs(r) <= TOL * scale, f"{name}: constraint {i} residual {mpmath.nstr(r, 5)}"
        assert all(conditions), f"{name}: side condition violated"
        assert ev.status == 0
        assert 0 < ev.sigma <= 1
        for out in prim.outputs:
            for fname, want in jet_fields(out.kind, smp.expected[out.name]).items():
                got = ev.fields[(out.name, fname)]
                err = discrepancy(got, want, scale)
                assert err <= TOL, f"{name}.{out.name}.{fname}: {got} vs sampled {want}"


def test_samples_cover_every_sorting_of_the_3r_triangle():
    """Kahan's formula sorts {l1, l2, q}: the samples must reach every largest side."""
    largest = set()
    for branch in (1, -1):
        for smp in samples("RRR_links", branch):
            v = smp.values()
            q = _norm(_sub((v["j2_x"], v["j2_y"]), (v["j1_x"], v["j1_y"])))
            sides = {"l1": v["l1_v"], "l2": v["l2_v"], "q": q}
            largest.add(max(sides, key=sides.get))
    assert largest == {"l1", "l2", "q"}


def test_samples_cover_both_wraps_of_the_angles():
    """phi + off leaves (-pi, pi] on both sides in the angle samples, so the wrap is exercised."""
    for name in ("link_angle", "offset_angle", "crank_angle"):
        sums = []
        for smp in samples(name, 1):
            v = smp.values()
            if name == "offset_angle":
                base = v["phi_the"]
            elif name == "crank_angle":
                base = v["theta_the"] + v["phi_the"]
            else:
                base = mpmath.atan2(v["j2_y"] - v["j1_y"], v["j2_x"] - v["j1_x"])
            sums.append(base + v["off"])
        assert any(x > mpmath.pi for x in sums) and any(x <= -mpmath.pi for x in sums), name
        assert any(-mpmath.pi < x <= mpmath.pi for x in sums), name


# --------------------------------------------------------------------------- the two sympy routes agree


def _literal_check(name: str, fields: list[tuple[str, str]], second: bool):
    """sympy.diff on the substituted expressions (X(t) functions) = the program's chain rule."""
    prog = program(name)
    by_field = {(r.output, r.field): r for r in oracle_rates(name)}
    literal, chained = [], []
    for out, f0 in fields:
        kind = next(o.kind for o in PRIMITIVES[name].outputs if o.name == out)
        i = RECORD_FIELDS[kind][0].index(f0)
        f1, f2 = RECORD_FIELDS[kind][1][i], RECORD_FIELDS[kind][2][i]
        d1 = time_derivative(name, prog.expand(prog.results[out][f0]))
        literal.append(d1)
        chained.append(by_field[(out, f1)].from_displacement)
        if second:
            literal.append(time_derivative(name, d1))
            chained.append(by_field[(out, f2)].from_displacement)
    lit = numeric(name, literal)
    chain = prog.compile(chained)
    checked = 0
    for smp in samples(name, 1)[:3]:
        values = smp.values()
        with mpmath.workdps(DPS):
            a, b = lit(values), chain(values)
        for x, y in zip(a, b):
            assert discrepancy(x, y, smp.scale()) <= TOL
            checked += 1
    assert checked == 3 * len(literal)


def _displacements(name: str) -> list[tuple[str, str]]:
    return [(o.name, f) for o in PRIMITIVES[name].outputs for f in RECORD_FIELDS[o.kind][0]]


@pytest.mark.parametrize(
    "name", ["crank_input", "slider_input", "link_angle", "offset_angle", "coupler_point", "link_point",
             "pair_point", "link_residual", "link_direction", "angle_direction"]
)
def test_literal_sympy_diff_agrees_with_chain_rule(name):
    _literal_check(name, _displacements(name), second=True)


@pytest.mark.parametrize(
    ("name", "fields"),
    [
        ("RRR_links", [("jb", "x")]),
        ("PRR_links", [("s", "v"), ("jb", "y")]),
        ("PRP_links", [("s1", "v"), ("jb", "x")]),
        ("RPR_links", [("psi", "the"), ("s", "v"), ("jp", "x")]),
        ("PPR_links", [("s1", "v"), ("sx", "v"), ("jpx", "y")]),
    ],
)
def test_literal_sympy_diff_agrees_with_chain_rule_on_chains(name, fields):
    _literal_check(name, fields, second=False)


def test_to_sympy_is_in_parameter_symbols_only():
    """to_sympy substitutes every let away, and agrees with the program view expanded."""
    for name, order in (("crank_input", 2), ("link_angle", 2), ("coupler_point", 2), ("PRP_links", 0),
                        ("PPR_links", 0), ("RPR_links", 0)):
        sprim = to_sympy(name)
        allowed = set(sprim.symbols.values()) | {NAN}
        prog = program(name)
        for o in PRIMITIVES[name].outputs:
            for f in record_fields(o.kind, order):
                e = sprim.results[o.name][f]
                assert e.free_symbols <= allowed
                assert sp.expand(prog.expand(prog.results[o.name][f]) - e) == 0
        for let in sprim.lets.values():
            assert let.free_symbols <= allowed


def test_time_derivative_refuses_a_third_derivative():
    with pytest.raises(ValueError):
        time_derivative("crank_input", to_sympy("crank_input").results["j2"]["ddx"])


# --------------------------------------------------------------------------- backends


def _as_floats(smp: Sample) -> dict[str, object]:
    return {k: (v if isinstance(v, int) else float(v)) for k, v in smp.values().items()}


def call_numpy(name: str, order: int, rows: list[dict]):
    """The numpy primitive on the rows, its cosines and sines numpy's own (the runtime's cos_sin,
    a half-angle tangent, rounds differently: test_cos_sin_is_within_an_eps holds it), so that the
    arithmetic is the Python primitive's, in the same order."""
    values = {k: np.array([r[k] for r in rows]) for k in rows[0]}
    fn = numpy_backend(order)[name]
    fast = fn.__globals__["cos_sin"]
    fn.__globals__["cos_sin"] = lambda t: (np.cos(t), np.sin(t))
    try:
        with np.errstate(all="ignore"):
            st, sigma, *outs = fn(*args_of(name, order, values))
    finally:
        fn.__globals__["cos_sin"] = fast
    return np.broadcast_to(st, (len(rows),)), np.broadcast_to(sigma, (len(rows),)), outs


def test_cos_sin_is_within_an_eps():
    """The numpy runtime's cosine and sine from one half-angle tangent, against numpy's own over
    angles of several turns, the quarter turns and their neighbours: within 2 eps absolute."""
    cos_sin = numpy_backend(2)["crank_input"].__globals__["cos_sin"]
    rng = np.random.default_rng(7)
    quarter = np.pi / 2 * np.arange(-8, 9)
    t = np.concatenate([rng.uniform(-4 * np.pi, 4 * np.pi, 100_000), quarter, np.nextafter(quarter, np.inf),
                        np.nextafter(quarter, -np.inf), [1e-300, -1e-300, 0.0]])
    c, s = cos_sin(t)
    eps = np.finfo(float).eps
    assert np.max(np.abs(c - np.cos(t))) <= 2 * eps and np.max(np.abs(s - np.sin(t))) <= 2 * eps


def bits(x: float) -> int:
    return struct.unpack("<q", struct.pack("<d", float(x)))[0]


def same(a: float, b: float) -> bool:
    """Bit for bit, any nan equal to any nan."""
    return (math.isnan(a) and math.isnan(b)) or bits(a) == bits(b)


FLOAT_SAMPLES = 150  # per primitive and branch: the libm functions differ in a few percent of last bits


@functools.cache
def float_rows(name: str) -> tuple[dict, ...]:
    branches = (1, -1) if name in BRANCHED else (1,)
    rows = [_as_floats(s) for b in branches for s in samples(name, b, FLOAT_SAMPLES, exact=False)]
    return tuple(rows + [row for _, _, row in special_inputs(name)])


def _flat(outs) -> list[float]:
    """Every field of every output record, in order."""
    return [float(x) for rec in outs for x in rec]


# numpy's arctan2 is its own (vectorised) implementation, not the platform's libm: the
# angles it gives may differ from math.atan2 in the last bits.  Everything else is the
# same arithmetic in the same order, so it must give the same bits (crank_angle: its atan2(sin, cos)
# of an input many turns away).
ATAN2_FIELDS = {("link_angle", "angle", "the"), ("RPR_links", "psi", "the"), ("crank_angle", "angle", "the")}
ATAN2_ULPS = 4
# loop_residual's f is an arc, l times an angle from atan2 less s / l: the atan2 bits' difference, after the
# subtraction, is within ATAN2_ULPS ulps of pi times the leg l
ATAN2_ARCS = {("loop_residual", "f", "v"): "l_v"}


def _ulps(a: float, b: float) -> float:
    return abs(a - b) / math.ulp(max(abs(a), abs(b)))


@pytest.mark.parametrize("order", [0, 1, 2])
@pytest.mark.parametrize("name", list(MOTIONS))
def test_python_and_numpy_backends_bit_identical(name, order):
    rows = float_rows(name)
    st_n, sig_n, outs_n = call_numpy(name, order, list(rows))
    prim = PRIMITIVES[name]
    mismatches = []
    for i, row in enumerate(rows):
        st, sigma, outs = call_python(name, order, row)
        if st is not None:
            assert st == st_n[i]
        if sigma is not None:
            assert same(sigma, sig_n[i])
        fields = [(o.name, f) for o in prim.outputs for f in record_fields(o.kind, order)]
        py = _flat(outs)
        npv = [float(column[i]) for out in outs_n for column in out]
        assert len(py) == len(npv) == len(fields)
        for (o, f), a, b in zip(fields, py, npv):
            if (name, o, f) in ATAN2_FIELDS and _ulps(a, b) <= ATAN2_ULPS:
                continue
            arc = ATAN2_ARCS.get((name, o, f))
            if arc is not None and abs(a - b) <= ATAN2_ULPS * math.ulp(math.pi) * abs(row[arc]):
                continue
            if not same(a, b):
                mismatches.append(f"row {i} {o}.{f}: math {a!r} numpy {b!r}")
    assert not mismatches, f"{name} order {order}: {len(mismatches)} fields differ, e.g. {mismatches[:3]}"


@pytest.mark.parametrize("order", [0, 1])
@pytest.mark.parametrize("name", list(MOTIONS))
def test_lower_orders_are_leading_fields_of_order_2(name, order):
    prim = PRIMITIVES[name]
    rows = list(float_rows(name))
    full_n = call_numpy(name, 2, rows)
    low_n = call_numpy(name, order, rows)
    assert np.array_equal(full_n[0], low_n[0])
    assert np.array_equal(full_n[1], low_n[1], equal_nan=True)
    for i, row in enumerate(rows):
        full, low = call_python(name, 2, row), call_python(name, order, row)
        assert full[0] == low[0]
        assert full[1] is None or same(full[1], low[1])
        for o, rec_full, rec_low, rn_full, rn_low in zip(prim.outputs, full[2], low[2], full_n[2], low_n[2]):
            k = len(record_fields(o.kind, order))
            assert len(rec_low) == k and len(rn_low) == k
            for a, b, an, bn in zip(rec_full[:k], rec_low, rn_full[:k], rn_low):
                assert same(a, b), f"{name}.{o.name} math order {order}: {a!r} != {b!r}"
                assert same(float(an[i]), float(bn[i])), f"{name}.{o.name} numpy order {order}"


@pytest.mark.parametrize(("name", "branch"), CASES, ids=CASE_IDS)
def test_generated_python_matches_sympy_on_the_same_floats(name, branch):
    """The printed code computes what the DSL says: 50 digits on the same binary inputs."""
    prim = PRIMITIVES[name]
    worst = 0.0
    for smp in samples(name, branch):
        row = _as_floats(smp)
        ev = evaluate(name, {k: mpf(v) if not isinstance(v, int) else v for k, v in row.items()})
        _, _, outs = call_python(name, 2, row)
        scale = max(abs(v) for v in row.values())
        for o, rec in zip(prim.outputs, outs):
            for f, got in zip(record_fields(o.kind, 2), rec):
                err = float(discrepancy(mpf(got), ev.fields[(o.name, f)], scale))
                worst = max(worst, err)
                assert err <= 1e-12, f"{name}.{o.name}.{f}: {got!r} vs {ev.fields[(o.name, f)]}"
    assert worst <= 1e-12


# --------------------------------------------------------------------------- (e) status discipline


SPECIAL = [(n, *case) for n in MOTIONS for case in special_inputs(n)]


@pytest.mark.parametrize(("name", "what", "status", "row"), SPECIAL,
                         ids=[f"{n}-{w}-{i}" for i, (n, w, _, _) in enumerate(SPECIAL)])
def test_status_masks_outputs(name, what, status, row):
    """Status 1: every output nan; 3: displacements finite, rates nan; never inf; both backends.
    (A function that cannot fail has no status: None, and 0 from the evaluator's twin.)"""
    kinds = {o.name: o.kind for o in PRIMITIVES[name].outputs}
    st_n, _, outs_n = call_numpy(name, 2, [row])
    assert st_n[0] == (status or 0)
    for order in (0, 1, 2):
        st, _, fields = all_outputs(name, row, order)
        assert st == status, f"{name} {what}: status {st}"
        for out, f, x in fields:
            assert not math.isinf(x), f"{name}.{out}.{f} is inf"
            if st == 1 or (st == 3 and field_level(kinds[out], f) > 0):
                assert math.isnan(x), f"{name} status {st}: {out}.{f} = {x}"
            else:
                assert math.isfinite(x), f"{name} status {st}: {out}.{f} = {x}"
    for out in outs_n:
        for column in out:
            assert not np.isinf(column).any()


WITH_SIGMA = [n for n in PRIMITIVES if PRIMITIVES[n].sigma is not None]


@pytest.mark.parametrize("name", WITH_SIGMA)
def test_sigma_in_unit_interval(name):
    """On assembled motions, toggles and failures (coincident points apart, see below)."""
    rows = [row for row in float_rows(name)]
    rows = [r for r in rows if r not in [row for what, _, row in special_inputs(name) if what == "coincident"]]
    for row in rows:
        _, sigma, _ = call_python(name, 0, row)
        assert 0 <= sigma <= 1, (name, row, sigma)
    _, sig_n, _ = call_numpy(name, 0, rows)
    assert ((sig_n >= 0) & (sig_n <= 1)).all()


@pytest.mark.parametrize(
    ("name", "row"),
    [(n, row) for n in WITH_SIGMA for what, _, row in special_inputs(n) if what == "coincident"],
)
def test_sigma_is_a_number_when_points_coincide(name, row):
    """j1 == j2 (RRR) or jg == js (RPR): the chain cannot close; sigma must still be in [0, 1], not nan."""
    st, sigma, _ = call_python(name, 0, row)
    assert st == 1
    assert 0 <= sigma <= 1, f"{name}: sigma = {sigma!r} with status 1"


def best_conditioned_rows(name: str, count: int = 400) -> list[dict]:
    """Inputs at the best conditioning of each chain, where sigma is 1 in exact arithmetic."""
    rng = random.Random(f"best {name}")
    rows = []
    for _ in range(count):
        k = rng.choice([1, 3, 5, 7, 9, 11]) * 2.0 ** rng.randint(-20, 20)
        a = rng.uniform(-3.1, 3.1)
        if name == "RRR_links":
            # right angle at jb: Pythagorean triples, exact in floats
            p, r, hyp = rng.choice([(3, 4, 5), (5, 12, 13), (8, 15, 17), (7, 24, 25), (20, 21, 29)])
            l1, l2 = (p, r) if rng.random() < 0.5 else (r, p)
            args = ((0.0, 0.0), (hyp * k, 0.0), (l1 * k,), (l2 * k,), rng.choice([1, -1]))
        elif name == "PRR_links":
            # jr on the slider's line: the link is along the guide
            args = ((rng.uniform(-5, 5), 0.0), (rng.uniform(0.1, 10.0),), (0.0, 0.0), (0.0,), 0.0, 0.0, 1)
        elif name == "PRP_links":
            args = ((0.0, 0.0), (a,), 0.0, 0.0, (1.0, 1.0), (a + rng.choice([1, -1]) * PI / 2,), 0.0, 0.0)
        elif name == "RPR_links":
            # js on the guide's line (bg == bs)
            js = (rng.uniform(-5, 5) * k, rng.uniform(-5, 5) * k)
            args = ((0.0, 0.0), js, 0.0, 1.0, 0.0, 1.0, rng.choice([1, -1]))
        elif name == "PPR_links":
            args = ((1.0, 2.0), (0.0, 0.0), (a,), 0.0, 0.0, 0.0, 0.0, rng.choice([1, -1]) * PI / 2, 1)
        rows.append(named(name, args))  # records given up to order 0
    return rows


@pytest.mark.parametrize("name", WITH_SIGMA)
def test_sigma_never_rounds_above_one(name):
    """sigma is a sine or a ratio of a leg to its hypotenuse: at a right angle it must not round past 1."""
    over = []
    for row in best_conditioned_rows(name):
        _, sigma, _ = call_python(name, 0, row)
        if sigma > 1:
            over.append((sigma, row))
    assert not over, f"{name}: sigma > 1 in {len(over)} of 400 cases, e.g. {over[0]}"
