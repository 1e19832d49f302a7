"""Accuracy of the two-link chains against 50-digit mpmath, and against the lecture's formulas.

    python bench/run.py accuracy       # (make bench runs it with the other groups)

3R chain (``RRR_links``): random assembled configurations whose pairs are exact doubles
(integer Pythagorean vectors on a lattice of 2^-50, so both link lengths are exact too),
placed at controlled distances from a toggle: sigma = h q/(l1 l2), the sine of the angle at
the middle pair, from 1e-12 to 1, exact toggles (sigma = 0) and needles (one link 1e-8 or
1e-12 of the other).  Slider chain (``PRR_links``): the slider up to 1e8 link lengths from
the guide's reference point.  linkgen runs as its Python backend and as the C printed by
``c_function`` (gcc -O2); the lecture's forms are re-derived here in Python and C.

Prints the tables of docs/accuracy.md and writes docs/accuracy-rrr.svg and
docs/accuracy-rrr-rates.svg (deterministic: fixed seed, no timings in the plots).
"""

from __future__ import annotations

import math
import shutil
import statistics
import subprocess
import sys
from dataclasses import replace
from fractions import Fraction
from pathlib import Path

import mpmath
import numpy as np

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from linkgen.backends.c.printer import c_function  # noqa: E402
from linkgen.backends.m.printer import octave_function  # noqa: E402
from linkgen.evaluate import evaluate  # noqa: E402
from linkgen.pipeline import build_log  # noqa: E402
from linkgen.primitives import PRIMITIVES, numpy_backend, python_backend  # noqa: E402
from linkgen.rows import input_rows  # noqa: E402

MP = mpmath.MPContext()
MP.dps = 50
EPS = 2.0**-52
SEED = 20240613
GRID = 50  # lattice 2^-GRID: lengths are integers up to 2^GRID, coordinates below 2^52
OUT = ROOT / "bench" / "out" / "accuracy"
DOCS = ROOT / "docs"
NAN = math.nan


# ----------------------------------------------------------------------------- helpers

def _div(a: float, b: float) -> float:
    """a / b with IEEE semantics (Python raises on a zero divisor; C does not)."""
    if b != 0 or a != a:
        return a / b if b != 0 else NAN
    return NAN if a == 0 else math.copysign(math.inf, a) * math.copysign(1.0, b)


def _hexes(values) -> str:
    return " ".join(float(v).hex() for v in values)


def _unhex(word: str) -> float:
    try:
        return float.fromhex(word)
    except ValueError:
        return float(word)  # nan, -nan, inf as C prints them


def _same(a, b) -> bool:
    """Bit-for-bit equality of two float sequences (nan equals nan)."""
    return all((x != x and y != y) or (x == y and math.copysign(1, x) == math.copysign(1, y)) for x, y in zip(a, b))


def _ulps(err, length: float) -> float:
    """An mpmath error in ulps of the length scale (nan stays nan)."""
    return NAN if err is None else float(err) / math.ulp(length)


def _norm(v) -> object:
    return MP.sqrt(sum(MP.mpf(x) ** 2 for x in v))


def _dist(got, want) -> object:
    """|got - want| in mpmath, None when got is not finite."""
    if not all(math.isfinite(g) for g in got):
        return None
    return MP.sqrt(sum((MP.mpf(g) - w) ** 2 for g, w in zip(got, want)))


def _rel(got, want, scale) -> float:
    d = _dist(got, want)
    return NAN if d is None else float(d / scale)


# ------------------------------------------------------------------- 3R configurations

def _turn(a: int, b: int, k: int) -> tuple[int, int]:
    for _ in range(k % 4):
        a, b = -b, a
    return a, b


def _direction(theta, length: int, rng=None) -> tuple[int, int, int]:
    """An integer vector (a, b) with integer length c <= length at about the angle theta.

    Pythagorean: (m^2 - n^2, 2mn) with n/m ~ tan(theta/2) after quarter turns.  Without rng
    n/m is the best approximation (error ~1/length rad); with rng a random fraction with a
    denominator near its limit, so later best approximations can come very close to it.
    """
    k = int(MP.nint(theta / (MP.pi / 2)))
    t = MP.tan((theta - k * MP.pi / 2) / 2)
    big = max(1, math.isqrt(int(length * 0.85)))
    if rng is None:
        sign, man, exp, _ = t._mpf_
        f = (Fraction((-1) ** sign * int(man)) * Fraction(2) ** int(exp)).limit_denominator(big)
        n, m = f.numerator, f.denominator
    else:
        m = int(rng.integers(big // 2 + 1, big + 1))
        n = round(float(t) * m)
    a, b, c = m * m - n * n, 2 * m * n, m * m + n * n
    g = math.gcd(math.gcd(a, b), c)
    a, b, c = _turn(a // g, b // g, k) + (c // g,)
    s = length // c
    return a * s, b * s, c * s


def rrr_case(rng, sigma: float, ratio: float, tag: str) -> dict:
    """An assembled 3R chain on the lattice: middle pair B, links B->P1, B->P2 of exact lengths.

    sigma is the target sine of the angle at B (0: exact toggle), ratio the short link over
    the long one; folded or extended toggle, which link is short, orientation and position
    are random.  Rates are random, lengths constant (the lecture's RRR_links has no length rates).
    """
    long_len, short_len = 2**GRID, max(1, round(2**GRID * ratio))
    theta = MP.mpf(rng.uniform(-math.pi, math.pi))
    folded = bool(rng.integers(2))
    if sigma == 0:  # both links along one primitive direction
        a, b, c = _direction(theta, 2**20, rng)
        k, m = short_len // c, long_len // c * (1 if folded else -1)
        vs, vl = (a * k, b * k, c * k), (a * m, b * m, c * abs(m))
    else:
        vs = _direction(theta, short_len, rng)
        gamma = MP.asin(sigma) if folded else MP.pi - MP.asin(sigma)
        vl = _direction(MP.atan2(vs[1], vs[0]) + gamma * int(rng.choice([-1, 1])), long_len)
    v1, v2 = (vs, vl) if rng.integers(2) else (vl, vs)
    bx, by = (int(x) for x in rng.integers(-(2**GRID), 2**GRID, size=2))
    p1, p2 = (bx + v1[0], by + v1[1]), (bx + v2[0], by + v2[1])
    cross = (p2[0] - p1[0]) * (by - p1[1]) - (p2[1] - p1[1]) * (bx - p1[0])
    f = [math.ldexp(v, -GRID) for v in (*p1, *p2, v1[2], v2[2], bx, by)]
    lscale = max(f[4], f[5], math.hypot(f[2] - f[0], f[3] - f[1]), *(abs(x) for x in f[0:4] + f[6:8]))
    rates = [float(x) * lscale for x in rng.normal(size=8)]
    j1 = (f[0], f[1], rates[0], rates[1], rates[2], rates[3])
    j2 = (f[2], f[3], rates[4], rates[5], rates[6], rates[7])
    case = {"tag": tag, "j1": j1, "j2": j2, "l1": f[4], "l2": f[5], "minv": 1 if cross >= 0 else -1,
            "sigma": abs(v1[0] * v2[1] - v1[1] * v2[0]) / (v1[2] * v2[2]), "L": lscale, "B": (f[6], f[7])}
    case["ref"] = rrr_exact(j1, j2, f[4], f[5], case["minv"], sigma > 0)
    # the same chain with P1 and P2 moved to neighbouring doubles: what one rounding upstream does
    moved = [[math.nextafter(x, math.copysign(math.inf, float(rng.normal()))) for x in j[:2]] + list(j[2:])
             for j in (j1, j2)]
    case["moved"] = rrr_exact(*moved, f[4], f[5], case["minv"], sigma > 1e-7)
    case["moved in"] = moved
    return case


def rrr_exact(j1, j2, l1: float, l2: float, minv: int, rates: bool):
    """50-digit position, velocity and acceleration of B on the binary inputs (velocity and
    acceleration None without rates); None when the chain cannot close."""
    p1, p2 = [MP.mpf(x) for x in j1], [MP.mpf(x) for x in j2]
    l1, l2 = MP.mpf(l1), MP.mpf(l2)
    dx, dy = p2[0] - p1[0], p2[1] - p1[1]
    q2 = dx * dx + dy * dy
    q = MP.sqrt(q2)
    area2 = 4 * l1**2 * q2 - (l1**2 + q2 - l2**2) ** 2  # (4 x area)^2, zero at a toggle
    if area2 < -1e-40 * max(l1, l2) ** 4:
        return None
    area4 = MP.sqrt(max(area2, 0))
    a, h = (l1**2 - l2**2 + q2) / (2 * q), minv * area4 / (2 * q)
    b = (p1[0] + (a * dx - h * dy) / q, p1[1] + (a * dy + h * dx) / q)
    e1, e2 = (b[0] - p1[0], b[1] - p1[1]), (b[0] - p2[0], b[1] - p2[1])
    det = e1[0] * e2[1] - e1[1] * e2[0]
    if not rates:
        return b, None, None

    def solve(r1, r2):
        return (r1 * e2[1] - r2 * e1[1]) / det, (e1[0] * r2 - e2[0] * r1) / det

    # (B - Pi).(B' - Pi') = li li' = 0 and (B - Pi).(B'' - Pi'') + |B' - Pi'|^2 = 0
    v = solve(e1[0] * p1[2] + e1[1] * p1[3], e2[0] * p2[2] + e2[1] * p2[3])
    w1, w2 = (v[0] - p1[2], v[1] - p1[3]), (v[0] - p2[2], v[1] - p2[3])
    acc = solve(e1[0] * p1[4] + e1[1] * p1[5] - w1[0] ** 2 - w1[1] ** 2,
                e2[0] * p2[4] + e2[1] * p2[5] - w2[0] ** 2 - w2[1] ** 2)
    return b, v, acc


def acos_rrr(j1, j2, l1: float, l2: float, minv: int):
    """The lecture's RRR_links: beta = acos(cos rule), then phi = alpha +- beta; None where it fails."""
    dx, dy = j2[0] - j1[0], j2[1] - j1[1]
    dvx, dvy = j2[2] - j1[2], j2[3] - j1[3]
    dax, day = j2[4] - j1[4], j2[5] - j1[5]
    q2 = dx * dx + dy * dy
    if q2 <= 10e-30:
        return None
    q = math.sqrt(q2)
    dq = (dvx * dx + dvy * dy) / q
    ddq = ((dax * dx + dvx * dvx + day * dy + dvy * dvy) * q - (dvx * dx + dvy * dy) * dq) / q2
    cb = (l1 * l1 + q2 - l2 * l2) / (2.0 * l1 * q)
    if abs(cb) > 1.0:
        return None
    sb = math.sqrt(1.0 - cb * cb)
    ss = l1 * l1 - l2 * l2 - q2
    the = math.atan2(dy, dx)
    dthe = (dx * dvy - dy * dvx) / q2
    ddthe = (dx * day - dy * dax) / q2 - 2.0 * dthe * (dx * dvx + dy * dvy) / q2
    bet = math.acos(cb)
    dbet = _div(ss * dq, 2.0 * l1 * q2 * sb)
    ddbet = _div((ss * (ddq * q - 2.0 * dq * dq) - 2.0 * (dq * q) * (dq * q)) * sb - ss * dq * q * dbet * cb,
                 2.0 * l1 * q2 * q * sb * sb)
    if minv > 0:
        phi, dphi, ddphi = the + bet, dthe + dbet, ddthe + ddbet
    else:
        phi, dphi, ddphi = the - bet, dthe - dbet, ddthe - ddbet
    cp, sp = math.cos(phi), math.sin(phi)
    return (j1[0] + l1 * cp, j1[1] + l1 * sp, j1[2] - l1 * dphi * sp, j1[3] + l1 * dphi * cp,
            j1[4] - l1 * (ddphi * sp + dphi * dphi * cp), j1[5] + l1 * (ddphi * cp - dphi * dphi * sp))


ACOS_RRR_C = r"""
/* The lecture's RRR_links (acos form), re-derived; segment_angle without its special case. */
static int acos_RRR(POINT j1, POINT j2, double l1, double l2, int minv, POINT *jb)
{
    const double dx = j2.P.x - j1.P.x, dy = j2.P.y - j1.P.y;
    const double dvx = j2.DP.x - j1.DP.x, dvy = j2.DP.y - j1.DP.y;
    const double dax = j2.DDP.x - j1.DDP.x, day = j2.DDP.y - j1.DDP.y;
    const double q2 = dx * dx + dy * dy;
    double q, dq, ddq, cb, sb, ss, the, dthe, ddthe, bet, dbet, ddbet, phi, dphi, ddphi, cp, sp;
    if (q2 <= 10e-30) { jb->P.x = jb->P.y = jb->DP.x = jb->DP.y = jb->DDP.x = jb->DDP.y = NAN; return 1; }
    q = sqrt(q2);
    dq = (dvx * dx + dvy * dy) / q;
    ddq = ((dax * dx + dvx * dvx + day * dy + dvy * dvy) * q - (dvx * dx + dvy * dy) * dq) / q2;
    cb = (l1 * l1 + q2 - l2 * l2) / (2.0 * l1 * q);
    if (fabs(cb) > 1.0) { jb->P.x = jb->P.y = jb->DP.x = jb->DP.y = jb->DDP.x = jb->DDP.y = NAN; return 1; }
    sb = sqrt(1.0 - cb * cb);
    ss = l1 * l1 - l2 * l2 - q2;
    the = atan2(dy, dx);
    dthe = (dx * dvy - dy * dvx) / q2;
    ddthe = (dx * day - dy * dax) / q2 - 2.0 * dthe * (dx * dvx + dy * dvy) / q2;
    bet = acos(cb);
    dbet = ss * dq / (2.0 * l1 * q2 * sb);
    ddbet = ((ss * (ddq * q - 2.0 * dq * dq) - 2.0 * (dq * q) * (dq * q)) * sb - ss * dq * q * dbet * cb)
            / (2.0 * l1 * q2 * q * sb * sb);
    if (minv > 0) { phi = the + bet; dphi = dthe + dbet; ddphi = ddthe + ddbet; }
    else { phi = the - bet; dphi = dthe - dbet; ddphi = ddthe - ddbet; }
    cp = cos(phi);
    sp = sin(phi);
    jb->P.x = j1.P.x + l1 * cp;
    jb->P.y = j1.P.y + l1 * sp;
    jb->DP.x = j1.DP.x - l1 * dphi * sp;
    jb->DP.y = j1.DP.y + l1 * dphi * cp;
    jb->DDP.x = j1.DDP.x - l1 * (ddphi * sp + dphi * dphi * cp);
    jb->DDP.y = j1.DDP.y + l1 * (ddphi * cp - dphi * dphi * sp);
    return 0;
}

/* The same, positions only. */
static int acos_RRR0(POINT j1, POINT j2, double l1, double l2, int minv, POINT *jb)
{
    const double dx = j2.P.x - j1.P.x, dy = j2.P.y - j1.P.y;
    const double q2 = dx * dx + dy * dy;
    double q, cb, phi;
    if (q2 <= 10e-30) { jb->P.x = jb->P.y = NAN; return 1; }
    q = sqrt(q2);
    cb = (l1 * l1 + q2 - l2 * l2) / (2.0 * l1 * q);
    if (fabs(cb) > 1.0) { jb->P.x = jb->P.y = NAN; return 1; }
    phi = minv > 0 ? atan2(dy, dx) + acos(cb) : atan2(dy, dx) - acos(cb);
    jb->P.x = j1.P.x + l1 * cos(phi);
    jb->P.y = j1.P.y + l1 * sin(phi);
    return 0;
}
"""


# ------------------------------------------------------------------ slider chain (PRR)

def prr_case(rng, far: float, tag: str) -> dict:
    """A slider chain with the slider about `far` link lengths from the guide's reference point."""
    ln = float(rng.uniform(0.5, 2.0))
    psig = float(rng.uniform(-math.pi, math.pi))
    gsi, eta = (float(x) for x in rng.uniform(-1, 1, size=2))
    u, n = (math.cos(psig), math.sin(psig)), (-math.sin(psig), math.cos(psig))
    jr = [float(x) for x in rng.uniform(-1, 1, size=2)]
    cphi = float(rng.uniform(0.1, 1.0)) * float(rng.choice([-1, 1]))  # (B - jr).u / l
    sphi = math.sqrt(1 - cphi * cphi) * float(rng.choice([-1, 1]))
    jb = (jr[0] + ln * (cphi * u[0] + sphi * n[0]), jr[1] + ln * (cphi * u[1] + sphi * n[1]))
    s = far * ln * float(rng.uniform(0.5, 1.0)) * float(rng.choice([-1, 1]))
    pg = (jb[0] - s * u[0] - gsi * u[0] - eta * n[0], jb[1] - s * u[1] - gsi * u[1] - eta * n[1])
    r = rng.normal(size=10)
    case = {"tag": tag, "far": far, "jr": (*jr, r[0] * ln, r[1] * ln, r[2] * ln, r[3] * ln), "l": ln,
            "pg": (*pg, r[4] * ln, r[5] * ln, r[6] * ln, r[7] * ln), "psig": (psig, float(r[8]), float(r[9])),
            "gsi": gsi, "eta": eta, "minv": 1 if cphi > 0 else -1}
    case["jr"] = tuple(float(x) for x in case["jr"])
    case["pg"] = tuple(float(x) for x in case["pg"])
    case["ref"], case["L"], case["scales"] = prr_exact(case)
    moved = dict(case)  # jr and pg moved to neighbouring doubles, as in rrr_case
    for key in ("jr", "pg"):
        moved[key] = tuple(math.nextafter(x, math.copysign(math.inf, float(rng.normal()))) for x in case[key][:2]) \
            + case[key][2:]
    case["moved"] = tuple(tuple(float(x) for x in rec) for rec in prr_exact(moved)[0])
    return case


def prr_exact(c: dict):
    """50-digit (s, jb) with rates; the length scale max(l, |w|); the rate scales."""
    jr, pg = [MP.mpf(x) for x in c["jr"]], [MP.mpf(x) for x in c["pg"]]
    th, om, al = (MP.mpf(x) for x in c["psig"])
    ln, gsi, eta, minv = MP.mpf(c["l"]), MP.mpf(c["gsi"]), MP.mpf(c["eta"]), c["minv"]
    u, n = (MP.cos(th), MP.sin(th)), (-MP.sin(th), MP.cos(th))
    w = [pg[i] + gsi * u[i] + eta * n[i] - jr[i] for i in (0, 1)]
    wu, p = w[0] * u[0] + w[1] * u[1], w[0] * u[1] - w[1] * u[0]
    eu = minv * MP.sqrt((ln - p) * (ln + p))
    s = eu - wu
    e = [eu * u[i] - p * n[i] for i in (0, 1)]
    jb = [jr[i] + e[i] for i in (0, 1)]
    rv = [pg[2 + i] - jr[2 + i] + om * ((s + gsi) * n[i] - eta * u[i]) for i in (0, 1)]
    ds = -(e[0] * rv[0] + e[1] * rv[1]) / eu
    ev = [rv[i] + ds * u[i] for i in (0, 1)]
    ra = [pg[4 + i] - jr[4 + i] + 2 * ds * om * n[i] + (s + gsi) * (al * n[i] - om**2 * u[i])
          - eta * (al * u[i] + om**2 * n[i]) for i in (0, 1)]
    dds = -(ev[0] ** 2 + ev[1] ** 2 + e[0] * ra[0] + e[1] * ra[1]) / eu
    ea = [ra[i] + dds * u[i] for i in (0, 1)]
    jbv = [jr[2 + i] + ev[i] for i in (0, 1)]
    jba = [jr[4 + i] + ea[i] for i in (0, 1)]
    length = max(float(max(ln, MP.sqrt(w[0] ** 2 + w[1] ** 2))), *(abs(x) for x in (*c["jr"][:2], *c["pg"][:2])),
                 *(abs(float(x)) for x in jb))
    vscale = max(_norm(jbv), _norm(c["jr"][2:4]), _norm(c["pg"][2:4]), abs(om) * length)
    ascale = max(_norm(jba), _norm(c["jr"][4:6]), _norm(c["pg"][4:6]), (abs(al) + om**2) * length)
    return ((s, *jb), (ds, *jbv), (dds, *jba)), length, (vscale, ascale)


def naive_prr(jr, ln: float, pg, psig, gsi: float, eta: float, minv: int):
    """s and jb with D = (w.u)^2 - |w|^2 + l^2 and the chain rule through sqrt; None where D < 0."""
    cg, sg = math.cos(psig[0]), math.sin(psig[0])
    om, al = psig[1], psig[2]
    rx, ry = gsi * cg - eta * sg, gsi * sg + eta * cg
    rvx, rvy = -om * ry, om * rx
    rax, ray = -al * ry - om * om * rx, al * rx - om * om * ry
    wx, wy = pg[0] + rx - jr[0], pg[1] + ry - jr[1]
    wvx, wvy = pg[2] + rvx - jr[2], pg[3] + rvy - jr[3]
    wax, way = pg[4] + rax - jr[4], pg[5] + ray - jr[5]
    wu = wx * cg + wy * sg
    wuv = wvx * cg + wvy * sg + om * (wy * cg - wx * sg)
    wua = wax * cg + way * sg + 2.0 * om * (wvy * cg - wvx * sg) + al * (wy * cg - wx * sg) - om * om * wu
    d = wu * wu - (wx * wx + wy * wy) + ln * ln
    if d < 0.0:
        return None
    dv = 2.0 * wu * wuv - 2.0 * (wx * wvx + wy * wvy)
    da = 2.0 * wuv * wuv + 2.0 * wu * wua - 2.0 * (wvx * wvx + wvy * wvy) - 2.0 * (wx * wax + wy * way)
    q = math.sqrt(d)
    dq = _div(dv, 2.0 * q)
    ddq = _div(2.0 * da * d - dv * dv, 4.0 * d * q)
    s, ds, dds = -wu + minv * q, -wuv + minv * dq, -wua + minv * ddq
    tn = 2.0 * ds * om + s * al
    return (s, pg[0] + s * cg + rx, pg[1] + s * sg + ry), \
        (ds, pg[2] + ds * cg - s * om * sg + rvx, pg[3] + ds * sg + s * om * cg + rvy), \
        (dds, pg[4] + dds * cg - tn * sg - s * om * om * cg + rax, pg[5] + dds * sg + tn * cg - s * om * om * sg + ray)


def lecture_prr(jr, ln: float, pg, psig, gsi: float, eta: float, minv: int):
    """The lecture's PRR_links position: d = l^2 - p^2 (unfactored), s = s0 +- sqrt(d)."""
    cp, sp = math.cos(psig[0]), math.sin(psig[0])
    a = -eta * sp + pg[0] - jr[0]
    b = eta * cp + pg[1] - jr[1]
    d = ln * ln - (a * sp - b * cp) * (a * sp - b * cp)
    if d < 0.0:
        return None
    s = -(a * cp + b * sp) - gsi + minv * math.sqrt(d)
    jpx, jpy = s * cp + pg[0], s * sp + pg[1]
    return s, gsi * cp - eta * sp + jpx, gsi * sp + eta * cp + jpy


NAIVE_PRR_C = r"""
/* PRR_links with D = (w.u)^2 - |w|^2 + l^2 and the chain rule through sqrt. */
static int naive_PRR(POINT jr, double l, POINT pg, ANGLE psig, double gsi, double eta, int minv,
                     VARIABLE *s, POINT *jb)
{
    const double cg = cos(psig.the), sg = sin(psig.the), om = psig.dthe, al = psig.ddthe;
    const double rx = gsi * cg - eta * sg, ry = gsi * sg + eta * cg;
    const double rvx = -om * ry, rvy = om * rx;
    const double rax = -al * ry - om * om * rx, ray = al * rx - om * om * ry;
    const double wx = pg.P.x + rx - jr.P.x, wy = pg.P.y + ry - jr.P.y;
    const double wvx = pg.DP.x + rvx - jr.DP.x, wvy = pg.DP.y + rvy - jr.DP.y;
    const double wax = pg.DDP.x + rax - jr.DDP.x, way = pg.DDP.y + ray - jr.DDP.y;
    const double wu = wx * cg + wy * sg;
    const double wuv = wvx * cg + wvy * sg + om * (wy * cg - wx * sg);
    const double wua = wax * cg + way * sg + 2.0 * om * (wvy * cg - wvx * sg) + al * (wy * cg - wx * sg) - om * om * wu;
    const double d = wu * wu - (wx * wx + wy * wy) + l * l;
    double dv, da, q, dq, ddq, tn;
    if (d < 0.0) {
        s->v = s->dv = s->ddv = NAN;
        jb->P.x = jb->P.y = jb->DP.x = jb->DP.y = jb->DDP.x = jb->DDP.y = NAN;
        return 1;
    }
    dv = 2.0 * wu * wuv - 2.0 * (wx * wvx + wy * wvy);
    da = 2.0 * wuv * wuv + 2.0 * wu * wua - 2.0 * (wvx * wvx + wvy * wvy) - 2.0 * (wx * wax + wy * way);
    q = sqrt(d);
    dq = dv / (2.0 * q);
    ddq = (2.0 * da * d - dv * dv) / (4.0 * d * q);
    s->v = -wu + minv * q;
    s->dv = -wuv + minv * dq;
    s->ddv = -wua + minv * ddq;
    tn = 2.0 * s->dv * om + s->v * al;
    jb->P.x = pg.P.x + s->v * cg + rx;
    jb->P.y = pg.P.y + s->v * sg + ry;
    jb->DP.x = pg.DP.x + s->dv * cg - s->v * om * sg + rvx;
    jb->DP.y = pg.DP.y + s->dv * sg + s->v * om * cg + rvy;
    jb->DDP.x = pg.DDP.x + s->ddv * cg - tn * sg - s->v * om * om * cg + rax;
    jb->DDP.y = pg.DDP.y + s->ddv * sg + tn * cg - s->v * om * om * sg + ray;
    return 0;
}
"""


# ------------------------------------------------------------------------- C harness

HARNESS = r"""
#define _POSIX_C_SOURCE 199309L
#include <float.h>
#include <math.h>
#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <time.h>

typedef struct { double x, y; } VEC2;
typedef struct { VEC2 P, DP, DDP; } POINT;
typedef struct { double the, dthe, ddthe; } ANGLE;
typedef struct { double v, dv, ddv; } VARIABLE;

RUNTIME

static POINT point(const double *d)
{
    POINT p;
    p.P.x = d[0]; p.P.y = d[1]; p.DP.x = d[2]; p.DP.y = d[3]; p.DDP.x = d[4]; p.DDP.y = d[5];
    return p;
}

static void put(const double *v, int n)
{
    int i;
    for (i = 0; i < n; i++) printf(i ? " %a" : "%a", v[i]);
    printf("\n");
}

static double now(void)
{
    struct timespec t;
    clock_gettime(CLOCK_MONOTONIC, &t);
    return t.tv_sec + 1e-9 * t.tv_nsec;
}

/* usage: harness rrr|prr eval|time REPS < cases (the count, then one case a line, hex floats).
   eval prints every case through linkgen, then through the lecture's form; time prints the
   ns per call of each (3R: also both at order 0, positions only), one run a line. */
int main(int argc, char **argv)
{
    const int prr = strcmp(argv[1], "prr") == 0, timing = strcmp(argv[2], "time") == 0;
    const int width = prr ? 19 : 15, reps = argc > 3 ? atoi(argv[3]) : 1;
    int n, i, k, r;
    double *in, sink = 0.0;
    if (scanf("%d", &n) != 1) return 2;
    in = malloc(sizeof(double) * (size_t)n * (size_t)width);
    for (i = 0; i < n * width; i++)
        if (scanf("%la", &in[i]) != 1) return 2;
    for (r = 0; r < (timing ? 15 : 1); r++) {
        double t[4];
        const int methods = timing && !prr ? 4 : 2;
        for (k = 0; k < methods; k++) {
            int rep;
            const double t0 = now();
            for (rep = 0; rep < reps; rep++) {
                for (i = 0; i < n; i++) {
                    const double *d = in + (size_t)i * (size_t)width;
                    double o[10];
                    POINT jb = {{0, 0}, {0, 0}, {0, 0}}, jp;
                    VARIABLE s;
                    if (!prr) {
                        VARIABLE l1 = {0, 0, 0}, l2 = {0, 0, 0};
                        const POINT p1 = point(d), p2 = point(d + 6);
                        double sigma = 0;
                        l1.v = d[12]; l2.v = d[13];
                        if (k == 0) o[0] = RRR_links(&p1, &p2, &l1, &l2, (int)d[14], &jb, &sigma);
                        else if (k == 1) o[0] = acos_RRR(point(d), point(d + 6), d[12], d[13], (int)d[14], &jb);
                        else if (k == 2) o[0] = RRR_links0(&p1, &p2, &l1, &l2, (int)d[14], &jb, &sigma);
                        else o[0] = acos_RRR0(point(d), point(d + 6), d[12], d[13], (int)d[14], &jb);
                        o[1] = sigma;
                    } else {
                        VARIABLE l = {0, 0, 0};
                        ANGLE psig;
                        const POINT pr = point(d), pgd = point(d + 7);
                        double sigma = 0;
                        l.v = d[6];
                        psig.the = d[13]; psig.dthe = d[14]; psig.ddthe = d[15];
                        if (k == 0)
                            o[0] = PRR_links(&pr, &l, &pgd, &psig, d[16], d[17], (int)d[18], &s, &jp, &jb, &sigma);
                        else o[0] = naive_PRR(point(d), d[6], point(d + 7), psig, d[16], d[17], (int)d[18], &s, &jb);
                        o[1] = s.v; o[2] = s.dv; o[3] = s.ddv;
                    }
                    if (timing) {
                        sink += jb.P.x + jb.P.y;
                        if (k < 2) sink += jb.DP.x + jb.DP.y + jb.DDP.x + jb.DDP.y;
                        continue;
                    }
                    o[prr ? 4 : 2] = jb.P.x; o[prr ? 5 : 3] = jb.P.y; o[prr ? 6 : 4] = jb.DP.x;
                    o[prr ? 7 : 5] = jb.DP.y; o[prr ? 8 : 6] = jb.DDP.x; o[prr ? 9 : 7] = jb.DDP.y;
                    put(o, prr ? 10 : 8);
                }
            }
            t[k] = (now() - t0) / ((double)reps * n) * 1e9;
        }
        if (timing) {
            for (k = 0; k < methods; k++) printf(k ? " %.3f" : "%.3f", t[k]);
            printf("\n");
        }
    }
    if (timing) fprintf(stderr, "%g\n", sink);
    free(in);
    return 0;
}
"""


def build_harness() -> Path:
    """Compile the harness: linkgen's printed C next to the lecture's forms, gcc -O2 -std=c99."""
    OUT.mkdir(parents=True, exist_ok=True)
    order0 = c_function(PRIMITIVES["RRR_links"], 0).replace("RRR_links(", "RRR_links0(")
    runtime = "\n".join([c_function(PRIMITIVES["RRR_links"], 2), order0, c_function(PRIMITIVES["PRR_links"], 2),
                         ACOS_RRR_C, NAIVE_PRR_C])
    (OUT / "harness.c").write_text(HARNESS.replace("RUNTIME", runtime))
    subprocess.run(["gcc", "-O2", "-std=c99", "-Wall", "harness.c", "-lm", "-o", "harness"], cwd=OUT, check=True)
    return OUT / "harness"


def rrr_row(c: dict) -> list[float]:
    return [*c["j1"], *c["j2"], c["l1"], c["l2"], c["minv"]]


def prr_row(c: dict) -> list[float]:
    return [*c["jr"], c["l"], *c["pg"], *c["psig"], c["gsi"], c["eta"], c["minv"]]


def run_harness(exe: Path, kind: str, mode: str, rows: list[list[float]], reps: int = 1) -> list[list[float]]:
    text = f"{len(rows)}\n" + "\n".join(_hexes(r) for r in rows) + "\n"
    out = subprocess.run([str(exe), kind, mode, str(reps)], input=text, capture_output=True, text=True, check=True)
    parse = _unhex if mode == "eval" else float
    return [[parse(w) for w in line.split()] for line in out.stdout.splitlines()]


# ---------------------------------------------------------------------------- study

def _rrr_errors(c: dict, out) -> tuple[float, float, float]:
    """(position error in ulps of L, velocity and acceleration relative errors) of one output."""
    if out is None:
        return NAN, NAN, NAN
    b, v, a = c["ref"]
    pos = _ulps(_dist(out[0:2], b), c["L"])
    if v is None:
        return pos, NAN, NAN
    vs = max(_norm(v), _norm(c["j1"][2:4]), _norm(c["j2"][2:4]))
    as_ = max(_norm(a), _norm(c["j1"][4:6]), _norm(c["j2"][4:6]))
    return pos, _rel(out[2:4], v, vs), _rel(out[4:6], a, as_)


def rrr_study(rng) -> dict:
    """Every 3R case through the four implementations; errors per case."""
    cases = [rrr_case(rng, 10 ** rng.uniform(-12, 0), 10 ** rng.uniform(-1, 0), "sweep") for _ in range(1200)]
    cases += [rrr_case(rng, 0.0, 10 ** rng.uniform(-1, 0), "toggle") for _ in range(150)]
    for ratio in (1e-8, 1e-12):
        cases += [rrr_case(rng, rng.uniform(0.1, 1), ratio, f"needle {ratio:.0e}") for _ in range(150)]
    for c in cases:  # the lattice B is the exact solution: check the reference against it
        assert _dist(c["B"], c["ref"][0]) < 1e-30 * c["L"], c
        moved = c["moved"]
        c["sens"] = (NAN, NAN, NAN) if moved is None else _rrr_errors(c, [float(x) for x in moved[0]] + (
            [NAN] * 4 if moved[1] is None else [float(x) for x in (*moved[1], *moved[2])]))
    fn = python_backend(2)["RRR_links"]
    exe = build_harness()
    cout = run_harness(exe, "rrr", "eval", [rrr_row(c) for c in cases])
    n = len(cases)
    c_lg, c_ac = cout[:n], cout[n:]
    diff = {"linkgen": 0, "acos": 0}
    for c, lg, ac in zip(cases, c_lg, c_ac):
        st, sig, out = fn(c["j1"], c["j2"], (c["l1"], 0.0, 0.0), (c["l2"], 0.0, 0.0), c["minv"])
        c["st"], c["lsigma"] = st, sig
        ref_acos = acos_rrr(c["j1"], c["j2"], c["l1"], c["l2"], c["minv"])
        c["err"] = {"linkgen": _rrr_errors(c, out), "acos": _rrr_errors(c, ref_acos)}
        diff["linkgen"] += not _same([st, sig, *out], lg)
        diff["acos"] += not _same(ref_acos or [NAN] * 6, ac[2:])
        c["out"] = (st, sig, out)
        j1, j2 = c["moved in"]
        c["moved fails"] = (fn(j1, j2, (c["l1"], 0.0, 0.0), (c["l2"], 0.0, 0.0), c["minv"])[0] == 1,
                            acos_rrr(j1, j2, c["l1"], c["l2"], c["minv"]) is None)
    timed = [rrr_row(c) for c in cases if c["tag"] == "sweep" and c["sigma"] > 1e-2]
    timing = [r for _ in range(3) for r in run_harness(exe, "rrr", "time", timed, reps=300)]
    return {"cases": cases, "diff": diff, "timing": timing, "timed": len(timed)}


def prr_study(rng) -> dict:
    """PRR_links against the naive quadratic and the lecture's l^2 - p^2, slider far from pg."""
    fars = (1.0, 1e2, 1e4, 1e6, 1e8)
    cases = [prr_case(rng, far, f"{far:.0e}") for far in fars for _ in range(100)]
    fn = python_backend(2)["PRR_links"]
    exe = OUT / "harness"
    cout = run_harness(exe, "prr", "eval", [prr_row(c) for c in cases])
    n = len(cases)
    diff = {"linkgen": 0, "naive": 0}

    def errors(c, s_jb):
        if s_jb is None or not all(math.isfinite(x) for x in s_jb[0]):
            return NAN, NAN, NAN
        (pos, vel, acc), (vs, as_) = c["ref"], c["scales"]
        e = max(_dist(s_jb[0][:1], pos[:1]), _dist(s_jb[0][1:], pos[1:]))
        return _ulps(e, c["L"]), _rel(s_jb[1][1:], vel[1:], vs), _rel(s_jb[2][1:], acc[1:], as_)

    for c, lg, nv in zip(cases, cout[:n], cout[n:]):
        args = (c["jr"], (c["l"], 0.0, 0.0), c["pg"], c["psig"], c["gsi"], c["eta"], c["minv"])
        st, sig, s, jp, jb = fn(*args)
        mine = ((s[0], jb[0], jb[1]), (s[1], jb[2], jb[3]), (s[2], jb[4], jb[5]))
        naive = naive_prr(c["jr"], c["l"], c["pg"], c["psig"], c["gsi"], c["eta"], c["minv"])
        lect = lecture_prr(c["jr"], c["l"], c["pg"], c["psig"], c["gsi"], c["eta"], c["minv"])
        c["err"] = {"linkgen": errors(c, mine), "naive": errors(c, naive),
                    "lecture": errors(c, None if lect is None else (lect, (0, 0, 0), (0, 0, 0)))[:1]}
        c["sens"] = errors(c, c["moved"])
        diff["linkgen"] += not _same([st, *s, *jb], [lg[0], *lg[1:4], *lg[4:10]])
        c["out"] = (st, sig, s, jb)
        want = [NAN] * 9 if naive is None else [naive[0][0], naive[1][0], naive[2][0], naive[0][1], naive[0][2],
                                                 naive[1][1], naive[1][2], naive[2][1], naive[2][2]]
        diff["naive"] += not _same(want, nv[1:10])
    timed = [prr_row(c) for c in cases if c["far"] == 1.0]
    timing = [r for _ in range(3) for r in run_harness(exe, "prr", "time", timed, reps=600)]
    return {"cases": cases, "fars": fars, "diff": diff, "timing": timing}


# --------------------------------------------------------------- languages and scaling

def scale_check(rrr: list[dict], prr: list[dict]) -> dict:
    """Outputs at inputs scaled by 2^k, compared bit for bit with 2^k times the unscaled ones."""
    fr, fp = python_backend(2)["RRR_links"], python_backend(2)["PRR_links"]
    out = {}
    for k in (-60, -20, 20, 60):
        f = 2.0**k
        bad = {"linkgen RRR": 0, "acos RRR": 0, "linkgen PRR": 0}
        for c in rrr:
            j1, j2 = tuple(x * f for x in c["j1"]), tuple(x * f for x in c["j2"])
            st, sig, got = fr(j1, j2, (c["l1"] * f, 0.0, 0.0), (c["l2"] * f, 0.0, 0.0), c["minv"])
            bad["linkgen RRR"] += not _same([st, sig, *got], [c["st"], c["lsigma"], *(x * f for x in c["out"][2])])
            a0 = acos_rrr(c["j1"], c["j2"], c["l1"], c["l2"], c["minv"])  # the same, unscaled
            a1 = acos_rrr(j1, j2, c["l1"] * f, c["l2"] * f, c["minv"])
            bad["acos RRR"] += not _same(a1 or [NAN] * 6, [x * f for x in (a0 or [NAN] * 6)])
        for c in prr:
            st, sig, s, jb = c["out"]
            got = fp(tuple(x * f for x in c["jr"]), (c["l"] * f, 0.0, 0.0), tuple(x * f for x in c["pg"]),
                     c["psig"], c["gsi"] * f, c["eta"] * f, c["minv"])
            bad["linkgen PRR"] += not _same([got[0], got[1], *got[2], *got[4]], [st, sig, *(x * f for x in (*s, *jb))])
        out[k] = bad
    return out


def _octave_call(name: str) -> list[str]:
    """Octave lines running one printed function on every row of d and printing its outputs."""
    point = "struct('x', r({0}), 'y', r({1}), 'dx', r({2}), 'dy', r({3}), 'ddx', r({4}), 'ddy', r({5}))"

    def pt(i):
        return point.format(*range(i, i + 6))

    if name == "RRR_links":
        call = (f"[jb, st, sigma] = RRR_links({pt(1)}, {pt(7)}, struct('v', r(13), 'dv', 0, 'ddv', 0), "
                "struct('v', r(14), 'dv', 0, 'ddv', 0), r(15));")
        outs = "st, sigma, jb.x, jb.y, jb.dx, jb.dy, jb.ddx, jb.ddy"
    else:
        call = (f"[s, jp, jb, st, sigma] = PRR_links({pt(1)}, struct('v', r(7), 'dv', 0, 'ddv', 0), {pt(8)}, "
                "struct('the', r(14), 'dthe', r(15), 'ddthe', r(16)), r(17), r(18), r(19));")
        outs = "st, sigma, s.v, s.dv, s.ddv, jb.x, jb.y, jb.dx, jb.dy, jb.ddx, jb.ddy"
    return [f"d = load('{name}.in'); f = fopen('{name}.out', 'w');", "for i = 1:rows(d)", "  r = d(i, :);",
            f"  {call}", f"  fprintf(f, '%.17g ', {outs}); fprintf(f, '\\n');", "end", "fclose(f);"]


def _expected(kind: str, c: dict) -> list[float]:
    st, sig, *rest = c["out"]
    return [st, sig, *rest[0]] if kind == "RRR_links" else [st, sig, *rest[0], *rest[1]]


def languages(rrr: list[dict], prr: list[dict]) -> dict:
    """Cases where the numpy backend and the Octave printing differ in any bit from the Python backend."""
    out = {}
    with np.errstate(all="ignore"):
        col = np.array([rrr_row(c) for c in rrr]).T
        st, sig, jb = numpy_backend(2)["RRR_links"](tuple(col[0:6]), tuple(col[6:12]), (col[12], 0 * col[12], 0),
                                                   (col[13], 0 * col[13], 0), col[14].astype(int))
        got = np.column_stack(np.broadcast_arrays(st, sig, *jb))
        out["numpy RRR_links"] = sum(not _same(g, _expected("RRR_links", c)) for g, c in zip(got, rrr))
        col = np.array([prr_row(c) for c in prr]).T
        st, sig, s, jp, jb = numpy_backend(2)["PRR_links"](
            tuple(col[0:6]), (col[6], 0 * col[6], 0), tuple(col[7:13]), tuple(col[13:16]), col[16], col[17],
            col[18].astype(int))
        got = np.column_stack(np.broadcast_arrays(st, sig, *s, *jb))
        out["numpy PRR_links"] = sum(not _same(g, _expected("PRR_links", c)) for g, c in zip(got, prr))
    if not shutil.which("octave-cli"):
        return out
    script = ["1;", octave_function(PRIMITIVES["RRR_links"], 2), octave_function(PRIMITIVES["PRR_links"], 2)]
    for name, cases, row in (("RRR_links", rrr, rrr_row), ("PRR_links", prr, prr_row)):
        (OUT / f"{name}.in").write_text("\n".join(" ".join(repr(float(x)) for x in row(c)) for c in cases) + "\n")
        script += _octave_call(name)
    (OUT / "languages.m").write_text("\n".join(script) + "\n")
    subprocess.run(["octave-cli", "-q", "languages.m"], cwd=OUT, check=True, capture_output=True)
    for name, cases in (("RRR_links", rrr), ("PRR_links", prr)):
        got = [[float(w) for w in line.split()] for line in (OUT / f"{name}.out").read_text().splitlines()]
        out[f"Octave {name}"] = sum(not _same(g, _expected(name, c)) for g, c in zip(got, cases))
    return out


def resolver_check() -> list[str]:
    """Final Add-link residuals of the samples with a resolver: linkgen's rule and one Newton step only."""
    lines = []
    for sample in ("sixbar_fig14", "double_triad"):
        log = build_log(str(ROOT / "samples" / sample / f"{sample}.yaml"))
        for rows in (361, 25):
            v, r, a = input_rows(log, rows)
            for label, lg in (("1e-10 L + one step", log),
                              ("one Newton step", replace(log, policy=replace(log.policy, tolerance=math.inf)))):
                res = evaluate(lg, v, r, a, order=2)
                ok = res.status <= 0
                f = max(float(np.max(np.abs(res.values[name][0][ok]))) for g in log.groups for name in g.residuals)
                its = np.concatenate([res.iterations[g.number][ok] for g in log.groups])
                lines.append(f"| {sample} | {rows} | {label} | {int(ok.sum())} | {f / log.length_scale / EPS:.2g} | "
                             f"{np.mean(its):.2f} | {np.max(its)} |")
    return lines


FAR_FOURBAR = """linkgen: 1
name: far_fourbar
units: {{length: mm, angle: rad}}
joints:
  O1: [{O1[0]!r}, {O1[1]!r}]
  A: [{A[0]!r}, {A[1]!r}]
  B: [{B[0]!r}, {B[1]!r}]
  O2: [{O2[0]!r}, {O2[1]!r}]
links:
  crank: {{joints: [O1, A]}}
  coupler: {{joints: [A, B]}}
  rocker: {{joints: [B, O2]}}
  frame: {{joints: [O1, O2], fixed: true}}
inputs:
  - {{joint: O1, link: crank, relative_to: frame, range: [0, 6.283185307179586], speed: 1.0}}
samples: 73
"""
FAR_SKETCH = {"O1": (0.0, 0.0), "A": (3.6, 4.8), "B": (45.0, 40.0), "O2": (70.0, 0.0)}  # crank 6, frame 70


def fourbar_exact(drawn: dict, theta, b_near) -> tuple:
    """50-digit A, B with velocities and accelerations (crank at unit speed), B the solution near b_near."""
    o1, a0, b0, o2 = (tuple(MP.mpf(c) for c in drawn[n]) for n in ("O1", "A", "B", "O2"))
    r, c, k = (MP.sqrt((p[0] - q[0]) ** 2 + (p[1] - q[1]) ** 2) for p, q in ((a0, o1), (b0, a0), (b0, o2)))
    t = MP.mpf(theta) + MP.atan2(o2[1] - o1[1], o2[0] - o1[0])  # the input is measured from the frame
    ca, sa = MP.cos(t), MP.sin(t)
    a, da, dda = (o1[0] + r * ca, o1[1] + r * sa), (-r * sa, r * ca), (-r * ca, -r * sa)
    dx, dy = o2[0] - a[0], o2[1] - a[1]
    d2 = dx * dx + dy * dy
    along = (c * c - k * k + d2) / (2 * d2)
    h = MP.sqrt(c * c / d2 - along * along)
    cands = [(a[0] + along * dx - s * h * dy, a[1] + along * dy + s * h * dx) for s in (1, -1)]
    b = min(cands, key=lambda p: (p[0] - b_near[0]) ** 2 + (p[1] - b_near[1]) ** 2)
    u, w = (b[0] - a[0], b[1] - a[1]), (b[0] - o2[0], b[1] - o2[1])
    det = u[0] * w[1] - u[1] * w[0]

    def solve(r1, r2):  # u . x = r1, w . x = r2
        return ((r1 * w[1] - r2 * u[1]) / det, (u[0] * r2 - w[0] * r1) / det)

    db = solve(u[0] * da[0] + u[1] * da[1], 0)
    rel = (db[0] - da[0], db[1] - da[1])
    ddb = solve(u[0] * dda[0] + u[1] * dda[1] - rel[0] ** 2 - rel[1] ** 2, -(db[0] ** 2 + db[1] ** 2))
    return {"A": (a, da, dda), "B": (b, db, ddb)}


def distance_study(distances=(0.0, 10.0, 1e3, 1e5)) -> list[str]:
    """A four-bar (crank 6, frame 70) moved n sizes away along (1, 0.7), over a full turn: worst errors
    of A and B against 50-digit closed form, computed relative to the sketch's centre (linkgen) and in
    absolute coordinates (the same step log with its origin set to (0, 0))."""
    import tempfile

    from linkgen.table import columns

    lines = []
    size = max(math.dist(p, q) for p in FAR_SKETCH.values() for q in FAR_SKETCH.values())
    with tempfile.TemporaryDirectory() as tmp:
        for n in distances:
            drawn = {k: (x + n * size, y + 0.7 * n * size) for k, (x, y) in FAR_SKETCH.items()}
            path = Path(tmp) / f"far_{n:g}.yaml"
            path.write_text(FAR_FOURBAR.format(**drawn))
            built = build_log(str(path), sweep=False)
            row = [f"{n:g}", f"({built.origin[0]:g}, {built.origin[1]:g})"]
            for log in (built, replace(built, origin=(0.0, 0.0))):
                v, r, a = input_rows(log, log.samples)
                names, data = columns(log, evaluate(log, v, r, a))
                col = {name: data[:, i] for i, name in enumerate(names)}
                worst = [0.0, 0.0, 0.0]
                exact = [fourbar_exact(drawn, v[k, 0], (col["B.x"][k], col["B.y"][k])) for k in range(len(v))]
                for p in ("A", "B"):
                    for level, fields in enumerate((("x", "y"), ("vx", "vy"), ("ax", "ay"))):
                        scale = max(MP.sqrt(e[p][level][0] ** 2 + e[p][level][1] ** 2) for e in exact)
                        for k, e in enumerate(exact):
                            err = MP.sqrt(sum((MP.mpf(float(col[f"{p}.{f}"][k])) - e[p][level][i]) ** 2
                                              for i, f in enumerate(fields)))
                            worst[level] = max(worst[level], float(err / (EPS * size) if level == 0 else err / scale))
                row += [f"{worst[0]:.3g}", f"{worst[1]:.2g}", f"{worst[2]:.2g}"]
            lines.append("| " + " | ".join(row) + " |")
    return lines


# -------------------------------------------------------------------------------- SVG

def svg_plot(path: Path, title: str, ylabel: str, ylim: tuple[int, int], series: list, guides: list,
             note: str) -> None:
    """A log-log line plot by hand: x = log10 sigma in [-12, 0] plus an 'exact toggle' column at -13.

    series: (label, colour, dash, [(x, y)]) in log10 units; guides: (label, colour, [(x, y)]).
    """
    w, h, left, right, top, bottom = 800, 480, 70, 230, 40, 70
    pw, ph = w - left - right, h - top - bottom
    x0, x1, (y0, y1) = -13.0, 0.0, ylim

    def px(x):
        return left + (x - x0) / (x1 - x0) * pw

    def py(y):
        return top + (y1 - min(max(y, y0), y1)) / (y1 - y0) * ph

    out = [f'<svg xmlns="http://www.w3.org/2000/svg" width="{w}" height="{h}" viewBox="0 0 {w} {h}" '
           'font-family="sans-serif" font-size="12">',
           f'<rect width="{w}" height="{h}" fill="white"/>',
           f'<text x="{left + pw / 2:.1f}" y="22" text-anchor="middle" font-size="14">{title}</text>']
    for y in range(y0, y1 + 1):
        out.append(f'<line x1="{left}" y1="{py(y):.1f}" x2="{left + pw}" y2="{py(y):.1f}" stroke="#e4e4e4"/>')
        out.append(f'<text x="{left - 6}" y="{py(y) + 4:.1f}" text-anchor="end">1e{y}</text>')
    for x in range(-12, 1):
        out.append(f'<line x1="{px(x):.1f}" y1="{top}" x2="{px(x):.1f}" y2="{top + ph}" stroke="#e4e4e4"/>')
        if x % 2 == 0:
            out.append(f'<text x="{px(x):.1f}" y="{top + ph + 16}" text-anchor="middle">1e{x}</text>')
    out.append(f'<text x="{px(-13):.1f}" y="{top + ph + 16}" text-anchor="middle">0</text>')
    out.append(f'<line x1="{px(-12.5):.1f}" y1="{top}" x2="{px(-12.5):.1f}" y2="{top + ph}" stroke="#999" '
               'stroke-dasharray="2,3"/>')
    out.append(f'<rect x="{left}" y="{top}" width="{pw}" height="{ph}" fill="none" stroke="#333"/>')
    out.append(f'<text x="{left + pw / 2:.1f}" y="{h - 32}" text-anchor="middle">'
               'sigma = h q / (l1 l2), distance to the toggle (0: exact toggle)</text>')
    out.append(f'<text x="{left}" y="{h - 10}" font-size="11" fill="#555">{note}</text>')
    out.append(f'<text transform="translate(16 {top + ph / 2:.1f}) rotate(-90)" text-anchor="middle">{ylabel}</text>')
    legend = []
    for label, colour, pts in guides:
        d = " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y in pts)
        out.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="1" stroke-dasharray="6,4"/>')
        legend.append((label, colour, "6,4", 1))
    for label, colour, dash, pts in series:
        pts = [(x, y) for x, y in pts if math.isfinite(y)]
        d = " ".join(f"{px(x):.1f},{py(y):.1f}" for x, y in pts)
        dash_attr = f' stroke-dasharray="{dash}"' if dash else ""
        out.append(f'<polyline points="{d}" fill="none" stroke="{colour}" stroke-width="2"{dash_attr}/>')
        out += [f'<circle cx="{px(x):.1f}" cy="{py(y):.1f}" r="2.5" fill="{colour}"/>' for x, y in pts]
        legend.append((label, colour, dash, 2))
    for i, (label, colour, dash, width) in enumerate(legend):
        y = top + 10 + 20 * i
        dash_attr = f' stroke-dasharray="{dash}"' if dash else ""
        out.append(f'<line x1="{w - right + 12}" y1="{y}" x2="{w - right + 40}" y2="{y}" stroke="{colour}" '
                   f'stroke-width="{width}"{dash_attr}/>')
        out.append(f'<text x="{w - right + 46}" y="{y + 4}">{label}</text>')
    out.append("</svg>")
    path.write_text("\n".join(out) + "\n")


def _bins(cases: list[dict], key, stat) -> list[tuple[float, float]]:
    """(log10 sigma, log10 stat of the finite errors) per half decade, the exact toggles at -13."""
    pts = []
    groups = [(-13.0, [c for c in cases if c["tag"] == "toggle"])]
    for k in range(24):
        lo, hi = -12 + k / 2, -12 + (k + 1) / 2
        groups.append((lo + 0.25, [c for c in cases if c["tag"] == "sweep" and lo <= math.log10(c["sigma"]) < hi]))
    for x, group in groups:
        vals = [key(c) for c in group]
        vals = [v for v in vals if math.isfinite(v)]
        if vals:
            pts.append((x, math.log10(max(stat(vals), 1e-30))))
    return pts


def plots(cases: list[dict]) -> None:
    def pos(m):
        return lambda c: max(c["err"][m][0] if m else c["sens"][0], 0.1)

    series = [("linkgen, median", "#1f6fb4", "", _bins(cases, pos("linkgen"), statistics.median)),
              ("linkgen, max", "#1f6fb4", "5,3", _bins(cases, pos("linkgen"), max)),
              ("acos form, median", "#d2452b", "", _bins(cases, pos("acos"), statistics.median)),
              ("acos form, max", "#d2452b", "5,3", _bins(cases, pos("acos"), max)),
              ("exact, inputs 1 ulp off, max", "#2a9d4b", "2,3", _bins(cases, pos(None), max))]
    root = math.log10(2.0**26)
    guides = [("1/sigma ulps", "#777", [(-root, root), (0, 0)]), ("sqrt(eps) L", "#aaa", [(-13, root), (0, root)])]
    svg_plot(DOCS / "accuracy-rrr.svg", "RRR_links: position error of B near a toggle (50-digit reference)",
             "error in ulps of L (0.1 = exact)", (-1, 10), series, guides,
             "per half decade of sigma; 'inputs 1 ulp off': how far the exact B moves when P1, P2 do")

    def rate(m, i):
        return lambda c: max(c["err"][m][i] if m else c["sens"][i], 1e-18)

    series = [("linkgen, velocity", "#1f6fb4", "", _bins(cases, rate("linkgen", 1), max)),
              ("linkgen, acceleration", "#1f6fb4", "5,3", _bins(cases, rate("linkgen", 2), max)),
              ("acos form, velocity", "#d2452b", "", _bins(cases, rate("acos", 1), max)),
              ("acos form, acceleration", "#d2452b", "5,3", _bins(cases, rate("acos", 2), max)),
              ("exact, inputs 1 ulp off", "#2a9d4b", "2,3", _bins(cases, rate(None, 1), max))]
    guides = [("eps / sigma^2", "#777", [(0.5 * math.log10(EPS), 0), (0, math.log10(EPS))])]
    svg_plot(DOCS / "accuracy-rrr-rates.svg", "RRR_links: worst relative error of the velocity and acceleration of B",
             "relative error (clipped at 1)", (-17, 0), series, guides,
             "linkgen gives no rates below sigma = 1e-7 (status 3); the acos form's inf and nan are left out")


# ----------------------------------------------------------------------------- report

def _fmt(x: float) -> str:
    if not math.isfinite(x):
        return "-"
    return f"{x:.2g}" if x < 1e4 else f"{x:.1e}"


def _stats(vals: list[float]) -> tuple[float, float, int]:
    fin = [v for v in vals if math.isfinite(v)]
    return (statistics.median(fin) if fin else NAN), (max(fin) if fin else NAN), len(vals) - len(fin)


RRR_BANDS = [("0.1 <= sigma <= 1", "sweep", 1e-1, 2), ("1e-3 <= sigma < 0.1", "sweep", 1e-3, 1e-1),
             ("1e-5 <= sigma < 1e-3", "sweep", 1e-5, 1e-3), ("1e-7 <= sigma < 1e-5", "sweep", 1e-7, 1e-5),
             ("1e-9 <= sigma < 1e-7", "sweep", 1e-9, 1e-7), ("1e-12 <= sigma < 1e-9", "sweep", 0, 1e-9),
             ("exact toggle (sigma = 0)", "toggle", 0, 1), ("needle, 1e-8 (sigma 0.1..1)", "needle 1e-08", 0, 2),
             ("needle, 1e-12 (sigma 0.1..1)", "needle 1e-12", 0, 2)]


def report_rrr(res: dict) -> None:
    cases = res["cases"]
    print("### RRR_links: position error of B in ulps of L, 50-digit reference")
    print("(L: the largest of l1, l2, q and the coordinates; 'moved': the exact B when P1 and P2 move to "
          "neighbouring doubles, what one rounding upstream does)")
    print("| case | n | linkgen median | linkgen max | max / kappa | acos median | acos max | acos failed |"
          " worst acos / linkgen | moved: B shifts (max) | moved: cannot close | moved: linkgen fails |"
          " moved: acos fails |")
    print("|---|---|---|---|---|---|---|---|---|---|---|---|---|")
    for label, tag, lo, hi in RRR_BANDS:
        group = [c for c in cases if c["tag"] == tag and lo <= c["sigma"] < hi]
        lm, lx, lnan = _stats([c["err"]["linkgen"][0] for c in group])
        am, ax, anan = _stats([c["err"]["acos"][0] for c in group])
        _, sx, snan = _stats([c["sens"][0] for c in group])
        kap = max((c["err"]["linkgen"][0] * c["sigma"] for c in group if c["sigma"] > 0), default=NAN)
        lnan_s = f" ({lnan} failed)" if lnan else ""
        print(f"| {label} | {len(group)} | {_fmt(lm)} | {_fmt(lx)}{lnan_s} | {_fmt(kap)} | {_fmt(am)} | {_fmt(ax)} | "
              f"{anan} ({100 * anan / len(group):.0f}%) | {_fmt(ax / lx) if lx > 0 else '-'} | {_fmt(sx)} | "
              f"{snan} ({100 * snan / len(group):.0f}%) | {sum(c['moved fails'][0] for c in group)} | "
              f"{sum(c['moved fails'][1] for c in group)} |")
    print()
    print("### RRR_links: worst relative error of the velocity and acceleration of B")
    print("(relative to the largest velocity (acceleration) of B, P1, P2; linkgen gives nan below sigma = 1e-7 "
          "by design; 'moved' as above)")
    print("| case | linkgen velocity | acos velocity | moved: velocity | linkgen acceleration | acos acceleration |"
          " moved: acceleration | acos inf/nan rates |")
    print("|---|---|---|---|---|---|---|---|")
    for label, tag, lo, hi in RRR_BANDS:
        if tag == "toggle":
            continue
        group = [c for c in cases if c["tag"] == tag and lo <= c["sigma"] < hi]
        cols = [_stats([c[k][m][i] if k == "err" else c[k][i] for c in group])[1]
                for i in (1, 2) for k, m in (("err", "linkgen"), ("err", "acos"), ("sens", None))]
        bad = sum(1 for c in group if math.isfinite(c["err"]["acos"][0]) and not math.isfinite(c["err"]["acos"][2]))
        print(f"| {label} | {' | '.join(_fmt(x) for x in cols)} | {bad} of {len(group)} |")
    print()
    print(f"C (gcc -O2 -std=c99) vs the Python versions: {res['diff']['linkgen']} of {len(cases)} cases differ in "
          f"any bit for linkgen, {res['diff']['acos']} for the acos form (the errors above hold for both).")
    t = [statistics.median(r[k] for r in res["timing"]) for k in range(4)]
    f = [min(r[k] for r in res["timing"]) for k in range(4)]
    print(f"C time per call, ns (gcc -O2; median of {len(res['timing'])} runs in 3 processes, fastest run in "
          f"brackets; {res['timed']} cases with sigma > 0.01 in a loop):")
    print(f"- with velocity and acceleration: linkgen {t[0]:.1f} ({f[0]:.1f}), acos form {t[1]:.1f} ({f[1]:.1f}); "
          f"acos / linkgen {t[1] / t[0]:.2f}")
    print(f"- positions only: linkgen {t[2]:.1f} ({f[2]:.1f}), acos form {t[3]:.1f} ({f[3]:.1f}); "
          f"acos / linkgen {t[3] / t[2]:.2f}")
    print()


def report_prr(res: dict) -> None:
    cases = res["cases"]
    print("### PRR_links: slider far from the guide's reference point (sigma 0.1..1), 50-digit reference")
    print("(position: worst of s and jb in ulps of L, the largest of l, |w| and the coordinates; 'moved': jr and pg "
          "moved to neighbouring doubles)")
    print("| distance / l | n | linkgen median | linkgen max | naive median | naive max | naive failed | "
          "lecture l^2 - p^2 max | moved: exact shifts (max) |")
    print("|---|---|---|---|---|---|---|---|---|")
    for far in res["fars"]:
        group = [c for c in cases if c["far"] == far]
        lm, lx, _ = _stats([c["err"]["linkgen"][0] for c in group])
        nm, nx, nn = _stats([c["err"]["naive"][0] for c in group])
        tx, sx = (_stats([c[k]["lecture"][0] if k == "err" else c[k][0] for c in group])[1] for k in ("err", "sens"))
        print(f"| {far:.0e} | {len(group)} | {_fmt(lm)} | {_fmt(lx)} | {_fmt(nm)} | {_fmt(nx)} | "
              f"{nn} ({100 * nn / len(group):.0f}%) | {_fmt(tx)} | {_fmt(sx)} |")
    print()
    print("| distance / l | linkgen velocity | naive velocity | moved: velocity | linkgen acceleration | "
          "naive acceleration | moved: acceleration |")
    print("|---|---|---|---|---|---|---|")
    for far in res["fars"]:
        group = [c for c in cases if c["far"] == far]
        cols = [_stats([c[k][m][i] if k == "err" else c[k][i] for c in group])[1]
                for i in (1, 2) for k, m in (("err", "linkgen"), ("err", "naive"), ("sens", None))]
        print(f"| {far:.0e} | {' | '.join(_fmt(x) for x in cols)} |")
    print()
    n = len(cases)
    print(f"C (gcc -O2 -std=c99) vs the Python versions: {res['diff']['linkgen']} of {n} cases differ in any bit for "
          f"linkgen, {res['diff']['naive']} for the naive form.")
    t = res["timing"]
    lg, nv = statistics.median(r[0] for r in t), statistics.median(r[1] for r in t)
    print(f"C time per call, ns (gcc -O2, median of {len(t)} runs in 3 processes, fastest in brackets, with velocity "
          f"and acceleration): linkgen {lg:.1f} ({min(r[0] for r in t):.1f}), naive {nv:.1f} "
          f"({min(r[1] for r in t):.1f}); naive / linkgen {nv / lg:.2f}")
    print()


def bench_accuracy() -> None:
    print("## Accuracy of the two-link chains (positions as exact doubles, 50-digit mpmath reference)")
    rng = np.random.default_rng(SEED)
    rrr = rrr_study(rng)
    prr = prr_study(rng)
    report_rrr(rrr)
    report_prr(prr)
    print("### Scale: inputs times 2^k, outputs compared bit for bit with 2^k times the unscaled ones")
    print("| k | linkgen RRR differ | acos RRR differ | linkgen PRR differ |")
    print("|---|---|---|---|")
    for k, bad in scale_check(rrr["cases"], prr["cases"]).items():
        print(f"| {k} | {bad['linkgen RRR']} of {len(rrr['cases'])} | {bad['acos RRR']} of {len(rrr['cases'])} | "
              f"{bad['linkgen PRR']} of {len(prr['cases'])} |")
    print()
    langs = {"C RRR_links": rrr["diff"]["linkgen"], "C PRR_links": prr["diff"]["linkgen"],
             **languages(rrr["cases"], prr["cases"])}
    print(f"Languages: cases (of {len(rrr['cases'])} 3R, {len(prr['cases'])} slider) differing in any bit from the "
          "Python backend: " + ", ".join(f"{k} {v}" for k, v in langs.items())
          + ("" if "Octave RRR_links" in langs else " (Octave not installed)") + ".")
    print()
    print("### Resolver: largest Add-link residual |f| over the sweep (rows that assemble), in eps L")
    print("| sample | rows | rule | rows ok | max abs(f) / (eps L) | Newton steps mean | max |")
    print("|---|---|---|---|---|---|---|")
    for line in resolver_check():
        print(line)
    print()
    print("### Far from the origin: a four-bar (crank 6, frame 70) moved n sizes away, a full turn in 73 rows")
    print("Worst errors of A and B: positions in eps L (L = the sketch's size), velocities and accelerations "
          "relative to their largest value over the turn.")
    print()
    print("| n sizes | origin | relative: position | velocity | acceleration | absolute: position | velocity "
          "| acceleration |")
    print("|---|---|---|---|---|---|---|---|")
    for line in distance_study():
        print(line)
    print()
    plots(rrr["cases"])
    print("wrote docs/accuracy-rrr.svg, docs/accuracy-rrr-rates.svg")
