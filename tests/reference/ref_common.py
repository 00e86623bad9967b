"""Shared by make_reference.py's modules: the working precisions and agreement bounds, the
cross-check of two routes (agree, with the worst agreement of each kind kept for the log),
adaptive tanh-sinh and Gauss-Legendre quadrature, and the break points of their panels."""

import mpmath
from mpmath import mp, mpf

INF = float("inf")

WORK_DPS = 45        # working precision of the quadratures (decimal digits)
CLOSED_DPS = 110     # closed forms (their complex E1 terms cancel by up to ~20 digits)
OUT_DIGITS = 25      # significant digits written
AGREE_REL = 1e-30    # the two routes to every value must agree this well (relative; reached: <= 1e-37)
SURFACE_AGREE_REL = 1e-30  # the same for the surface terms
CHECK_REL = 1e-22    # --check: recomputed vs committed (the files hold 25 digits)


class ReferenceError(Exception):
    pass


def rel_diff(a, b):
    """|a - b| / |b|, and |a| when b = 0."""
    if b == 0:
        return abs(a)
    return abs(a - b) / abs(b)


WORST = {}  # the worst agreement of each cross-check, for the log


def agree(what, a, b, tol=AGREE_REL):
    e = rel_diff(a, b)
    key = what.split("(")[0] + (" vs" + what.split(" vs", 1)[1] if " vs" in what else "")
    WORST[key] = max(WORST.get(key, mpf(0)), e)
    if e > tol:
        raise ReferenceError("%s: the two methods disagree: %s vs %s (relative %s > %g)"
                             % (what, mpmath.nstr(a, 30), mpmath.nstr(b, 30), mpmath.nstr(e, 3), tol))
    return e


def quad_ts(f, pts, what):
    """Adaptive tanh-sinh over the panels pts (the last may be +inf); raises if mpmath's own
    error estimate exceeds 1e-32 relative. mpmath's estimate has an absolute floor near the
    working epsilon, so a small integral is integrated again scaled to order 1."""
    val, err = mp.quad(f, pts, method="tanh-sinh", error=True)
    if err > mpf("1e-32") * abs(val) and val != 0:
        scale = 1 / val
        val, err = mp.quad(lambda x: f(x) * scale, pts, method="tanh-sinh", error=True)
        val, err = val / scale, err / abs(scale)
    if err > mpf("1e-32") * abs(val):
        raise ReferenceError("%s: tanh-sinh error estimate %s for %s" % (what, mpmath.nstr(err, 3), mpmath.nstr(val, 10)))
    return val


def quad_gl(f, pts, estimate):
    """Gauss-Legendre over finite panels pts (mpmath raises the degree until it converges).
    mpmath stops at an absolute error near the working epsilon, so the integrand is scaled to
    order 1 by an estimate of the integral (the tanh-sinh value)."""
    scale = 1 / estimate if estimate != 0 else mpf(1)
    return mp.quad(lambda x: f(x) * scale, pts, method="gauss-legendre") / scale


def ladder(lo_scale, hi, ratio):
    """Geometric break points lo_scale * ratio^k in (0, hi)."""
    out = []
    x = lo_scale
    while x < hi:
        out.append(x)
        x *= ratio
    return out


def panels(length, scales, far, peak=None, width=None, ratio=2):
    """Break points on [0, length] (length may be +inf: then the panels run to `far` and a
    last panel [far, inf] is appended). A geometric ladder from the smallest positive scale
    / 16 resolves boundary layers at 0 and e-folding; a second ladder peak +- width * ratio^k
    resolves a near-singular peak at `peak` of half-width `width`."""
    end = far if length == INF else length
    small = min(s for s in scales if s > 0) / 16
    pts = set(x for x in ladder(small, end, ratio))
    if peak is not None and 0 < peak < end:
        pts.add(peak)
        for x in ladder(width, 2 * end, ratio):
            for y in (peak - x, peak + x):
                if 0 < y < end:
                    pts.add(y)
    pts = [mpf(0)] + sorted(pts) + [end]
    if length == INF:
        pts.append(mpmath.inf)
    return pts
