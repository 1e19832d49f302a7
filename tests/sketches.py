"""Random assembled sketches and independent 50-digit answers, for tests/test_properties.py.

Everything here is drawn as *positions*: pairs of a mechanism, or the points of one
two-link chain, at random places times a scale from 1e-6 to 1e6, some segments short
down to 1e-12 of the others.  Lengths and offsets are only ever derived from positions,
so every example is assembled (up to the rounding of the derived numbers).

* ``Source``: the random numbers, from hypothesis (``HypothesisSource``, shrinkable), from
  a seeded ``random.Random`` (``RandomSource``, for the deterministic program runs) or
  replayed from a list (``ReplaySource``: a counterexample kept as an explicit example).
  Every number drawn is inside the supported range (docs/mechanism-format.md): never
  subnormal, and 0 or at least ``TINY`` of its range's bound in magnitude (``reals``).
* Chains: ``CHAINS[name](src)`` gives a :class:`Case`, the float arguments of one runtime
  primitive (rates drawn at random: a chain has no freedom, so any rates are consistent),
  with an independent 50-digit answer (closed-form geometry in truncated Taylor arithmetic,
  :class:`Jet`, so velocities and accelerations are exact as well) and the chain's
  residual functions, written from the geometry the primitive's docstring states.
* Mechanisms: ``MECHANISMS[kind](src)`` gives a :class:`Sketch` (four-bar, slider-crank,
  inverted slider-crank, Watt and Stephenson six-bars, the Fig. 14 six-bar and a general
  triad), written as a mechanism file by :meth:`Sketch.yaml`.  ``reach`` follows the
  sketch's assembly with tests/reference.py (a float continuation from the sketch pose,
  then its 50-digit solve), never starting from linkgen's answer.
* ``WORST``: every worst error measured, for the summary table (tests/conftest.py).
"""

from __future__ import annotations

import math
import random
from dataclasses import dataclass, field, replace

import mpmath
import numpy as np
from reference import Reference

EPS = 2.0**-52
MP = mpmath.MPContext()
MP.dps = 50
SCALE_DIGITS = 6  # scales from 1e-6 to 1e6
NEEDLE_DIGITS = 12  # short segments down to 1e-12 of the others
TINY = 1e-30  # the supported range: a number drawn is 0 or at least this times its range's bound


# --------------------------------------------------------------------------- worst errors


@dataclass
class Worst:
    value: float = 0.0
    count: int = 0
    note: str = ""


WORST: dict[tuple[str, str, str], Worst] = {}


def record(prop: str, subject: str, quantity: str, value: float, note: str = "", count: int = 1) -> float:
    """Keep the largest value of (property, subject, quantity), where it was seen, and the count."""
    w = WORST.setdefault((prop, subject, quantity), Worst())
    w.count += count
    if value > w.value or (math.isnan(value) and not math.isnan(w.value)):
        w.value, w.note = value, note
    return value


def rows() -> list[list]:
    """WORST as plain rows (property, subject, quantity, value, count, note), for another process."""
    return [[*key, w.value, w.count, w.note] for key, w in WORST.items()]


def merge(table: list[list]) -> None:
    """Rows of another process's WORST (an xdist worker's) into this one's."""
    for prop, subject, quantity, value, count, note in table:
        record(prop, subject, quantity, value, note, count)


def summary() -> str:
    """The table of worst errors, one line per (property, subject, quantity)."""
    lines = [f"{'property':<26} {'subject':<22} {'quantity':<34} {'worst':>10} {'n':>7}"]
    for (prop, subject, quantity), w in sorted(WORST.items()):
        lines.append(f"{prop:<26} {subject:<22} {quantity:<34} {w.value:>10.3g} {w.count:>7}")
    return "\n".join(lines)


# --------------------------------------------------------------------------- random numbers


class Degenerate(Exception):
    """The drawn positions do not make a chain (two of its points coincide)."""



class Source:
    """Random numbers for the generators (subclasses draw them)."""

    def real(self, lo: float, hi: float) -> float:
        raise NotImplementedError

    def integer(self, lo: int, hi: int) -> int:
        raise NotImplementedError

    def choice(self, seq):
        return seq[self.integer(0, len(seq) - 1)]

    def flag(self) -> bool:
        return self.integer(0, 1) == 1

    # derived draws
    def scale(self) -> float:
        """A length scale from 1e-6 to 1e6."""
        return 10.0 ** self.real(-SCALE_DIGITS, SCALE_DIGITS)

    def ratio(self) -> float:
        """A short segment's length relative to the others: 1e-12 to 1."""
        return 10.0 ** -self.real(0, NEEDLE_DIGITS)

    def angle(self) -> float:
        return self.real(-math.pi, math.pi)

    def point(self, s: float) -> tuple[float, float]:
        return (s * self.real(-1, 1), s * self.real(-1, 1))

    def near(self, p: tuple[float, float], length: float) -> tuple[float, float]:
        """A point at ``length`` from p in a random direction (rounded to doubles)."""
        a = self.angle()
        return (p[0] + length * math.cos(a), p[1] + length * math.sin(a))


def reals(lo: float, hi: float):
    """The hypothesis strategy of the reals from lo to hi inside the supported range: never subnormal, and
    a magnitude below TINY times the range's bound drawn as 0 (lengths and coordinates stay within 1e-30 ..
    1e30 of the scale; decisions of issue 17)."""
    from hypothesis import strategies as st

    floor = TINY * max(abs(lo), abs(hi)) if lo <= 0 <= hi else 0.0
    return st.floats(lo, hi, allow_nan=False, allow_infinity=False, allow_subnormal=False).map(
        lambda x: x if abs(x) >= floor else 0.0)


class HypothesisSource(Source):
    """Numbers from hypothesis; ``drawn`` lists them in order, for a ReplaySource."""

    def __init__(self, draw):
        from hypothesis import strategies as st

        self.draw, self.st, self.drawn = draw, st, []

    def real(self, lo, hi):
        self.drawn.append(self.draw(reals(lo, hi)))
        return self.drawn[-1]

    def integer(self, lo, hi):
        self.drawn.append(self.draw(self.st.integers(lo, hi)))
        return self.drawn[-1]


class ReplaySource(Source):
    """The numbers a HypothesisSource drew, in order: a counterexample found by a property test."""

    def __init__(self, numbers):
        self.numbers = list(numbers)

    def real(self, lo, hi):
        x = self.numbers.pop(0)
        assert isinstance(x, float) and lo <= x <= hi, (x, lo, hi)
        return x

    def integer(self, lo, hi):
        n = self.numbers.pop(0)
        assert isinstance(n, int) and lo <= n <= hi, (n, lo, hi)
        return n


class RandomSource(Source):
    def __init__(self, seed):
        self.rng = random.Random(seed)

    def real(self, lo, hi):
        return self.rng.uniform(lo, hi)

    def integer(self, lo, hi):
        return self.rng.randint(lo, hi)


# --------------------------------------------------------------------------- Taylor arithmetic


def mp(x):
    return x if isinstance(x, Jet) else MP.mpf(x)


class Jet:
    """A quantity with its first and second time derivative, at 50 digits."""

    __slots__ = ("v", "d", "dd")

    def __init__(self, v, d=0, dd=0):
        self.v, self.d, self.dd = MP.mpf(v), MP.mpf(d), MP.mpf(dd)

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

    def __truediv__(self, o):
        o = Jet.of(o)
        q = self.v / o.v
        d = (self.d - q * o.d) / o.v
        return Jet(q, d, (self.dd - 2 * d * o.d - q * o.dd) / o.v)

    def __rtruediv__(self, o):
        return Jet.of(o) / self


def jsqrt(a: Jet) -> Jet:
    a = Jet.of(a)
    r = MP.sqrt(a.v)
    if r == 0:
        return Jet(0, MP.nan, MP.nan)
    d = a.d / (2 * r)
    return Jet(r, d, (a.dd - 2 * d * d) / (2 * r))


def jcos(a) -> Jet:
    a = Jet.of(a)
    c, s = MP.cos(a.v), MP.sin(a.v)
    return Jet(c, -s * a.d, -c * a.d**2 - s * a.dd)


def jsin(a) -> Jet:
    a = Jet.of(a)
    c, s = MP.cos(a.v), MP.sin(a.v)
    return Jet(s, c * a.d, -s * a.d**2 + c * a.dd)


def jatan2(y, x) -> Jet:
    """The angle of (x, y) with its rates: theta' = (x y' - y x')/r^2, and its derivative."""
    y, x = Jet.of(y), Jet.of(x)
    r2 = x.v**2 + y.v**2
    om = (x.v * y.d - y.v * x.d) / r2
    al = (x.v * y.dd - y.v * x.dd) / r2 - 2 * om * (x.v * x.d + y.v * y.d) / r2
    return Jet(MP.atan2(y.v, x.v), om, al)


def wrap(a):
    """Into (-pi, pi] (mpmath numbers)."""
    two = 2 * MP.pi
    return a - two * MP.ceil((a - MP.pi) / two)


def vsub(a, b):
    return (a[0] - b[0], a[1] - b[1])


def vadd(*vs):
    return tuple(sum(c[1:], c[0]) for c in zip(*vs))


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
    """gsi u + eta n."""
    return vadd(vscale(gsi, u), vscale(eta, normal(u)))


def vnorm(a):
    return jsqrt(vdot(a, a)) if isinstance(a[0], Jet) else MP.sqrt(vdot(a, a))


# --------------------------------------------------------------------------- one chain: a Case


@dataclass
class Case:
    """One call of a runtime primitive on assembled float inputs, with its 50-digit answer.

    ``exact`` maps each output to Jets (a POINT to (x, y)); None where the exact problem on
    these float inputs does not close (rounding of a derived length at a toggle).
    ``length`` is L of the step: the largest length, offset or coordinate it involves;
    ``ratio`` its longest link over its shortest; ``toggle`` marks an exact toggle;
    ``sigma`` the exact conditioning (nan where there is none).
    """

    name: str
    args: tuple
    values: dict  # parameter name -> mpmath number or Jet or (Jet, Jet) or int
    exact: dict | None
    length: float
    ratio: float
    sigma: float
    toggle: bool = False
    what: str = ""
    arm: float = 1.0  # length that turns an angle output's error into a length
    per: float = 1.0  # length that divides an area output (loop_turn's c) and its rates into lengths
    drawn: tuple = ()  # the numbers drawn (sketches.replay makes the case again from them)

    def note(self) -> str:
        return f"{self.name} {self.what} args={self.args!r}\nreplay: sketches.replay({self.name!r}, {self.drawn!r})"


def _rates(src: Source, s: float, w: float) -> tuple[float, float, float, float]:
    """Random velocity and acceleration components of a point of a body of size s turning at about w."""
    return (s * w * src.real(-1, 1), s * w * src.real(-1, 1), s * w * w * src.real(-1, 1), s * w * w * src.real(-1, 1))


def _pt_arg(p, r) -> tuple:
    return (p[0], p[1], r[0], r[1], r[2], r[3])


def _pt_jet(rec) -> tuple[Jet, Jet]:
    return (Jet(rec[0], rec[2], rec[4]), Jet(rec[1], rec[3], rec[5]))


def _rec_jet(rec) -> Jet:
    return Jet(*rec)


def _magnitude(*xs) -> float:
    return max(abs(float(x)) for x in xs)


def _sign(x) -> int:
    return 1 if x > 0 else -1 if x < 0 else 0


def _exact_len(a, b) -> float:
    """|b - a| of two double points, correctly rounded."""
    return float(MP.sqrt((MP.mpf(b[0]) - a[0]) ** 2 + (MP.mpf(b[1]) - a[1]) ** 2))


PYTHAGOREAN = ((3, 4, 5), (5, 12, 13), (8, 15, 17), (7, 24, 25), (20, 21, 29), (1, 0, 1))


def _pythagorean(src: Source) -> tuple[int, int, int]:
    """An exact direction (a, b)/c, turned by a random multiple of 90 degrees or mirrored."""
    a, b, c = src.choice(PYTHAGOREAN)
    if src.flag():
        a, b = b, a
    return (a if src.flag() else -a), (b if src.flag() else -b), c


def _dyadic_point(src: Source, unit: float, bits: int = 30) -> tuple[float, float]:
    return (src.integer(-(2**bits), 2**bits) * unit, src.integer(-(2**bits), 2**bits) * unit)


def _toggle_multiples(src: Source) -> tuple[int, int]:
    """(k, m): the chain's far pair at k steps, its middle pair at m steps along one exact direction.

    m between 0 and k puts the middle pair between the ends (stretched out), outside folds it back;
    a short link is a small m (or k - m, or m - k) against k up to 2^40.
    """
    k = src.integer(1, 2**src.integer(1, 40))
    kind = src.integer(0, 2)
    if kind == 0:  # stretched: 0 < m < k
        m = src.integer(1, max(1, k - 1)) if k > 1 else 1
        if k == 1:
            k = 2
    elif kind == 1:  # folded beyond the far end
        m = k + src.integer(1, 2**src.integer(0, 40))
    else:  # folded behind the near end
        m = -src.integer(1, 2**src.integer(0, 40))
    return k, m


def _unit(s: float) -> float:
    """A power of two near s / 2^40: integer multiples of it up to 2^52 are exact."""
    return 2.0 ** (round(math.log2(s)) - 40)


def _angular(src: Source) -> float:
    return 10.0 ** src.real(-2, 2)


def rrr_case(src: Source) -> Case:
    """3R chain: P1, P2 known; B at distance l1 from P1 and l2 from P2."""
    s = src.scale()
    mode = src.choice(("random", "random", "needle", "toggle", "near toggle"))
    toggle = False
    if mode in ("random", "needle"):
        p1, p2, b = src.point(s), src.point(s), src.point(s)
        if mode == "needle":
            short = src.choice(("l1", "l2", "q"))
            ln = s * src.ratio()
            if short == "l1":
                b = src.near(p1, ln)
            elif short == "l2":
                b = src.near(p2, ln)
            else:
                p2 = src.near(p1, ln)
    else:
        a, bb, c = _pythagorean(src)
        unit = _unit(s)
        p1 = _dyadic_point(src, unit * 2**10)
        k, m = _toggle_multiples(src)
        p2 = (p1[0] + k * a * unit, p1[1] + k * bb * unit)
        b = (p1[0] + m * a * unit, p1[1] + m * bb * unit)
        toggle = mode == "toggle"
        if not toggle:  # off the line by 1e-16 to 1e-3 of the chain
            eps_off = 10.0 ** -src.real(3, 16) * abs(k * c * unit)
            b = (b[0] - bb / c * eps_off, b[1] + a / c * eps_off)
    side = vcross(vsub([MP.mpf(x) for x in p2], p1), vsub([MP.mpf(x) for x in b], p1))
    minv = _sign(side) or src.choice((1, -1))
    l1, l2 = _exact_len(p1, b), _exact_len(p2, b)
    if min(l1, l2, _exact_len(p1, p2)) == 0:
        raise Degenerate("RRR: two pairs coincide")
    w = _angular(src)
    r1, r2 = _rates(src, s, w), _rates(src, s, w)
    dl = (s * w * src.real(-1, 1), s * w * w * src.real(-1, 1))
    dl2 = (s * w * src.real(-1, 1), s * w * w * src.real(-1, 1))
    args = (_pt_arg(p1, r1), _pt_arg(p2, r2), (l1, *dl), (l2, *dl2), minv)
    j1, j2, L1, L2 = _pt_jet(args[0]), _pt_jet(args[1]), _rec_jet(args[2]), _rec_jet(args[3])
    d = vsub(j2, j1)
    q = vnorm(d)
    a_ = (vdot(d, d) + L1 * L1 - L2 * L2) / (2 * q)
    h2 = L1 * L1 - a_ * a_
    q_f = float(q.v)
    length = max(l1, l2, q_f, _magnitude(*p1, *p2, *b))
    lengths = [x for x in (l1, l2, q_f) if x > 0]
    ratio = max(lengths) / min(lengths)
    values = {"j1": j1, "j2": j2, "l1": L1, "l2": L2, "minv": minv}
    if h2.v < 0 or q.v == 0:
        return Case("RRR_links", args, values, None, length, ratio, 0.0, toggle, mode)
    if h2.v == 0:
        u = (d[0].v / q.v, d[1].v / q.v)
        pos = (j1[0].v + a_.v * u[0], j1[1].v + a_.v * u[1])
        jb = (Jet(pos[0], MP.nan, MP.nan), Jet(pos[1], MP.nan, MP.nan))
        return Case("RRR_links", args, values, {"jb": jb}, length, ratio, 0.0, toggle, mode)
    h = jsqrt(h2)
    u = (d[0] / q, d[1] / q)
    jb = vadd(j1, local(u, a_, minv * h))
    sigma = float(h.v * q.v / (L1.v * L2.v))
    return Case("RRR_links", args, values, {"jb": jb}, length, ratio, sigma, toggle, mode)


def prr_case(src: Source) -> Case:
    """2R1P chain: B at distance l from R, carried at (gsi, eta) by a slider on the line (pg, psig)."""
    s = src.scale()
    mode = src.choice(("random", "random", "needle", "toggle", "near toggle"))
    toggle = False
    if mode in ("random", "needle"):
        pg, jr, jb = src.point(s), src.point(s), src.point(s)
        psig = src.angle()
        off = src.choice(("random", "zero", "short"))
        u = (math.cos(psig), math.sin(psig))
        if off == "random":
            gsi, eta = s * src.real(-1, 1), s * src.real(-1, 1)
        elif off == "zero":
            gsi, eta = 0.0, 0.0
        else:
            gsi, eta = s * src.ratio() * src.real(-1, 1), s * src.ratio() * src.real(-1, 1)
        if mode == "needle":
            jr = src.near(jb, s * src.ratio())
        # the slider point sits on the line: move pg along the normal so jb - (gsi, eta) is on it
        jp = (jb[0] - gsi * u[0] + eta * u[1], jb[1] - gsi * u[1] - eta * u[0])
        t = (jp[0] - pg[0]) * u[0] + (jp[1] - pg[1]) * u[1]
        pg = (jp[0] - t * u[0], jp[1] - t * u[1])
    else:
        unit = _unit(s)
        psig = 0.0
        gsi, eta = src.integer(-(2**20), 2**20) * unit * 2**20, src.integer(-(2**20), 2**20) * unit * 2**20
        pg = _dyadic_point(src, unit * 2**10)
        jb = _dyadic_point(src, unit * 2**10)
        pg = (pg[0], jb[1] - eta)  # the slider point jb - (gsi, eta) lies on the line y = pg.y
        k = src.integer(1, 2**src.integer(1, 40))
        jr = (jb[0], jb[1] + src.choice((1, -1)) * k * unit)  # the link square to the guide
        toggle = mode == "toggle"
        if not toggle:
            jr = (jr[0] + src.choice((1, -1)) * 10.0 ** -src.real(3, 16) * k * unit, jr[1])
    u_mp = (MP.cos(psig), MP.sin(psig))
    minv = _sign(vdot(vsub([MP.mpf(x) for x in jb], jr), u_mp)) or src.choice((1, -1))
    ln = _exact_len(jr, jb)
    if ln == 0:
        raise Degenerate("PRR: the link has no length")
    w = _angular(src)
    rr, rg = _rates(src, s, w), _rates(src, s, w)
    args = (_pt_arg(jr, rr), (ln, s * w * src.real(-1, 1), s * w * w * src.real(-1, 1)), _pt_arg(pg, rg),
            (psig, w * src.real(-1, 1), w * w * src.real(-1, 1)), gsi, eta, minv)
    JR, L, PG, PS = _pt_jet(args[0]), _rec_jet(args[1]), _pt_jet(args[2]), _rec_jet(args[3])
    u = direction(PS)
    r = local(u, mp(gsi), mp(eta))
    wv = vsub(vadd(PG, r), JR)
    c = vdot(wv, normal(u))
    d2 = L * L - c * c
    length = max(ln, _magnitude(*jr, *pg, *jb, gsi, eta))
    ratio = length / ln if ln > 0 else math.inf
    values = {"jr": JR, "l": L, "pg": PG, "psig": PS, "gsi": mp(gsi), "eta": mp(eta), "minv": minv}
    if d2.v < 0:
        return Case("PRR_links", args, values, None, length, ratio, 0.0, toggle, mode)
    root = jsqrt(d2) if d2.v > 0 else Jet(0, MP.nan, MP.nan)
    sv = minv * root - vdot(wv, u)
    jp = vadd(PG, vscale(sv, u))
    jbx = vadd(jp, r)
    sigma = float(root.v / L.v)
    return Case("PRR_links", args, values, {"s": sv, "jp": jp, "jb": jbx}, length, ratio, sigma, toggle, mode)


def rpr_case(src: Source) -> Case:
    """RPR chain: a guide turning about G and a slider turning about S slide along one line."""
    s = src.scale()
    mode = src.choice(("random", "random", "needle", "toggle", "near toggle"))
    toggle = False
    if mode in ("random", "needle"):
        jg, js = src.point(s), src.point(s)
        psi = src.angle()
        jp = src.point(s)  # the slider's copy of the pair's reference point
        if mode == "needle":
            which = src.choice(("q", "slider offset", "guide offset"))
            if which == "q":
                js = src.near(jg, s * src.ratio())
            elif which == "slider offset":
                jp = src.near(js, s * src.ratio())
        sv = s * src.real(-1, 1)
        u = (math.cos(psi), math.sin(psi))
        if mode == "needle" and which == "guide offset":
            g = src.near(jg, s * src.ratio())
            jp = (g[0] + sv * u[0], g[1] + sv * u[1])
        g = (jp[0] - sv * u[0], jp[1] - sv * u[1])  # the guide's copy
        # js must see the line where jg does: move js along the normal onto it
        dn_g = -(g[0] - jg[0]) * u[1] + (g[1] - jg[1]) * u[0]
        dn_s = -(jp[0] - js[0]) * u[1] + (jp[1] - js[1]) * u[0]
        ag = (g[0] - jg[0]) * u[0] + (g[1] - jg[1]) * u[1]
        as_ = (jp[0] - js[0]) * u[0] + (jp[1] - js[1]) * u[1]
        bg, bs = dn_g, dn_s
    else:
        unit = _unit(s)
        a, b, c = _pythagorean(src)
        jg = _dyadic_point(src, unit * 2**10)
        k = src.integer(1, 2**src.integer(1, 40))
        js = (jg[0] + k * a * unit, jg[1] + k * b * unit)
        hh = src.choice((1, -1)) * k * c * unit  # |d| = |hh|: d square to the line
        bs = src.integer(-(2**30), 2**30) * unit * 2**10
        bg = bs + hh
        ag, as_ = src.integer(-(2**30), 2**30) * unit * 2**10, src.integer(-(2**30), 2**30) * unit * 2**10
        toggle = mode == "toggle"
        if not toggle:
            bg = bs + hh * (1 - 10.0 ** -src.real(3, 16))
        psi = math.nan
    w = _angular(src)
    args = (_pt_arg(jg, _rates(src, s, w)), _pt_arg(js, _rates(src, s, w)), ag, bg, as_, bs, 1)
    JG, JS = _pt_jet(args[0]), _pt_jet(args[1])
    d = vsub(JS, JG)
    hh = mp(bg) - mp(bs)
    q2 = vdot(d, d)
    t2 = q2 - hh * hh
    minv = src.choice((1, -1)) if mode in ("toggle", "near toggle") else _sign(
        vdot(vsub([MP.mpf(x) for x in js], jg), (MP.cos(psi), MP.sin(psi)))) or 1
    args = (*args[:6], minv)
    q = float(MP.sqrt(q2.v))
    if q == 0:
        raise Degenerate("RPR: the pivots coincide")
    length = max(q, _magnitude(*jg, *js, ag, bg, as_, bs))
    ratio = length / q if q > 0 else math.inf
    values = {"jg": JG, "js": JS, "ag": mp(ag), "bg": mp(bg), "as_": mp(as_), "bs": mp(bs), "minv": minv}
    if t2.v < 0 or q2.v == 0:
        return Case("RPR_links", args, values, None, length, ratio, 0.0, toggle, mode)
    t = jsqrt(t2) if t2.v > 0 else Jet(0, MP.nan, MP.nan)
    mt = minv * t
    u = ((mt * d[0] + hh * d[1]) / q2, (mt * d[1] - hh * d[0]) / q2)
    if t2.v == 0:
        u = tuple(Jet(x.v, MP.nan, MP.nan) for x in u)
    psi_j = jatan2(u[1], u[0]) if t2.v > 0 else Jet(MP.atan2(u[1].v, u[0].v), MP.nan, MP.nan)
    sv = mt + (mp(as_) - mp(ag))
    jp = vadd(JS, local(u, mp(as_), mp(bs)))
    sigma = float(t.v / max(MP.sqrt(q2.v), *(abs(mp(x)) for x in (ag, bg, as_, bs))))
    return Case("RPR_links", args, values, {"psi": psi_j, "s": sv, "jp": jp}, length, ratio, sigma, toggle, mode, q)


def prp_case(src: Source) -> Case:
    """1R2P chain: B carried by two sliders on two guide lines."""
    s = src.scale()
    mode = src.choice(("random", "random", "needle", "near parallel"))
    jb = src.point(s)
    psig1 = src.angle()
    psig2 = src.angle()
    if mode == "near parallel":
        psig2 = psig1 + src.choice((0.0, math.pi)) + src.choice((1, -1)) * 10.0 ** -src.real(1, 15)
    offs = []
    for _ in range(2):
        kind = src.choice(("random", "zero", "short")) if mode == "needle" else src.choice(("random", "zero"))
        k = s * (src.ratio() if kind == "short" else 1.0) * (0.0 if kind == "zero" else 1.0)
        offs.append((k * src.real(-1, 1), k * src.real(-1, 1), s * src.real(-1, 1)))
    pgs = []
    for psig, (gsi, eta, sv) in zip((psig1, psig2), offs):
        u = (math.cos(psig), math.sin(psig))
        pgs.append((jb[0] - (sv + gsi) * u[0] + eta * u[1], jb[1] - (sv + gsi) * u[1] - eta * u[0]))
    w = _angular(src)
    args = (_pt_arg(pgs[0], _rates(src, s, w)), (psig1, w * src.real(-1, 1), w * w * src.real(-1, 1)),
            offs[0][0], offs[0][1],
            _pt_arg(pgs[1], _rates(src, s, w)), (psig2, w * src.real(-1, 1), w * w * src.real(-1, 1)),
            offs[1][0], offs[1][1])
    P1, S1, P2, S2 = _pt_jet(args[0]), _rec_jet(args[1]), _pt_jet(args[4]), _rec_jet(args[5])
    u1, u2 = direction(S1), direction(S2)
    c1 = vadd(P1, local(u1, mp(args[2]), mp(args[3])))
    c2 = vadd(P2, local(u2, mp(args[6]), mp(args[7])))
    g = vsub(c2, c1)
    cr = vcross(u1, u2)
    length = _magnitude(*pgs[0], *pgs[1], *jb, *offs[0], *offs[1])
    values = {"pg1": P1, "psig1": S1, "gsi1": mp(args[2]), "eta1": mp(args[3]),
              "pg2": P2, "psig2": S2, "gsi2": mp(args[6]), "eta2": mp(args[7])}
    if cr.v == 0:
        return Case("PRP_links", args, values, None, length, 1.0, 0.0, False, mode)
    s1, s2 = vcross(g, u2) / cr, vcross(g, u1) / cr
    jp1, jp2 = vadd(P1, vscale(s1, u1)), vadd(P2, vscale(s2, u2))
    out = {"s1": s1, "jp1": jp1, "s2": s2, "jp2": jp2, "jb": vadd(jp1, local(u1, mp(args[2]), mp(args[3])))}
    return Case("PRP_links", args, values, out, length, 1.0, float(abs(cr.v)), False, mode)


def ppr_case(src: Source) -> Case:
    """PPR chain (Scotch yoke): b slides on a guide, a turns about R and slides on b."""
    s = src.scale()
    mode = src.choice(("random", "random", "needle", "near parallel"))
    pg = src.point(s)
    psig = src.angle()
    cx = src.real(-math.pi, math.pi)
    if mode == "near parallel":
        cx = src.choice((0.0, math.pi)) + src.choice((1, -1)) * 10.0 ** -src.real(1, 15)
    short = mode == "needle"
    xa, ya, xb, yb = (s * (src.ratio() if short and src.flag() else 1.0) * src.real(-1, 1) for _ in range(4))
    s1, sx = s * src.real(-1, 1), s * src.real(-1, 1)
    sgn = src.choice((1, -1))
    u1 = (math.cos(psig), math.sin(psig))
    ux = (math.cos(psig + cx), math.sin(psig + cx))
    jp1 = (pg[0] + s1 * u1[0], pg[1] + s1 * u1[1])
    pb = (jp1[0] + xb * u1[0] - yb * u1[1], jp1[1] + xb * u1[1] + yb * u1[0])
    pa = (pb[0] + sgn * sx * ux[0], pb[1] + sgn * sx * ux[1])
    jr = (pa[0] - xa * u1[0] + ya * u1[1], pa[1] - xa * u1[1] - ya * u1[0])
    w = _angular(src)
    args = (_pt_arg(jr, _rates(src, s, w)), _pt_arg(pg, _rates(src, s, w)),
            (psig, w * src.real(-1, 1), w * w * src.real(-1, 1)), xa, ya, xb, yb, cx, sgn)
    JR, PG, PS = _pt_jet(args[0]), _pt_jet(args[1]), _rec_jet(args[2])
    U1, UX = direction(PS), direction(PS + mp(cx))
    ra, rb = local(U1, mp(xa), mp(ya)), local(U1, mp(xb), mp(yb))
    pa_j = vadd(JR, ra)
    wv = vsub(vsub(pa_j, PG), rb)
    cr = vcross(U1, UX)
    length = _magnitude(*jr, *pg, *pa, *pb, xa, ya, xb, yb)
    values = {"jr": JR, "pg": PG, "psig": PS, "xa": mp(xa), "ya": mp(ya), "xb": mp(xb), "yb": mp(yb),
              "cx": mp(cx), "sgn": sgn}
    if cr.v == 0:
        return Case("PPR_links", args, values, None, length, 1.0, 0.0, False, mode)
    sv1 = vcross(wv, UX) / cr
    jp1j = vadd(PG, vscale(sv1, U1))
    pb_j = vadd(jp1j, rb)
    sxj = sgn * vdot(vsub(pa_j, pb_j), UX)
    out = {"s1": sv1, "jp1": jp1j, "sx": sxj, "jpx": pa_j if sgn > 0 else pb_j}
    return Case("PPR_links", args, values, out, length, 1.0, float(abs(cr.v)), False, mode)


def coupler_point_case(src: Source) -> Case:
    s = src.scale()
    j0 = src.point(s)
    short = src.flag()
    jc = src.near(j0, s * src.ratio()) if short else src.point(s)
    phi = src.angle()
    c, sn = math.cos(phi), math.sin(phi)
    dx, dy = jc[0] - j0[0], jc[1] - j0[1]
    gsi, eta = c * dx + sn * dy, -sn * dx + c * dy
    w = _angular(src)
    args = (_pt_arg(j0, _rates(src, s, w)), (phi, w * src.real(-1, 1), w * w * src.real(-1, 1)), gsi, eta)
    J0, PH = _pt_jet(args[0]), _rec_jet(args[1])
    out = {"jc": vadd(J0, local(direction(PH), mp(gsi), mp(eta)))}
    length = _magnitude(*j0, *jc, gsi, eta)
    return Case("coupler_point", args, {"j0": J0, "phi": PH, "gsi": mp(gsi), "eta": mp(eta)}, out, length,
                1.0, math.nan, False, "short" if short else "random")


def link_point_case(src: Source) -> Case:
    """A point of a link in the frame of two of its points (a needle of a base with a far point in the short
    mode): gsi and eta as the extraction rounds them, the exact point from those doubles."""
    s = src.scale()
    j1 = src.point(s)
    short = src.flag()
    j2 = src.near(j1, s * src.ratio()) if short else src.point(s)
    jc = src.point(s)
    dx, dy, rx, ry = (MP.mpf(j2[0]) - j1[0], MP.mpf(j2[1]) - j1[1], MP.mpf(jc[0]) - j1[0], MP.mpf(jc[1]) - j1[1])
    q = MP.sqrt(dx * dx + dy * dy)
    if q == 0:
        raise Degenerate("link_point: the base's points coincide")
    gsi, eta = float((rx * dx + ry * dy) / q), float((dx * ry - dy * rx) / q)
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), _pt_arg(j2, _rates(src, s, w)), gsi, eta)
    J1, J2 = _pt_jet(args[0]), _pt_jet(args[1])
    d = vsub(J2, J1)
    out = {"jc": vadd(J1, local(vscale(1 / vnorm(d), d), mp(gsi), mp(eta)))}
    arm = math.hypot(gsi, eta) / float(q)
    length = max(_magnitude(*j1, *j2, *jc), math.hypot(gsi, eta))
    return Case("link_point", args, {"j1": J1, "j2": J2, "gsi": mp(gsi), "eta": mp(eta)}, out, length,
                max(1.0, arm), math.nan, False, "short" if short else "random")


def pair_point_case(src: Source) -> Case:
    """A point of a link linear in two of its points (a needle of a base with a far point in the short mode):
    along and across as the extraction rounds them (the nearest doubles), the exact point from those doubles."""
    s = src.scale()
    j1 = src.point(s)
    short = src.flag()
    j2 = src.near(j1, s * src.ratio()) if short else src.point(s)
    jc = src.point(s)
    dx, dy, rx, ry = (MP.mpf(j2[0]) - j1[0], MP.mpf(j2[1]) - j1[1], MP.mpf(jc[0]) - j1[0], MP.mpf(jc[1]) - j1[1])
    q2 = dx * dx + dy * dy
    if q2 == 0:
        raise Degenerate("pair_point: the base's points coincide")
    along, across = float((rx * dx + ry * dy) / q2), float((dx * ry - dy * rx) / q2)
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), _pt_arg(j2, _rates(src, s, w)), along, across)
    J1, J2 = _pt_jet(args[0]), _pt_jet(args[1])
    out = {"jc": vadd(J1, local(vsub(J2, J1), mp(along), mp(across)))}
    arm = math.hypot(along, across)
    length = max(_magnitude(*j1, *j2, *jc), arm * float(MP.sqrt(q2)))
    return Case("pair_point", args, {"j1": J1, "j2": J2, "along": mp(along), "across": mp(across)}, out, length,
                max(1.0, arm), math.nan, False, "short" if short else "random")


def link_angle_case(src: Source) -> Case:
    s = src.scale()
    j1 = src.point(s)
    short = src.flag()
    j2 = src.near(j1, s * src.ratio()) if short else src.point(s)
    off = src.angle()
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), _pt_arg(j2, _rates(src, s, w)), off)
    J1, J2 = _pt_jet(args[0]), _pt_jet(args[1])
    d = vsub(J2, J1)
    values = {"j1": J1, "j2": J2, "off": mp(off)}
    if d[0].v == 0 and d[1].v == 0:
        raise Degenerate("link_angle: the points coincide")
    th = jatan2(d[1], d[0])
    th = Jet(wrap(th.v + mp(off)), th.d, th.dd)
    r = float(MP.sqrt(vdot(d, d).v))
    length = max(r, _magnitude(*j1, *j2))  # the link itself may be longer than any coordinate
    return Case("link_angle", args, values, {"angle": th}, length, length / r, math.nan, False,
                "short" if short else "random", r)


def link_direction_case(src: Source) -> Case:
    """The unit vector of a link from two of its points, turned by the sketch offset (c, s):
    dimensionless, so L of the step is 1."""
    s = src.scale()
    j1 = src.point(s)
    short = src.flag()
    j2 = src.near(j1, s * src.ratio()) if short else src.point(s)
    off = src.angle()
    c, sn = math.cos(off), math.sin(off)
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), _pt_arg(j2, _rates(src, s, w)), c, sn)
    J1, J2 = _pt_jet(args[0]), _pt_jet(args[1])
    d = vsub(J2, J1)
    if d[0].v == 0 and d[1].v == 0:
        raise Degenerate("link_direction: the points coincide")
    r = vnorm(d)
    out = {"u": local(vscale(1 / r, d), mp(c), mp(sn))}
    return Case("link_direction", args, {"j1": J1, "j2": J2, "c": mp(c), "s": mp(sn)}, out, 1.0, 1.0, math.nan,
                False, "short" if short else "random")


def angle_direction_case(src: Source) -> Case:
    phi = src.angle()
    w = _angular(src)
    args = ((phi, w * src.real(-1, 1), w * w * src.real(-1, 1)),)
    PH = _rec_jet(args[0])
    return Case("angle_direction", args, {"phi": PH}, {"u": direction(PH)}, 1.0, 1.0, math.nan)


def crank_input_case(src: Source) -> Case:
    s = src.scale()
    j1 = src.point(s)
    j2 = src.near(j1, s * src.ratio()) if src.flag() else src.point(s)
    ln = _exact_len(j1, j2)
    phi = src.angle()
    theta = math.atan2(j2[1] - j1[1], j2[0] - j1[0]) - phi
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), ln, (theta, w * src.real(-1, 1), w * w * src.real(-1, 1)),
            (phi, w * src.real(-1, 1), w * w * src.real(-1, 1)))
    J1, TH, PH = _pt_jet(args[0]), _rec_jet(args[2]), _rec_jet(args[3])
    out = {"j2": vadd(J1, vscale(mp(ln), direction(TH + PH)))}
    length = _magnitude(*j1, *j2, ln)
    return Case("crank_input", args, {"j1": J1, "l": mp(ln), "theta": TH, "phi": PH}, out, length, 1.0, math.nan)


def slider_input_case(src: Source) -> Case:
    s = src.scale()
    pg = src.point(s)
    psig = src.angle()
    sv = s * src.real(-1, 1)
    gsi, eta = (s * src.ratio() * src.real(-1, 1), s * src.real(-1, 1)) if src.flag() else (
        s * src.real(-1, 1), s * src.real(-1, 1))
    w = _angular(src)
    args = (_pt_arg(pg, _rates(src, s, w)), (psig, w * src.real(-1, 1), w * w * src.real(-1, 1)),
            (sv, s * w * src.real(-1, 1), s * w * w * src.real(-1, 1)), gsi, eta)
    PG, PS, SV = _pt_jet(args[0]), _rec_jet(args[1]), _rec_jet(args[2])
    u = direction(PS)
    jp = vadd(PG, vscale(SV, u))
    out = {"jp": jp, "jc": vadd(jp, local(u, mp(gsi), mp(eta)))}
    length = _magnitude(*pg, sv, gsi, eta, float(jp[0].v), float(jp[1].v), float(out["jc"][0].v),
                        float(out["jc"][1].v))
    return Case("slider_input", args, {"pg": PG, "psig": PS, "s": SV, "gsi": mp(gsi), "eta": mp(eta)}, out,
                length, 1.0, math.nan)


def offset_angle_case(src: Source) -> Case:
    phi, off = src.angle(), src.angle()
    w = _angular(src)
    args = ((phi, w * src.real(-1, 1), w * w * src.real(-1, 1)), off)
    PH = _rec_jet(args[0])
    out = {"angle": Jet(wrap(PH.v + mp(off)), PH.d, PH.dd)}
    return Case("offset_angle", args, {"phi": PH, "off": mp(off)}, out, math.pi, 1.0, math.nan)


def crank_angle_case(src: Source) -> Case:
    """An input angle (now and then many turns away) and a root angle, summed with an offset and wrapped."""
    theta = src.angle() + 2 * math.pi * src.choice((0, 0, 0, 2, -7))
    phi, off = src.angle(), src.angle()
    w = _angular(src)
    args = ((theta, w * src.real(-1, 1), w * w * src.real(-1, 1)), (phi, w * src.real(-1, 1), w * w * src.real(-1, 1)),
            off)
    TH, PH = _rec_jet(args[0]), _rec_jet(args[1])
    total = TH + PH
    out = {"angle": Jet(wrap(total.v + mp(off)), total.d, total.dd)}
    return Case("crank_angle", args, {"theta": TH, "phi": PH, "off": mp(off)}, out, max(math.pi, abs(theta)), 1.0,
                math.nan)


def link_residual_case(src: Source) -> Case:
    s = src.scale()
    j1 = src.point(s)
    j2 = src.near(j1, s * src.ratio()) if src.flag() else src.point(s)
    ln = _exact_len(j1, j2) * (1 + src.real(-1e-3, 1e-3))
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), _pt_arg(j2, _rates(src, s, w)),
            (ln, s * w * src.real(-1, 1), s * w * w * src.real(-1, 1)))
    J1, J2, LN = _pt_jet(args[0]), _pt_jet(args[1]), _rec_jet(args[2])
    r = vnorm(vsub(J2, J1))
    length = _magnitude(*j1, *j2, ln)
    values = {"j1": J1, "j2": J2, "l": LN}
    if r.v == 0:
        raise Degenerate("link_residual: the points coincide")
    return Case("link_residual", args, values, {"f": r - LN}, length, length / float(r.v), math.nan)


def loop_point_case(src: Source) -> Case:
    """A loop's leg of length l (a needle now and then) at the assumed angle theta in (-pi, pi], carried as the
    arc length s = l theta rounded to a double; the leg's length is constant (no rates)."""
    s = src.scale()
    j1 = src.point(s)
    short = src.flag()
    ln = s * (src.ratio() if short else src.real(0.1, 2))
    sv = ln * src.angle()
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), (ln, 0.0, 0.0),
            (sv, ln * w * src.real(-1, 1), ln * w * w * src.real(-1, 1)))
    J1, LN, S = _pt_jet(args[0]), _rec_jet(args[1]), _rec_jet(args[2])
    out = {"j2": vadd(J1, vscale(LN, direction(S / LN)))}
    length = _magnitude(*j1, ln, sv, out["j2"][0].v, out["j2"][1].v)
    return Case("loop_point", args, {"j1": J1, "l": LN, "s": S}, out, length, 1.0, math.nan, False,
                "short" if short else "random")


def loop_residual_case(src: Source) -> Case:
    """X1 come back round the loop at the distance l from K1 (a needle now and then), the assumed angle theta
    = atan2 - m a turn away now and then (m in (-3.1, 3.1): the wrap is never within 0.04 of its edge), carried
    as s = l theta: f = l wrap(atan2(X1 - K1) - s / l) with its rates."""
    s = src.scale()
    j1 = src.point(s)
    short = src.flag()
    j2 = src.near(j1, s * src.ratio()) if short else src.point(s)
    ln = _exact_len(j1, j2)
    if ln == 0:
        raise Degenerate("loop_residual: the points coincide")
    theta = math.atan2(j2[1] - j1[1], j2[0] - j1[0]) - src.real(-3.1, 3.1) + 2 * math.pi * src.choice((0, 0, 1, -1))
    w = _angular(src)
    args = (_pt_arg(j1, _rates(src, s, w)), _pt_arg(j2, _rates(src, s, w)), (ln, 0.0, 0.0),
            (ln * theta, ln * w * src.real(-1, 1), ln * w * w * src.real(-1, 1)))
    J1, J2, LN, S = _pt_jet(args[0]), _pt_jet(args[1]), _rec_jet(args[2]), _rec_jet(args[3])
    d = vsub(J2, J1)
    if d[0].v == 0 and d[1].v == 0:
        raise Degenerate("loop_residual: the points coincide")
    th = jatan2(d[1], d[0])
    back = S / LN
    f = LN * Jet(wrap(th.v - back.v), th.d - back.d, th.dd - back.dd)
    length = _magnitude(*j1, *j2, ln, args[3][0])
    return Case("loop_residual", args, {"j1": J1, "j2": J2, "l": LN, "s": S}, {"f": f}, length, length / ln,
                math.nan, False, "short" if short else "random")


def loop_turn_case(src: Source) -> Case:
    """A body's three pairs (two of them close now and then) and the turn they are drawn with: c = (j2 - j1) x
    (j3 - j1), an area, compared as a length over the longer side; within 4 eps of collinear the float inputs
    do not resolve the sign (no exact answer is required there)."""
    s = src.scale()
    j1 = src.point(s)
    short = src.choice(("", "j2", "j3"))
    j2 = src.near(j1, s * src.ratio()) if short == "j2" else src.point(s)
    j3 = src.near(j1, s * src.ratio()) if short == "j3" else src.point(s)
    w = _angular(src)
    pts = tuple(_pt_arg(p, _rates(src, s, w)) for p in (j1, j2, j3))
    J1, J2, J3 = (_pt_jet(p) for p in pts)
    u, v = vsub(J2, J1), vsub(J3, J1)
    c = vcross(u, v)
    if c.v == 0:
        raise Degenerate("loop_turn: the pairs are collinear")
    args = (*pts, _sign(c.v))
    sides = (float(vnorm(u).v), float(vnorm(v).v))
    sine = float(abs(c.v)) / (sides[0] * sides[1])
    exact = {"c": c} if sine > 4 * EPS else None
    length = max(_magnitude(*j1, *j2, *j3), *sides)
    return Case("loop_turn", args, {"j1": J1, "j2": J2, "j3": J3, "turn": _sign(c.v)}, exact, length, 1.0, sine,
                False, short or "random", per=max(sides))


def _checked(make):
    def case(src: Source) -> Case:
        c = make(src)
        if not c.length > 0:
            raise Degenerate(f"{c.name}: every position at the origin")
        c.drawn = tuple(getattr(src, "drawn", ()))
        return c

    return case


CHAINS = {
    "RRR_links": rrr_case,
    "PRR_links": prr_case,
    "RPR_links": rpr_case,
    "PRP_links": prp_case,
    "PPR_links": ppr_case,
    "coupler_point": coupler_point_case,
    "link_point": link_point_case,
    "pair_point": pair_point_case,
    "link_angle": link_angle_case,
    "link_direction": link_direction_case,
    "angle_direction": angle_direction_case,
    "crank_input": crank_input_case,
    "slider_input": slider_input_case,
    "offset_angle": offset_angle_case,
    "crank_angle": crank_angle_case,
    "link_residual": link_residual_case,
    "loop_point": loop_point_case,
    "loop_residual": loop_residual_case,
    "loop_turn": loop_turn_case,
}
CHAINS = {name: _checked(make) for name, make in CHAINS.items()}


def replay(name: str, numbers) -> Case:
    """The case of chain ``name`` made from the numbers a property test drew (its note prints them)."""
    return CHAINS[name](ReplaySource(numbers))


# --------------------------------------------------------------------------- chain residuals


def _p(values, name):
    v = values[name]
    return (v[0].v, v[1].v)


def _val(values, name):
    v = values[name]
    return v.v if isinstance(v, Jet) else v


def _dir_mp(a):
    return (MP.cos(a), MP.sin(a))


def residuals(case: Case, outs: dict) -> list:
    """Residuals of the chain's constraints at the float outputs, at 50 digits, as lengths.

    ``outs`` maps output names to the float records the primitive returned.  Written from
    the geometry in each primitive's docstring (the same constraints test_primitives uses).
    """
    v = case.values

    def pt(name):
        rec = outs[name]
        return (MP.mpf(rec[0]), MP.mpf(rec[1]))

    def sc(name):
        return MP.mpf(outs[name][0])

    n = case.name
    if n == "RRR_links":
        jb = pt("jb")
        return [vnorm(vsub(jb, _p(v, "j1"))) - _val(v, "l1"), vnorm(vsub(jb, _p(v, "j2"))) - _val(v, "l2")]
    if n == "PRR_links":
        u = _dir_mp(_val(v, "psig"))
        jp, jb = pt("jp"), pt("jb")
        rel = vsub(jp, _p(v, "pg"))
        res = [vnorm(vsub(jb, _p(v, "jr"))) - _val(v, "l"), vcross(rel, u), vdot(rel, u) - sc("s")]
        return res + list(vsub(vsub(jb, jp), local(u, v["gsi"], v["eta"])))
    if n == "RPR_links":
        u = _dir_mp(sc("psi"))
        jp = pt("jp")
        res = list(vsub(vsub(jp, _p(v, "js")), local(u, v["as_"], v["bs"])))
        rel = vsub(jp, _p(v, "jg"))
        return res + [vcross(u, rel) - v["bg"], vdot(rel, u) - (v["ag"] + sc("s"))]
    if n == "PRP_links":
        jb, res = pt("jb"), []
        for i in (1, 2):
            u, jp = _dir_mp(_val(v, f"psig{i}")), pt(f"jp{i}")
            rel = vsub(jp, _p(v, f"pg{i}"))
            res += [vcross(rel, u), vdot(rel, u) - sc(f"s{i}")]
            res += list(vsub(vsub(jb, jp), local(u, v[f"gsi{i}"], v[f"eta{i}"])))
        return res
    if n == "PPR_links":
        u1, ux = _dir_mp(_val(v, "psig")), _dir_mp(_val(v, "psig") + v["cx"])
        jp1 = pt("jp1")
        rel = vsub(jp1, _p(v, "pg"))
        pa = vadd(_p(v, "jr"), local(u1, v["xa"], v["ya"]))
        pb = vadd(jp1, local(u1, v["xb"], v["yb"]))
        res = [vcross(rel, u1), vdot(rel, u1) - sc("s1"), vcross(vsub(pa, pb), ux),
               sc("sx") - v["sgn"] * vdot(vsub(pa, pb), ux)]
        return res + list(vsub(pt("jpx"), pa if v["sgn"] > 0 else pb))
    if n == "coupler_point":
        d = vsub(pt("jc"), _p(v, "j0"))
        u = _dir_mp(_val(v, "phi"))
        return [vdot(d, u) - v["gsi"], vcross(u, d) - v["eta"]]
    if n == "link_point":  # jc - j1 = gsi e + eta n, e the unit vector of j2 - j1
        d = vsub(_p(v, "j2"), _p(v, "j1"))
        r = vsub(pt("jc"), _p(v, "j1"))
        q = MP.sqrt(vdot(d, d))
        return [vdot(r, d) / q - v["gsi"], vcross(d, r) / q - v["eta"]]
    if n == "pair_point":  # jc - j1 = along d + across n(d), d = j2 - j1: its components along e = d / |d| and n(e)
        d = vsub(_p(v, "j2"), _p(v, "j1"))
        r = vsub(pt("jc"), _p(v, "j1"))
        q = MP.sqrt(vdot(d, d))
        return [vdot(r, d) / q - v["along"] * q, vcross(d, r) / q - v["across"] * q]
    if n == "crank_input":
        d = vsub(pt("j2"), _p(v, "j1"))
        u = _dir_mp(_val(v, "theta") + _val(v, "phi"))
        return [vcross(d, u), vdot(d, u) - v["l"]]
    if n == "slider_input":
        u = _dir_mp(_val(v, "psig"))
        jp, jc = pt("jp"), pt("jc")
        rel = vsub(jp, _p(v, "pg"))
        return [vcross(rel, u), vdot(rel, u) - _val(v, "s"), vdot(vsub(jc, jp), u) - v["gsi"],
                vcross(u, vsub(jc, jp)) - v["eta"]]
    if n == "link_angle":
        d = vsub(_p(v, "j2"), _p(v, "j1"))
        th = sc("angle")
        return [wrap(th - MP.atan2(d[1], d[0]) - v["off"]) * vnorm(d)]
    if n == "link_direction":  # u turned back by the offset is along j2 - j1, of unit length
        d = vsub(_p(v, "j2"), _p(v, "j1"))
        u = pt("u")
        e = (v["c"] * u[0] + v["s"] * u[1], -v["s"] * u[0] + v["c"] * u[1])
        return [vcross(e, d) / vnorm(d), vdot(e, d) / vnorm(d) - 1]
    if n == "angle_direction":
        u, phi = pt("u"), _val(v, "phi")
        return [u[0] - MP.cos(phi), u[1] - MP.sin(phi)]
    if n == "offset_angle":
        return [wrap(sc("angle") - _val(v, "phi") - v["off"])]
    if n == "crank_angle":
        return [wrap(sc("angle") - _val(v, "theta") - _val(v, "phi") - v["off"])]
    if n == "link_residual":
        return [sc("f") - (vnorm(vsub(_p(v, "j2"), _p(v, "j1"))) - _val(v, "l"))]
    if n == "loop_point":  # j2 at the distance l from j1, at the angle s / l
        d, u = vsub(pt("j2"), _p(v, "j1")), _dir_mp(_val(v, "s") / _val(v, "l"))
        return [vcross(d, u), vdot(d, u) - _val(v, "l")]
    if n == "loop_residual":  # f = l wrap(angle of j2 - j1 less s / l)
        d, ln = vsub(_p(v, "j2"), _p(v, "j1")), _val(v, "l")
        return [sc("f") - ln * wrap(MP.atan2(d[1], d[0]) - _val(v, "s") / ln)]
    if n == "loop_turn":  # c = (j2 - j1) x (j3 - j1), over the longer side
        c = vcross(vsub(_p(v, "j2"), _p(v, "j1")), vsub(_p(v, "j3"), _p(v, "j1")))
        return [(sc("c") - c) / case.per]
    raise KeyError(n)


# --------------------------------------------------------------------------- mechanisms


@dataclass(frozen=True)
class Pair:
    name: str
    x: float
    y: float
    axis: float | None = None  # radians; prismatic pairs only


@dataclass(frozen=True)
class Body:
    name: str
    joints: tuple[str, ...]
    fixed: bool = False
    points: tuple[tuple[str, float, float], ...] = ()


@dataclass(frozen=True)
class Sketch:
    """A mechanism as drawn: pairs at their positions, links, one crank driven relative to the frame."""

    kind: str
    pairs: tuple[Pair, ...]
    bodies: tuple[Body, ...]
    crank: tuple[str, str]  # (pair, link) of the revolute input
    short: str = ""  # which segment was drawn short (for reports)
    ratio: float = 1.0

    @property
    def frame(self) -> Body:
        return next(b for b in self.bodies if b.fixed)

    def position(self, name: str) -> tuple[float, float]:
        for p in self.pairs:
            if p.name == name:
                return p.x, p.y
        for b in self.bodies:
            for n, x, y in b.points:
                if n == name:
                    return x, y
        raise KeyError(name)

    def theta0(self) -> float:
        """The input's value in the sketch: the crank's direction from its input pair (the frame's is 0)."""
        joint, link = self.crank
        body = next(b for b in self.bodies if b.name == link)
        k = body.joints.index(joint)
        order = list(body.joints[k + 1:]) + list(body.joints[:k]) + [n for n, _, _ in body.points]
        x0, y0 = self.position(joint)
        for n in order:
            x, y = self.position(n)
            if (x, y) != (x0, y0):
                return math.atan2(y - y0, x - x0)
        raise ValueError("crank pairs coincide")

    def spots(self) -> list[tuple[float, float]]:
        return [(p.x, p.y) for p in self.pairs] + [(x, y) for b in self.bodies for _, x, y in b.points]

    def yaml(self, name: str, span: tuple[float, float] = (-0.5, 0.5), samples: int = 5,
             speed: float = 1.0) -> str:
        """The mechanism file (angles in radians); the input runs over theta0 + span."""
        t0 = self.theta0()
        lines = ["linkgen: 1", f"name: {name}", "units: {length: mm, angle: rad}", "joints:"]
        for p in self.pairs:
            if p.axis is None:
                lines.append(f"  {p.name}: [{p.x!r}, {p.y!r}]")
            else:
                lines.append(f"  {p.name}: {{type: prismatic, at: [{p.x!r}, {p.y!r}], axis: {p.axis!r}}}")
        lines.append("links:")
        for b in self.bodies:
            parts = [f"joints: [{', '.join(b.joints)}]"]
            if b.fixed:
                parts.append("fixed: true")
            if b.points:
                pts = ", ".join(f"{n}: [{x!r}, {y!r}]" for n, x, y in b.points)
                parts.append(f"points: {{{pts}}}")
            lines.append(f"  {b.name}: {{{', '.join(parts)}}}")
        lo, hi = t0 + span[0], t0 + span[1]
        lines.append("inputs:")
        lines.append(f"  - {{joint: {self.crank[0]}, link: {self.crank[1]}, relative_to: {self.frame.name}, "
                     f"range: [{lo!r}, {hi!r}], speed: {speed!r}}}")
        lines.append(f"samples: {samples}")
        return "\n".join(lines) + "\n"

    def mapped(self, f, turn: float = 0.0) -> Sketch:
        """Every position through f, every prismatic axis turned by ``turn``."""
        pairs = tuple(replace(p, x=f(p.x, p.y)[0], y=f(p.x, p.y)[1],
                              axis=None if p.axis is None else p.axis + turn) for p in self.pairs)
        bodies = tuple(replace(b, points=tuple((n, *f(x, y)) for n, x, y in b.points)) for b in self.bodies)
        return replace(self, pairs=pairs, bodies=bodies)

    def scaled(self, k: float) -> Sketch:
        return self.mapped(lambda x, y: (x * k, y * k))

    def moved(self, angle: float, dx: float, dy: float) -> Sketch:
        c, s = math.cos(angle), math.sin(angle)
        return self.mapped(lambda x, y: (c * x - s * y + dx, s * x + c * y + dy), angle)

    def size(self) -> float:
        """The largest distance between two spots (linkgen's and the reference's length scale)."""
        pts = self.spots()
        return max(math.hypot(a[0] - b[0], a[1] - b[1]) for a in pts for b in pts)

    def extent(self) -> float:
        """The largest coordinate magnitude (the ulp positions are written to)."""
        return max(max(abs(x), abs(y)) for x, y in self.spots())

    def distinct(self, tol: float = 0.0) -> bool:
        """No two revolute pairs (or points) of one link closer than tol times the size, and every link with
        two spots apart (prismatic pairs may sit on revolute ones)."""
        s = self.size()
        if not s > 0:
            return False
        kinds = {p.name: p.axis is None for p in self.pairs}
        for b in self.bodies:
            every = [self.position(n) for n in b.joints] + [(x, y) for _, x, y in b.points]
            if all(p == every[0] for p in every):
                return False
            names = [n for n in b.joints if kinds[n]] + [n for n, _, _ in b.points]
            spots = [self.position(n) for n in names]
            for i, a in enumerate(spots):
                for c in spots[i + 1:]:
                    if math.hypot(a[0] - c[0], a[1] - c[1]) <= tol * s:
                        return False
        return True


def _short(src: Source, options: tuple[str, ...]) -> tuple[str, float]:
    """Which segment (if any) is drawn short, and how short relative to the scale."""
    if src.integer(0, 2) > 0:
        return "", 1.0
    return src.choice(options), src.ratio()


def fourbar(src: Source) -> Sketch:
    s = src.scale()
    short, r = _short(src, ("crank", "frame", "point"))
    o1 = src.point(s)
    a = src.near(o1, s * r) if short == "crank" else src.point(s)
    o2 = src.near(o1, s * r) if short == "frame" else src.point(s)
    b = src.point(s)
    p = src.near(src.choice((a, b)), s * r) if short == "point" else src.point(s)
    return Sketch("fourbar", (Pair("O1", *o1), Pair("A", *a), Pair("B", *b), Pair("O2", *o2)),
                  (Body("frame", ("O1", "O2"), True), Body("crank", ("O1", "A")),
                   Body("coupler", ("A", "B"), points=(("P", *p),)), Body("rocker", ("O2", "B"))),
                  ("O1", "crank"), short, r)


def slider_crank(src: Source) -> Sketch:
    s = src.scale()
    short, r = _short(src, ("crank", "offset"))
    o = src.point(s)
    a = src.near(o, s * r) if short == "crank" else src.point(s)
    b = src.point(s)
    axis = src.angle()
    at = src.choice((b, src.near(b, s * r) if short == "offset" else src.point(s)))
    guide_first = src.flag()
    block = Body("block", ("B", "S"))
    frame = Body("frame", ("O", "S") if guide_first else ("S", "O"), True)
    return Sketch("slider_crank", (Pair("O", *o), Pair("A", *a), Pair("B", *b), Pair("S", *at, axis)),
                  (frame, Body("crank", ("O", "A")), Body("rod", ("A", "B")), block), ("O", "crank"), short, r)


def inverted_slider(src: Source) -> Sketch:
    s = src.scale()
    short, r = _short(src, ("crank", "frame", "offset"))
    o1 = src.point(s)
    a = src.near(o1, s * r) if short == "crank" else src.point(s)
    o2 = src.near(o1, s * r) if short == "frame" else src.point(s)
    at = src.choice((a, src.near(a, s * r) if short == "offset" else src.point(s)))
    axis = src.choice((math.atan2(at[1] - o2[1], at[0] - o2[0]), src.angle()))  # the slot through O2, or not
    lever = Body("lever", ("O2", "S"), points=(("P", *src.point(s)),))
    block = Body("block", ("A", "S"))
    bodies = (Body("frame", ("O1", "O2"), True), Body("crank", ("O1", "A")))
    bodies += (lever, block) if src.flag() else (block, lever)  # which of them is the guide
    return Sketch("inverted_slider", (Pair("O1", *o1), Pair("A", *a), Pair("O2", *o2), Pair("S", *at, axis)),
                  bodies, ("O1", "crank"), short, r)


def watt(src: Source) -> Sketch:
    """Watt II: a four-bar whose rocker (a ternary link) drives a second four-bar."""
    s = src.scale()
    short, r = _short(src, ("crank", "frame", "rocker"))
    o1, o3 = src.point(s), src.point(s)
    a = src.near(o1, s * r) if short == "crank" else src.point(s)
    o2 = src.near(o1, s * r) if short == "frame" else src.point(s)
    b = src.point(s)
    c = src.near(b, s * r) if short == "rocker" else src.point(s)
    d = src.point(s)
    pairs = tuple(Pair(n, *p) for n, p in (("O1", o1), ("A", a), ("B", b), ("O2", o2), ("C", c), ("D", d),
                                           ("O3", o3)))
    bodies = (Body("frame", ("O1", "O2", "O3"), True), Body("crank", ("O1", "A")), Body("coupler", ("A", "B")),
              Body("rocker", ("O2", "B", "C")), Body("coupler2", ("C", "D"), points=(("P", *src.point(s)),)),
              Body("rocker2", ("O3", "D")))
    return Sketch("watt", pairs, bodies, ("O1", "crank"), short, r)


def stephenson(src: Source) -> Sketch:
    """Stephenson III: the coupler of a four-bar (a ternary link) drives a dyad to the frame."""
    s = src.scale()
    short, r = _short(src, ("crank", "frame", "coupler"))
    o1, o3 = src.point(s), src.point(s)
    a = src.near(o1, s * r) if short == "crank" else src.point(s)
    o2 = src.near(o1, s * r) if short == "frame" else src.point(s)
    b = src.point(s)
    c = src.near(src.choice((a, b)), s * r) if short == "coupler" else src.point(s)
    d = src.point(s)
    pairs = tuple(Pair(n, *p) for n, p in (("O1", o1), ("A", a), ("B", b), ("O2", o2), ("C", c), ("D", d),
                                           ("O3", o3)))
    bodies = (Body("frame", ("O1", "O2", "O3"), True), Body("crank", ("O1", "A")), Body("coupler", ("A", "B", "C")),
              Body("rocker", ("O2", "B")), Body("link", ("C", "D")), Body("rocker2", ("O3", "D")))
    return Sketch("stephenson", pairs, bodies, ("O1", "crank"), short, r)


FIG14 = {"J1": (0, 0), "J2": (0, 70), "J3": (100, 0), "J4": (105, 65), "J5": (60, 80), "J6": (-60, 100),
         "J7": (-60, 80)}
FIG14_LINKS = (("rocker1", ("J1", "J2")), ("ternary", ("J2", "J4", "J5")), ("rocker2", ("J3", "J4")),
               ("coupler", ("J6", "J5")), ("crank", ("J7", "J6")))


def _triad_sketch(kind: str, pos: dict, short: str, r: float, point=None) -> Sketch:
    pairs = tuple(Pair(n, *pos[n]) for n in ("J1", "J2", "J3", "J4", "J5", "J6", "J7"))
    bodies = [Body(n, js, points=(("P", *point),) if point is not None and n == "ternary" else ())
              for n, js in FIG14_LINKS]
    bodies.append(Body("frame", ("J1", "J3", "J7"), True))
    return Sketch(kind, pairs, tuple(bodies), ("J7", "crank"), short, r)


def fig14(src: Source) -> Sketch:
    """The paper's Fig. 14 six-bar (a class-III group driven by a crank), every pair moved at random."""
    s = src.scale() / 100
    jiggle = 30 * src.real(0, 1)
    pos = {n: ((x + jiggle * src.real(-1, 1)) * s, (y + jiggle * src.real(-1, 1)) * s) for n, (x, y) in FIG14.items()}
    short, r = _short(src, ("crank",))
    if short:
        pos["J6"] = src.near(pos["J7"], 100 * s * r)
    return _triad_sketch("fig14", pos, short, r)


def triad(src: Source) -> Sketch:
    """A crank-driven triad with every pair anywhere (Fig. 14's topology, any geometry)."""
    s = src.scale()
    short, r = _short(src, ("crank", "ternary", "frame"))
    pos = {n: src.point(s) for n in FIG14}
    if short == "crank":
        pos["J6"] = src.near(pos["J7"], s * r)
    elif short == "ternary":
        pos["J5"] = src.near(pos[src.choice(("J2", "J4"))], s * r)
    elif short == "frame":
        pos["J3"] = src.near(pos["J1"], s * r)
    return _triad_sketch("triad", pos, short, r, src.point(s) if src.flag() else None)


MECHANISMS = {
    "fourbar": fourbar,
    "slider_crank": slider_crank,
    "inverted_slider": inverted_slider,
    "watt": watt,
    "stephenson": stephenson,
    "fig14": fig14,
    "triad": triad,
}


# --------------------------------------------------------------------------- the reference


def conditioning(ref: Reference, jac) -> float:
    """The reference's scale-free conditioning of a Jacobian (Reference.cond)."""
    return ref.cond(jac)


def sketch_condition(ref: Reference) -> float:
    """The conditioning of the sketch configuration (inputs included)."""
    return conditioning(ref, ref.jacobian(ref.sketch_pose(), ref.sketch_inputs()))


def newton_float(ref: Reference, q: list, u: list, max_iter: int = 12) -> tuple[list, list]:
    """Newton in float on the reference's constraints, converged on a scale-free step size and
    then required to close them (past a limit position least squares converges too, to the
    nearest pose that does not close: triad_1454).

    (Reference.newton's float mode stops on an absolute residual that angle rows cannot reach
    at small length scales.)"""
    scale = [ref.length_scale, ref.length_scale, 1.0] * len(ref.moving)
    q = [float(x) for x in q]
    for _ in range(max_iter):
        jac = ref.jacobian(q, u)
        res = [float(r) for r in ref.constraints(q, u)]
        dq = np.linalg.lstsq(np.array(jac, dtype=float), np.array(res), rcond=None)[0]
        if not np.all(np.isfinite(dq)):
            break
        q = [a - b for a, b in zip(q, dq)]
        if max(abs(d) / s for d, s in zip(dq, scale)) < 1e-13:
            res = [float(r) for r in ref.constraints(q, u)]
            if max(abs(r) / s for r, s in zip(res, ref.constraint_scales())) > CLOSED:
                break
            return q, ref.jacobian(q, u)
    raise ArithmeticError("float Newton did not converge")


CLOSED = 1e-9  # the largest constraint residual (over L, or in radians) of a pose that closes


STEP = math.radians(1)  # the reference's continuation step in the input angle
MIN_COND = 1e-7  # a continuation step closer than this to a singular position is cut
FINE_STEP = 1e-4  # the shortest continuation step (radians): the conditioning bounds the step down to this


def walk(ref: Reference, q: list, start: float, stop: float, step: float = STEP) -> list | None:
    """Follow the assembly at q (inputs ``start``) to ``stop`` in float steps; None where it is cut.

    A step is at most ``step`` and at most the conditioning at its start (down to FINE_STEP):
    where two branches pass within c L of each other (conditioning c), a longer step can land
    on the other one.  Cut where Newton fails, the pose jumps, or the path comes near a
    singular position.
    """
    scale = [ref.length_scale, ref.length_scale, 1.0] * len(ref.moving)
    sign = math.copysign(1.0, stop - start)
    t, h = start, min(step, max(conditioning(ref, ref.jacobian(q, [start])), FINE_STEP))
    while t != stop:
        u = stop if abs(stop - t) <= h else t + sign * h
        try:
            try:
                new, jac = newton_float(ref, q, ref.turned_inputs(q, [u]))
            except ArithmeticError:  # float Newton stalls where the conditioning is 1e-4: 50 digits
                new, jac, _ = ref.newton(q, ref.turned_inputs(q, [u]), exact=True, max_iter=30)
                new = [float(x) for x in new]
        except (ArithmeticError, np.linalg.LinAlgError, ZeroDivisionError, OverflowError, ValueError):
            return None
        c = conditioning(ref, jac)
        if c < MIN_COND or max(abs(a - b) / s for a, b, s in zip(new, q, scale)) > 0.3:
            return None
        q, t, h = new, u, min(step, max(c, FINE_STEP))
    return q


@dataclass
class Reached:
    """The reference at one input value: the sketch's assembly reached by continuation, at 50 digits."""

    value: float
    columns: dict
    cond: float
    q: list = field(default_factory=list)


def reach(ref: Reference, values: list[float], rates: list[float]) -> list[Reached | None]:
    """The sketch's assembly at each input value (one revolute input), or None where it is not reached."""
    t0 = ref.sketch_inputs()[0]
    out = []
    for v, w in zip(values, rates):
        q = walk(ref, ref.sketch_pose(), t0, v)
        if q is None:
            out.append(None)
            continue
        try:
            sol = ref.solve([v], [w], q)
        except (ArithmeticError, ZeroDivisionError):
            out.append(None)
            continue
        out.append(Reached(v, sol.columns, conditioning(ref, ref.jacobian([float(x) for x in sol.q], [v])), sol.q))
    return out


def follow(ref: Reference, values: list[float], rates: list[float]) -> list[Reached | None]:
    """The sketch's assembly row after row, as the generated programs follow it (one revolute input):
    each row from the last one reached (the first from the sketch), the shorter way round, else the
    other way round past a limit position; a row reached neither way is None, and the next row starts
    from the sketch again.  Rows reached the other way round are counted in WORST."""
    t0 = ref.sketch_inputs()[0]
    q, t = ref.sketch_pose(), t0
    out = []
    for v, w in zip(values, rates):
        goal = v - 2 * math.pi * math.floor((v - t) / (2 * math.pi) + 0.5)
        new = walk(ref, q, t, goal)
        if new is None and goal != t:
            new = walk(ref, q, t, goal - math.copysign(2 * math.pi, goal - t))
            if new is not None:
                record("2 went round", "rows", "rows reached the other way round", 1.0)
        sol = None
        if new is not None:
            try:
                sol = ref.solve([v], [w], new)
            except (ArithmeticError, ZeroDivisionError):
                sol = None
        if sol is None:
            out.append(None)
            q, t = ref.sketch_pose(), t0
            continue
        q, t = [float(x) for x in sol.q], v
        out.append(Reached(v, sol.columns, conditioning(ref, ref.jacobian(q, [v])), sol.q))
    return out


# --------------------------------------------------------------------------- comparing rows

CLASS = {"x": "position", "y": "position", "s": "position", "vx": "velocity", "vy": "velocity", "ds": "velocity",
         "ax": "acceleration", "ay": "acceleration", "dds": "acceleration", "phi": "angle",
         "omega": "angular_velocity", "alpha": "angular_acceleration"}


def quantity(name: str) -> str:
    """The spec's quantity class of a CSV column (outputs only)."""
    return CLASS[name.rsplit(".", 1)[1]]


def link_sizes(sketch: Sketch) -> dict[str, float]:
    """Per link, the largest distance between its spots in the sketch (its arm for angle errors)."""
    out = {}
    for b in sketch.bodies:
        spots = [sketch.position(n) for n in b.joints] + [(x, y) for _, x, y in b.points]
        out[b.name] = max(math.hypot(a[0] - c[0], a[1] - c[1]) for a in spots for c in spots)
    return out


def class_scales(want: dict, length: float) -> dict[str, float]:
    """The near-zero scale S of each quantity class, from the reference row (the spec's rule, with the
    floors of tests/test_accuracy.py: S_omega >= S_v / L, S_a >= S_v^2 / L, S_alpha >= S_a / L, S_omega^2)."""
    s = dict.fromkeys(("velocity", "acceleration", "angular_velocity", "angular_acceleration"), 0.0)
    for name, v in want.items():
        q = quantity(name)
        if q in s:
            s[q] = max(s[q], abs(float(v)))
    s["angular_velocity"] = max(s["angular_velocity"], s["velocity"] / length)
    s["acceleration"] = max(s["acceleration"], s["velocity"] * s["velocity"] / length)
    s["angular_acceleration"] = max(s["angular_acceleration"], s["acceleration"] / length,
                                    s["angular_velocity"] * s["angular_velocity"])
    return s


def row_errors(row: dict, want: dict, length: float, arms: dict[str, float]) -> dict[str, tuple[float, str]]:
    """Worst error per quantity class of a linkgen row against a reference row, normalised:

    positions in eps L, angles in eps L / (the link's size), rates relative to max(|a|, |b|, S)."""
    scales = class_scales(want, length)
    worst: dict[str, tuple[float, str]] = {}
    for name, b in want.items():
        a, q = row[name], quantity(name)
        if q == "position":
            err = abs(MP.mpf(a) - b) / (EPS * length)
        elif q == "angle":
            err = abs(wrap(MP.mpf(a) - b)) * arms[name.rsplit(".", 1)[0]] / (EPS * length)
        else:
            err = abs(MP.mpf(a) - b) / max(abs(a), abs(float(b)), scales[q], 1e-300)
        err = float(err) if math.isfinite(a) else math.inf
        if err > worst.get(q, (-1.0, ""))[0]:
            worst[q] = (err, name)
    return worst
