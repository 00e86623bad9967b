#!/usr/bin/env python3
"""30-digit reference values for scatterlut's tests (tests/reference/README.md).

    python3 tests/reference/make_reference.py            # writes F_ref.json, N_ref.json, physical_ref.json, hg_ref.json, surface_ref.json
    python3 tests/reference/make_reference.py --check    # recomputes a subset, compares with the files

Every value is an integral computed with mpmath by adaptive tanh-sinh quadrature on panels
cut at the integrand's features (boundary layers, near-singular peaks, e-folding lengths),
and computed a second time by an independent route (a closed form, or Gauss-Legendre
quadrature on a different set of panels). The two must agree to AGREE_REL (relative) or the
script stops with an error and writes nothing. Values are written as decimal strings with
25 significant digits. Inputs are IEEE doubles, taken exactly (v = pi/2 means the double
nearest pi/2, which lies 6.1e-17 below it). Needs python3 and mpmath (>= 1.2.1).
"""

import argparse
import json
import os
import sys
import tempfile
import time

SKIP = 77  # CTest's SKIP_RETURN_CODE for --check

try:
    import mpmath
    from mpmath import mp, mpf, mpc
except ImportError as exc:  # pragma: no cover - depends on the machine
    if "--check" in sys.argv[1:]:
        print("skipped: python module mpmath not found (%s; Debian: apt-get install python3-mpmath)" % exc)
        sys.exit(SKIP)
    sys.exit("make_reference.py: needs the python module mpmath (Debian: apt-get install python3-mpmath): %s" % exc)

HERE = os.path.dirname(os.path.abspath(__file__))
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


# --------------------------------------------------------------------------------------------
# F(u, v) = int_0^v exp(-u tan xi) dxi and tail(u, v) = int_v^{pi/2} exp(-u tan xi) dxi
# (Sun et al. 2005). u >= 0, 0 <= v <= pi/2; v is the given double, pi/2 in the tail exact.

def F_quadrature(u, v):
    """xi-space tanh-sinh; break points where u tan xi = 2^k (the e-folds of the integrand)."""
    if v == 0:
        return mpf(0)
    if u == 0:
        return v
    pts = [mpf(0)]
    for k in range(-8, 12):
        x = mpmath.atan(mpf(2) ** k / u)
        if 0 < x < v and x > pts[-1]:
            pts.append(x)
    pts.append(v)
    return quad_ts(lambda x: mpmath.exp(-u * mpmath.tan(x)), pts, "F(%s, %s)" % (u, v))


def tail_quadrature(u, v):
    """t = tan xi, s = t - tan v:  tail = e^{-u tan v} int_0^inf e^{-us} / (1 + (tan v + s)^2) ds,
    the exponential factor taken out exactly; break points at 2^k/u and at 2^k (1 + tan v)."""
    with mp.workdps(WORK_DPS + 40):
        # pi/2 - v cancels up to 16 digits (v = the double nearest pi/2), and u tan v reaches
        # 1.6e20 in the exponent: both at 40 extra digits.
        W = mp.pi / 2 - v
        if u == 0:
            return +W
        T = mpmath.cot(W) if W > 0 else mpf(0)
        factor = mpmath.exp(-u * T)
    scales = [1 / u, 1 + T]
    pts = set()
    for s in scales:
        for k in range(-6, 12):
            pts.add(s * mpf(2) ** k)
    pts = [mpf(0)] + sorted(pts) + [mpmath.inf]
    g = quad_ts(lambda s: mpmath.exp(-u * s) / (1 + (T + s) ** 2), pts, "tail(%s, %s)" % (u, v))
    return factor * g


def F_closed(u, v):
    """With t = tan xi, F = int_0^{tan v} e^{-ut}/(1+t^2) dt; partial fractions
    1/(1+t^2) = Im[1/(t - i)] and int e^{-ut}/(t - i) = e^{-iu} [E1(-iu) - E1(u(t - i))] give
        F = Im(e^{-iu} [E1(-iu) - E1(u(tan v - i))]),  tail = Im(e^{-iu} E1(u(tan v - i))),
    E1 the principal exponential integral (the path -iu -> u(tan v - i) stays in Im z = -u)."""
    with mp.workdps(CLOSED_DPS):
        u = mpf(u)
        v = mpf(v)
        W = mp.pi / 2 - v
        if u == 0:
            return v, W
        T = mpmath.cot(W) if W > 0 else mpmath.inf
        phase = mpmath.exp(mpc(0, -u))
        full = mpmath.im(phase * mpmath.e1(mpc(0, -u)))
        if v == 0:
            return mpf(0), full
        tail = mpmath.im(phase * mpmath.e1(u * mpc(T, -1)))
        return full - tail, tail


def F_point(u, v):
    """Both values of one point, each by quadrature checked against the closed form."""
    uq, vq = mpf(u), mpf(v)
    F = F_quadrature(uq, vq)
    tail = tail_quadrature(uq, vq)
    Fc, tailc = F_closed(u, v)
    agree("F(u=%r, v=%r)" % (u, v), F, Fc)
    agree("tail(u=%r, v=%r)" % (u, v), tail, tailc)
    return {"u": u, "v": v, "F": F, "tail": tail}


# --------------------------------------------------------------------------------------------
# N(T, g, r, S) = int_0^S exp(-t - h t/(t + T r)) / h^2 dt,  h^2 = t^2 + T^2 + 2 t T g,
# H = int_0^S h^-2 dt, E = N/H (Gath 2008 §4.2). t: optical depth along the eye ray below the
# surface; T: optical distance surface point - light; g: cosine between the eye direction and
# the direction to the light; r = mu_l / mu_e; S: optical thickness (inf = thick).

def N_features(T, g, r, S):
    """(peak, half-width) of 1/h^2 and the scales that need panels."""
    T, g, r = mpf(T), mpf(g), mpf(r)
    b = T * mpmath.sqrt((1 - g) * (1 + g))        # h^2 = (t + T g)^2 + b^2
    peak = -T * g if g < 0 else None
    width = b
    if peak is not None:
        end = mpf(S) if S != INF else mpmath.inf
        dist = peak - end if peak > end else mpf(0)  # the far face may stop short of the peak
        width = max(b, dist)
        if width == 0:
            raise ReferenceError("N(T=%r, g=%r, S=%r): g = -1 with S >= T diverges" % (T, g, S))
    scales = [mpf(1), T, r, T * r]
    if peak is not None:
        scales.append(width)
    return peak, width, scales


def N_integrand(T, g, r, with_attenuation=True):
    T, g, r = mpf(T), mpf(g), mpf(r)
    Tg, b2, Tr = T * g, T * T * (1 - g) * (1 + g), T * r

    def f(t):
        h2 = (t + Tg) ** 2 + b2
        if not with_attenuation:
            return 1 / h2
        frac = t / (t + Tr) if Tr > 0 else mpf(1)  # the light path's share below the surface
        return mpmath.exp(-t - mpmath.sqrt(h2) * frac) / h2
    return f


def H_closed(T, g, S):
    """h^2 = (t + T g)^2 + b^2, b = T sqrt(1 - g^2):  H = (1/b) [atan2(S + T g, b) - atan2(T g, b)]
    (atan2(S + T g, b) -> pi/2 for S = inf); at g = 1, H = S/(T (T + S)) (1/T thick); at
    g = -1, H = S/(T (T - S)), finite only for S < T. Evaluated at CLOSED_DPS digits."""
    with mp.workdps(CLOSED_DPS):
        T, g = mpf(T), mpf(g)
        Sm = mpmath.inf if S == INF else mpf(S)
        if g == 1:
            return 1 / T if S == INF else Sm / (T * (T + Sm))
        if g == -1:
            if not Sm < T:
                raise ReferenceError("H(T=%r, g=-1, S=%r) diverges" % (T, S))
            return Sm / (T * (T - Sm))
        b = T * mpmath.sqrt((1 - g) * (1 + g))
        hi = mp.pi / 2 if S == INF else mpmath.atan2(Sm + T * g, b)
        return (hi - mpmath.atan2(T * g, b)) / b


def N_far(T, g, peak, width):
    """Where the ladders of a thick slab stop (the last panel runs on to infinity)."""
    far = max(mpf(64), 4 * mpf(T))
    if peak is not None:
        far = max(far, peak + 64 * width)
    return far


def N_quadrature_ts(T, g, r, S, with_attenuation=True):
    peak, width, scales = N_features(T, g, r, S)
    pts = panels(S if S == INF else mpf(S), scales, N_far(T, g, peak, width), peak, width, ratio=2)
    return quad_ts(N_integrand(T, g, r, with_attenuation), pts, "N(%r, %r, %r, %r)" % (T, g, r, S))


def N_quadrature_gl(T, g, r, S, estimate):
    """Second route: Gauss-Legendre on ratio-3 panels; a thick slab is cut where the rest,
    int_c^inf e^{-t}/h^2 dt <= e^{-c}/h(c)^2, is below 1e-40 of the estimate."""
    peak, width, scales = N_features(T, g, r, S)
    f = N_integrand(T, g, r)
    if S == INF:
        c = N_far(T, g, peak, width)
        Tg, b2 = mpf(T) * mpf(g), mpf(T) ** 2 * (1 - mpf(g)) * (1 + mpf(g))
        while mpmath.exp(-c) / ((c + Tg) ** 2 + b2) > mpf("1e-40") * estimate:
            c *= 2
        end = c
    else:
        end = mpf(S)
    pts = panels(end, scales, end, peak, width, ratio=3)
    return quad_gl(f, pts, estimate)


def N_point(T, g, r, S):
    N = N_quadrature_ts(T, g, r, S)
    N2 = N_quadrature_gl(T, g, r, S, N)
    agree("N(T=%r, g=%r, r=%r, S=%r)" % (T, g, r, S), N, N2)
    H = H_closed(T, g, S)
    agree("H(T=%r, g=%r, S=%r) quadrature vs closed form" % (T, g, S), N_quadrature_ts(T, g, r, S, False), H)
    if r == 0:
        # r = 0 is the airlight in optical units (sigma_t = 1, D = T, cos(gamma) = -g).
        A = airlight_integral(1, 1, mpf(T), -mpf(g), mpmath.sqrt((1 - mpf(g)) * (1 + mpf(g))), S)
        agree("N(T=%r, g=%r, r=0, S=%r) vs the airlight integral" % (T, g, S), A, N)
    return {"T": T, "g": g, "r": r, "S": S, "N": N, "H": H, "E": N / H}


# --------------------------------------------------------------------------------------------
# Radiance in physical units (W/(m^2 sr) for I0 in W/sr, sigma in 1/m, lengths in m), by direct
# quadrature along the view ray with the isotropic phase function 1/(4 pi).

def airlight_integral(sigma_t, prefactor, D, cos_g, sin_g, s, method="ts", estimate=None):
    """prefactor * int_0^s e^{-sigma_t (x + d)} / d^2 dx, d^2 = (x - D cos g)^2 + (D sin g)^2."""
    sigma_t = mpf(sigma_t)
    xc, b = D * cos_g, D * sin_g

    def f(x):
        d2 = (x - xc) ** 2 + b * b
        return mpmath.exp(-sigma_t * (x + mpmath.sqrt(d2))) / d2
    peak = xc if xc > 0 else None
    length = INF if s == INF else mpf(s)
    end = length
    if peak is not None:
        if end != INF and peak > end:
            width = max(b, peak - end)
        else:
            width = b
        if width == 0:
            raise ReferenceError("airlight: the view ray runs through the light")
    else:
        width = b
    scales = [D, b]
    if sigma_t > 0:
        scales.append(1 / sigma_t)
    far = max(D, 64 / sigma_t if sigma_t > 0 else D) * 4
    if peak is not None:
        far = max(far, peak + 64 * width)
    if method == "ts":
        pts = panels(length, scales, far, peak, width if peak is not None else None, ratio=2)
        return prefactor * quad_ts(f, pts, "airlight integral")
    if length == INF:
        raise ReferenceError("airlight: Gauss-Legendre route needs a finite length")
    pts = panels(length, scales, length, peak, width if peak is not None else None, ratio=3)
    return prefactor * quad_gl(f, pts, estimate / prefactor)


def airlight_case(sigma_s, sigma_a, intensity, distance, gamma, length):
    """Viewer and point light inside the medium; gamma = angle between the view direction and
    the direction viewer -> light (0: looking at the light); distance = viewer-light distance;
    length = view ray length:  L = sigma_s/(4 pi) I0 int_0^s e^{-sigma_t (x + d(x))}/d(x)^2 dx,
    d(x)^2 = x^2 + D^2 - 2 x D cos(gamma)."""
    ss, st = mpf(sigma_s), mpf(sigma_s) + mpf(sigma_a)
    D, g = mpf(distance), mpf(gamma)
    pre = ss / (4 * mp.pi) * mpf(intensity)
    L = airlight_integral(st, pre, D, mpmath.cos(g), mpmath.sin(g), length, "ts")
    L2 = airlight_integral(st, pre, D, mpmath.cos(g), mpmath.sin(g), length, "gl", L)
    what = "airlight(%r, %r, %r, %r, %r, %r)" % (sigma_s, sigma_a, intensity, distance, gamma, length)
    agree(what, L, L2)
    # Conventions: the same radiance is sigma_s/(4 pi) I0 sigma_t N(sigma_t D, -cos(gamma), 0, sigma_t s).
    if st > 0:
        N = airlight_integral(1, 1, st * D, mpmath.cos(g), mpmath.sin(g), st * mpf(length), "ts")
        agree(what + " vs sigma_t N(T, -cos(gamma), 0, S)", pre * st * N, L)
    return {"quantity": "airlight", "sigma_s": sigma_s, "sigma_a": sigma_a, "intensity": intensity,
            "distance": distance, "gamma": gamma, "length": length, "L": L}


def dot(a, b):
    return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]


def unit(a):
    a = [mpf(x) for x in a]
    n = mpmath.sqrt(dot(a, a))
    return [x / n for x in a]


def near_light_case(sigma_s, sigma_a, intensity, normal, eye_dir, light_pos, length):
    """Point light outside a medium bounded by a plane through the origin O (the entry point),
    outward unit normal n, medium on the side n.p < 0. e = unit vector from O towards the viewer
    (n.e > 0); the view ray inside runs through P(x) = -x e, x in [0, length] (inf = thick).
    light_pos = l relative to O. The light path P -> l is straight; only its part below the plane
    attenuates: k(x) = d(x) * x mu_e / (x mu_e + h), h = n.l, mu_e = n.e, d(x) = |l - P(x)|:
        L = sigma_s/(4 pi) I0 int_0^length e^{-sigma_t (x + k(x))} / d(x)^2 dx,
    and L = 0 for a light below the plane (h < 0). normal and eye_dir are normalised here."""
    n, e = unit(normal), unit(eye_dir)
    l = [mpf(x) for x in light_pos]
    ss, st = mpf(sigma_s), mpf(sigma_s) + mpf(sigma_a)
    mu_e, h = dot(n, e), dot(n, l)
    what = "near_light(%r, %r, %r, %r, %r, %r, %r)" % (sigma_s, sigma_a, intensity, normal, eye_dir, light_pos, length)
    if not mu_e > 0:
        raise ReferenceError(what + ": the viewer is below the surface")
    base = {"quantity": "near_light", "sigma_s": sigma_s, "sigma_a": sigma_a, "intensity": intensity,
            "normal": list(normal), "eye_dir": list(eye_dir), "light_pos": list(light_pos), "length": length}
    if h < 0:
        base["L"] = mpf(0)
        return base
    el = dot(e, l)
    cross = [e[1] * l[2] - e[2] * l[1], e[2] * l[0] - e[0] * l[2], e[0] * l[1] - e[1] * l[0]]
    b2 = dot(cross, cross)                 # d(x)^2 = (x + e.l)^2 + |e x l|^2
    dist = mpmath.sqrt(dot(l, l))
    pre = ss / (4 * mp.pi) * mpf(intensity)

    def f(x):
        d2 = (x + el) ** 2 + b2
        d = mpmath.sqrt(d2)
        k = d * (x * mu_e) / (x * mu_e + h) if h > 0 else d
        return mpmath.exp(-st * (x + k)) / d2
    peak = -el if el < 0 else None
    width = mpmath.sqrt(b2)
    Lm = INF if length == INF else mpf(length)
    if peak is not None and Lm != INF and peak > Lm:
        width = max(width, peak - Lm)
    scales = [dist, width, 1 / st]
    if h > 0:
        scales += [h / mu_e, h / (st * dist * mu_e)]
    far = max(dist, 64 / st) * 4
    if peak is not None:
        far = max(far, peak + 64 * width)
    L = pre * quad_ts(f, panels(Lm, scales, far, peak, width, 2), what)
    if Lm == INF:
        c = far
        while mpmath.exp(-st * c) / (st * (c - dist) ** 2) > mpf("1e-40") * L / pre:
            c *= 2
        end = c
    else:
        end = Lm
    L2 = pre * quad_gl(f, panels(end, scales, end, peak, width, 3), L / pre)
    agree(what, L, L2)
    # Conventions: the same radiance through N, L = sigma_s/(4 pi) I0 sigma_t N(T, g, r, S),
    # T = sigma_t |l|, g = e.l/|l|, r = (n.l/|l|)/mu_e, S = sigma_t length.
    T, g, r = st * dist, el / dist, (h / dist) / mu_e
    S = INF if Lm == INF else st * Lm
    peakN, widthN, scalesN = N_features(T, g, r, S)
    N = quad_ts(N_integrand(T, g, r), panels(S, scalesN, N_far(T, g, peakN, widthN), peakN, widthN, 2), what + " via N")
    agree(what + " vs sigma_t N(T, g, r, S)", pre * st * N, L)
    base["L"] = L
    return base


# --------------------------------------------------------------------------------------------
# The same radiance with a Henyey-Greenstein phase function (docs/PHYSICS.md 1.4):
#   p_g(theta) = (1 - g^2) / (4 pi (1 + g^2 - 2 g cos theta)^{3/2}),
# theta between the light's propagation direction at the point (light -> point) and the
# direction from the point to the viewer; g > 0 forward.

def hg_psi(g, cos_theta):
    """4 pi p_g(theta)."""
    g = mpf(g)
    den = 1 + g * g - 2 * g * cos_theta
    return (1 - g) * (1 + g) / (den * mpmath.sqrt(den))


def hg_airlight_integral(g, sigma_t, prefactor, D, cos_g, sin_g, s, method="ts", estimate=None):
    """prefactor * int_0^s psi_g(theta(x)) e^{-sigma_t (x + d)} / d^2 dx, cos theta = (D cos gamma - x)/d;
    the panels of airlight_integral (the phase's complex singularities, at x - D cos gamma =
    +-i D sin gamma (1 + g^2)/(1 - g^2), lie farther from the ray than those of 1/d^2)."""
    sigma_t = mpf(sigma_t)
    xc, b = D * cos_g, D * sin_g

    def f(x):
        d2 = (x - xc) ** 2 + b * b
        d = mpmath.sqrt(d2)
        return hg_psi(g, (xc - x) / d) * mpmath.exp(-sigma_t * (x + d)) / d2
    peak = xc if xc > 0 else None
    length = INF if s == INF else mpf(s)
    width = b
    if peak is not None and length != INF and peak > length:
        width = max(b, peak - length)
    if peak is not None and width == 0:
        raise ReferenceError("airlight: the view ray runs through the light")
    scales = [D, b]
    if sigma_t > 0:
        scales.append(1 / sigma_t)
    far = max(D, 64 / sigma_t if sigma_t > 0 else D) * 4
    if peak is not None:
        far = max(far, peak + 64 * width)
    if method == "ts":
        pts = panels(length, scales, far, peak, width if peak is not None else None, ratio=2)
        return prefactor * quad_ts(f, pts, "HG airlight integral")
    if length == INF:
        c = far
        while mpmath.exp(-sigma_t * c) * hg_psi(g, -1 if g < 0 else 1) / ((c - xc) ** 2 + b * b) > mpf("1e-40") * estimate / prefactor:
            c *= 2
        end = c
    else:
        end = length
    pts = panels(end, scales, end, peak, width if peak is not None else None, ratio=3)
    return prefactor * quad_gl(f, pts, estimate / prefactor)


def hg_airlight_xi(g, sigma_t, prefactor, D, gamma, s):
    """The third route, through Sun et al. 2005's substitution, in which the scattering angle
    is 2 xi: prefactor (2/h) e^{-sigma_t D cos gamma} int_{gamma/2}^{v1} psi_g(2 xi)
    e^{-u tan xi} dxi, u = sigma_t h, h = D sin gamma, v1 = pi/4 + atan((s - D cos gamma)/h)/2."""
    D, gm = mpf(D), mpf(gamma)
    h = D * mpmath.sin(gm)
    u = mpf(sigma_t) * h
    v1 = mp.pi / 2 if s == INF else mp.pi / 4 + mpmath.atan((mpf(s) - D * mpmath.cos(gm)) / h) / 2
    v2 = gm / 2
    off = mpf(sigma_t) * D * mpmath.cos(gm)

    def f(xi):
        return hg_psi(g, mpmath.cos(2 * xi)) * mpmath.exp(-off - u * mpmath.tan(xi))
    # panels: a geometric ladder towards pi/2 (the e^{-u tan xi} layer) and away from the ends
    pts = set([v2, v1])
    for k in range(1, 200):
        x = v1 - (v1 - v2) / mpf(2) ** k
        if x <= v2 or (v1 - x) < mpf(10) ** -40:
            break
        pts.add(x)
    for k in range(1, 60):
        x = v2 + (v1 - v2) / mpf(2) ** k
        if x - v2 < mpf(10) ** -40:
            break
        pts.add(x)
    return prefactor * 2 / h * quad_ts(f, sorted(pts), "HG airlight in xi")


def hg_airlight_case(phase_g, sigma_s, sigma_a, intensity, distance, gamma, length):
    """hg_airlight_integral by tanh-sinh and by Gauss-Legendre, and through the xi form (theta = 2 xi)."""
    ss, st = mpf(sigma_s), mpf(sigma_s) + mpf(sigma_a)
    D, gm = mpf(distance), mpf(gamma)
    pre = ss / (4 * mp.pi) * mpf(intensity)
    L = hg_airlight_integral(phase_g, st, pre, D, mpmath.cos(gm), mpmath.sin(gm), length, "ts")
    L2 = hg_airlight_integral(phase_g, st, pre, D, mpmath.cos(gm), mpmath.sin(gm), length, "gl", L)
    what = "hg_airlight(%r, %r, %r, %r, %r, %r, %r)" % (phase_g, sigma_s, sigma_a, intensity, distance, gamma, length)
    agree(what, L, L2)
    if gm > 0 and gm < mp.pi:
        agree(what + " vs the xi form (theta = 2 xi)", hg_airlight_xi(phase_g, st, pre, D, gamma, length), L)
    return {"quantity": "airlight", "phase_g": phase_g, "sigma_s": sigma_s, "sigma_a": sigma_a, "intensity": intensity,
            "distance": distance, "gamma": gamma, "length": length, "L": L}


def hg_near_light_case(phase_g, sigma_s, sigma_a, intensity, normal, eye_dir, light_pos, length):
    """near_light_case with the phase: cos theta(x) = -(x + e.l)/d(x) (the light propagates along
    P - l = -(x e + l), the viewer lies along +e). Second route Gauss-Legendre on other panels;
    for a light on the plane (r = 0) also the anisotropic airlight with D = |l|,
    cos gamma = -e.l/|l|."""
    n, e = unit(normal), unit(eye_dir)
    l = [mpf(x) for x in light_pos]
    ss, st = mpf(sigma_s), mpf(sigma_s) + mpf(sigma_a)
    mu_e, hgt = dot(n, e), dot(n, l)
    what = "hg_near_light(%r, %r, %r, %r, %r, %r, %r, %r)" % (phase_g, sigma_s, sigma_a, intensity, normal, eye_dir,
                                                              light_pos, length)
    if not mu_e > 0:
        raise ReferenceError(what + ": the viewer is below the surface")
    base = {"quantity": "near_light", "phase_g": phase_g, "sigma_s": sigma_s, "sigma_a": sigma_a,
            "intensity": intensity, "normal": list(normal), "eye_dir": list(eye_dir), "light_pos": list(light_pos),
            "length": length}
    if hgt < 0:
        base["L"] = mpf(0)
        return base
    el = dot(e, l)
    cross = [e[1] * l[2] - e[2] * l[1], e[2] * l[0] - e[0] * l[2], e[0] * l[1] - e[1] * l[0]]
    b2 = dot(cross, cross)
    dist = mpmath.sqrt(dot(l, l))
    pre = ss / (4 * mp.pi) * mpf(intensity)

    def f(x):
        d2 = (x + el) ** 2 + b2
        d = mpmath.sqrt(d2)
        k = d * (x * mu_e) / (x * mu_e + hgt) if hgt > 0 else d
        return hg_psi(phase_g, -(x + el) / d) * mpmath.exp(-st * (x + k)) / d2
    peak = -el if el < 0 else None
    width = mpmath.sqrt(b2)
    Lm = INF if length == INF else mpf(length)
    if peak is not None and Lm != INF and peak > Lm:
        width = max(width, peak - Lm)
    scales = [dist, width, 1 / st]
    if hgt > 0:
        scales += [hgt / mu_e, hgt / (st * dist * mu_e)]
    far = max(dist, 64 / st) * 4
    if peak is not None:
        far = max(far, peak + 64 * width)
    L = pre * quad_ts(f, panels(Lm, scales, far, peak, width, 2), what)
    if Lm == INF:
        c = far
        while mpmath.exp(-st * c) * hg_psi(phase_g, -1 if phase_g < 0 else 1) / (st * (c - dist) ** 2) > mpf("1e-40") * L / pre:
            c *= 2
        end = c
    else:
        end = Lm
    L2 = pre * quad_gl(f, panels(end, scales, end, peak, width, 3), L / pre)
    agree(what, L, L2)
    if hgt == 0:
        cg = -el / dist
        A = hg_airlight_integral(phase_g, st, pre, dist, cg, mpmath.sqrt((1 - cg) * (1 + cg)), length, "ts")
        agree(what + " vs the anisotropic airlight (r = 0)", A, L)
    base["L"] = L
    return base


# --------------------------------------------------------------------------------------------
# Surfaces lit through the medium (Sun et al. 2005; docs/PHYSICS.md 1.5). T = sigma_t D,
# theta = angle between the normal (n = 1) or the mirror direction (Phong exponent n) and the
# direction from the surface point to the light:
#   G_n(T, theta) = int_0^pi A(T, gamma) sin(gamma) K_n(theta, gamma) dgamma
#   A sin(gamma)  = 2 Im[exp(-T e^{i gamma}) E_1(T (1 - e^{i gamma}))]      (pi - gamma at T = 0)
#   K_n           = int_0^{2 pi} max(cos(theta) cos(gamma) + sin(theta) sin(gamma) cos(phi), 0)^n dphi

def surface_incident_sin(T, gamma):
    """A(T, gamma) sin(gamma) from the complex exponential integral."""
    if T == 0:
        return mp.pi - gamma
    e = mpmath.expj(gamma)
    return 2 * mpmath.im(mpmath.exp(-T * e) * mpmath.e1(T * (1 - e)))


def surface_incident_sin_xi(T, gamma):
    """The same from its definition: 2 int_{gamma/2}^{pi/2} exp(-T (cos(gamma) + sin(gamma) tan(xi))) dxi."""
    c, s = mpmath.cos(gamma), mpmath.sin(gamma)
    return 2 * mp.quad(lambda xi: mpmath.exp(-T * (c + s * mpmath.tan(xi))), [gamma / 2, mp.pi / 2], method="tanh-sinh")


def surface_kernel(n, theta, gamma):
    """K_n in closed form: 2 pi (a^2-b^2)^{n/2} P_n(a/sqrt(a^2-b^2)) for the whole ring inside the lobe,
    2 B(n+1, 1/2) c^{n+1/2} (2b)^{-1/2} 2F1(1/2, 1/2; n+3/2; c/(2b)), c = a + b, where it crosses the edge."""
    a = mpmath.cos(theta) * mpmath.cos(gamma)
    b = mpmath.sin(theta) * mpmath.sin(gamma)
    if b <= 0:
        return 2 * mp.pi * a ** n if a > 0 else mpf(0)
    if a >= b:
        r = mpmath.sqrt((a - b) * (a + b))
        return 2 * mp.pi * r ** n * mpmath.legenp(n, 0, a / r)
    if a <= -b:
        return mpf(0)
    c = a + b
    return 2 * mpmath.beta(n + 1, mpf(1) / 2) * c ** (n + mpf(1) / 2) / mpmath.sqrt(2 * b) * \
        mpmath.hyp2f1(mpf(1) / 2, mpf(1) / 2, n + mpf(3) / 2, c / (2 * b))


def surface_kernel_phi(n, theta, gamma):
    """K_n by tanh-sinh quadrature over the part of the ring inside the lobe."""
    a = mpmath.cos(theta) * mpmath.cos(gamma)
    b = mpmath.sin(theta) * mpmath.sin(gamma)
    if a <= -b:
        return mpf(0)
    end = mp.pi if a >= b else mpmath.acos(-a / b)
    pts = [mpf(0)] + [k / mpmath.sqrt(n) for k in (1, 4, 16) if k / mpmath.sqrt(n) < end] + [end]  # the peak at phi = 0
    return 2 * quad_ts(lambda p: (a + b * mpmath.cos(p)) ** n, pts, "K_n(%d, %s, %s)" % (n, theta, gamma))


def surface_breaks(n, T, theta, ratio):
    g1 = abs(mp.pi / 2 - theta)
    pts = {mpf(0), mp.pi, g1, mp.pi - g1}
    if n > 1:
        w = 1 / mpmath.sqrt(n)
        pts.add(theta)
        for x in ladder(w / 4, 2 * mp.pi, ratio):
            pts.update((theta - x, theta + x))
    if T > 0:
        pts.update(ladder(1 / (4 * T), mp.pi, ratio))
    pts = sorted(p for p in pts if 0 <= p <= mp.pi)
    if ratio != 2:  # the second route: every panel split once more, off the first route's points
        pts = sorted(set(pts) | set(a + (b - a) * mpf(3) / 7 for a, b in zip(pts, pts[1:])))
    return pts


def surface_case(quantity, sigma_s, sigma_a, intensity, distance, theta, exponent):
    """E_ss (quantity "surface", exponent 1) or S_n (quantity "surface_specular") in W/m^2."""
    st = mpf(sigma_s) + mpf(sigma_a)
    T, th, n = st * mpf(distance), mpf(theta), exponent
    pre = mpf(sigma_s) * mpf(intensity) / (4 * mp.pi * mpf(distance))
    what = "%s(%r, %r, %r, %r, %r, %r)" % (quantity, sigma_s, sigma_a, intensity, distance, theta, exponent)
    f = lambda g: surface_incident_sin(T, g) * surface_kernel(n, th, g)
    # Two tanh-sinh routes on different panels: K_n has (gamma - gamma_1)^{3/2} terms where the
    # ring of directions starts to cross the lobe's edge, and A sin(gamma) a u ln u term at
    # gamma = 0, on which Gauss-Legendre converges slowly and can stop early (it agreed to only
    # 1e-15 here); tanh-sinh is exact to working precision at such panel ends.
    G = quad_ts(f, surface_breaks(n, T, th, 2), what)
    G2 = quad_ts(f, surface_breaks(n, T, th, 3), what + " (second panels)")
    agree(what, G, G2, SURFACE_AGREE_REL)
    # The closed forms against their definitions, at the lobe's centre and off it.
    for g in (th / 2 + mpf("0.1"), th + 1 / mpmath.sqrt(4 * n), mp.pi - th / 3):
        if 0 < g < mp.pi:
            agree(what + " vs K_n by phi quadrature", surface_kernel(n, th, g), surface_kernel_phi(n, th, g))
            agree(what + " vs A sin(gamma) by xi quadrature", surface_incident_sin(T, g), surface_incident_sin_xi(T, g))
    if n == 1 and T < mpf("0.002"):  # the limit sigma_t -> 0 in closed form (E: complete elliptic, 2nd kind)
        G0 = quad_ts(lambda g: surface_incident_sin(0, g) * surface_kernel(1, th, g), surface_breaks(1, 0, th, 2), what)
        with mp.workdps(CLOSED_DPS):  # mpmath's ellipe(m) loses ~20 digits as m -> 1 (theta -> pi/2)
            closed = 2 * mp.pi * (mpmath.cos(th) + mpmath.ellipe(mpmath.sin(th) ** 2))
        agree(what + " at T = 0 vs 2 pi (cos theta + E(sin theta))", G0, +closed)
    out = {"quantity": quantity, "sigma_s": sigma_s, "sigma_a": sigma_a, "intensity": intensity,
           "distance": distance, "theta": theta}
    if quantity == "surface_specular":
        out["exponent"] = exponent
    out["G"] = G
    out["E"] = pre * G
    return out


# --------------------------------------------------------------------------------------------
# Inputs. The corners are the hard edges of the tables' domains; the other points were drawn
# at random once (log-uniform where the quantity varies over decades) and are fixed here.

PIO4 = 0.7853981633974483          # the double nearest pi/4
PIO2 = 1.5707963267948966          # the double nearest pi/2 (6.1e-17 below it)
PIO2_M6 = 1.5707953267948966       # the double nearest pi/2 - 1e-6
PI = 3.141592653589793             # the double nearest pi

F_CORNER_U = [0.0, 1e-09, 0.0001, 0.5, 10.0, 200.0, 10000.0]
F_CORNER_V = [0.0, 1e-09, 0.001, PIO4, PIO2_M6, PIO2]
F_CORNERS = [(u, v) for u in F_CORNER_U for v in F_CORNER_V]

# Hard points of N added to the random ones: g = -1 exactly (finite only for S < T), g = 1
# thick, the peak at g -> -1 narrower (width T sqrt(1 - g^2) = 1.4e-3 T), thinner slabs,
# a thinner boundary layer, r = 0 thick at large T.
N_EXTRA = [
    (2.0, -1.0, 0.5, 1.5),
    (2.0, -1.0, 0.0, 1.9),
    (0.5, 1.0, 1.0, INF),
    (3.0, 1.0, 0.0, INF),
    (1.0, -0.999999, 0.0, INF),
    (1.0, -0.999999, 0.3, INF),
    (0.5, -0.5, 0.1, 1e-09),
    (50.0, 0.9, 1e-06, INF),
    (20.0, 0.5, 0.0, INF),
]

# Airlight cases added: the light exactly behind the viewer (gamma = the double pi), looking
# straight at the light with the ray ending before it (gamma = 0), a long ray past the light.
AIRLIGHT_EXTRA = [
    (0.5, 0.0, 1.0, 4.0, PI, 10.0),
    (0.3, 0.2, 1.0, 4.0, 0.0, 3.0),
    (0.02, 0.01, 10.0, 5.0, 0.01, 200.0),
]

# Near-light cases added: the light on the surface plane (h = 0: the whole light path
# attenuates), a tilted surface, a grazing view (mu_e = 0.05).
NEAR_LIGHT_EXTRA = [
    (1.0, 0.5, 1.0, (0.0, 0.0, 1.0), (0.6, 0.0, 0.8), (1.0, 0.5, 0.0), INF),
    (0.7, 0.3, 2.0, (0.6, 0.0, 0.8), (0.0, 0.0, 1.0), (0.3, 0.4, 1.5), 2.0),
    (2.0, 1.0, 1.0, (0.0, 0.0, 1.0), (0.99874921777190895, 0.0, 0.05), (0.5, 0.1, 0.3), INF),
]
F_INTERIOR = [
    (14.546098765419181, 1.298931299128533),
    (9.328482817416464, 0.35943381668820956),
    (1.2676402800333875, 0.6516994766536627),
    (4.429768304800355, 0.3898232347963878),
    (10.57477822642536, 0.1325036752378245),
    (8.626885371231282, 0.8395179074089546),
    (0.0011042991434438581, 0.03687651026104572),
    (11.939857552272082, 0.9069060699684839),
    (5.049815729669634, 1.28266761749233),
    (0.012195326503747063, 0.6640057402456641),
    (10.315069433436326, 1.3045221272051566),
    (19.706634880237676, 0.7931825369761308),
    (0.0036046363269964916, 0.7610195324339553),
    (4.452188382444953, 0.5874574201118038),
    (0.45777462085970433, 1.0893059255913462),
    (0.5080705737523483, 1.4309459564911144),
    (0.9907572739720538, 0.7306841041777089),
    (0.041017768994559854, 1.2702787695024291),
    (0.01045509971463583, 0.7185977894070622),
    (12.330400797120294, 1.4185442311680816),
    (4.933185233819167, 1.5199045474346746),
    (2.1947929282342113, 1.0588092042530772),
    (2.7605148679296665, 0.11288366449774903),
    (0.0734369142904279, 0.15940459836143353),
    (17.23759534743846, 0.4292220417708671),
    (0.5975513866032078, 0.26801163850075294),
    (10.77458464633011, 1.5425928864681409),
    (18.828830598603783, 0.1582636024087092),
    (0.015955689195973212, 1.3826695706713266),
    (14.079351988775539, 0.09455163468891963),
    (0.0885813114243652, 1.4807328739722552),
    (21.135162395798407, 1.1925212049927336),
    (0.0044564508318487425, 1.238205821067834),
    (0.8275527256760062, 1.466054335283479),
    (3.294486384574382, 0.20692732741552308),
    (34.53954056679045, 1.5500795656554682),
    (0.012719229948141694, 0.7754575075294073),
    (78.13897146610462, 1.0616803075070225),
    (4.765987809252692, 1.3987901549460806),
    (13.683335825788902, 0.08855161029377556),
    (14.411866422958656, 0.7212220120530667),
    (14.311806011048375, 0.11636032768599744),
    (0.004307580647034586, 0.16933733484750568),
    (1.2161793971647679, 0.008527049003358218),
    (15.131864484920692, 0.7785035594809595),
    (0.005313265357643558, 1.29072720142414),
    (17.79770446756924, 0.41386719650655807),
    (0.1665543560954074, 0.7993448573654058),
    (0.8132131173623525, 0.23336397177559218),
    (61.83399806386564, 0.42162050638296555),
    (8.683403478630902, 0.7893211948452958),
    (0.15076977197997096, 0.19024727159061386),
    (5.647789585614158, 0.7017827167675985),
    (1.9117058743282396, 0.42347534646169166),
    (0.17341890011470343, 0.49588958362237384),
    (0.05079830719335329, 0.21729597847677717),
    (1.780977681401681, 0.9944236983350496),
    (12.94510136125268, 0.7058290077444642),
    (0.4591916917023564, 0.9261373437784162),
    (19.57672005558433, 0.18598558758703618),
    (0.4182116738909763, 0.8939600581179397),
    (21.226876455090316, 0.27531801409198886),
    (12.801855505271707, 1.0885051436798487),
    (33.54842248847168, 1.5398294697652215),
    (23.971371725618553, 0.8429961393411683),
    (0.21958699993396424, 1.3631158951271927),
    (16.406771071274942, 0.6208874347058206),
    (10.505766898219772, 0.8499705695923166),
    (85.79030972354745, 0.7202920587479635),
    (3.054992812079751, 0.5625522528123408),
    (67.15584165702704, 0.9209763582009238),
    (0.1622953711332661, 1.1576687898724636),
    (0.8001874575451999, 0.4934037301482846),
    (10.864586087189261, 0.7055754555108469),
    (67.29269980465402, 0.01570486567614841),
    (0.05656805683392999, 1.401766123471432),
    (0.012663099563445857, 1.3160776811348252),
    (17.565192171839968, 1.5505179840553371),
    (0.014818260180527155, 1.2920292463483873),
    (27.935012400223314, 1.285382860165299),
    (0.2604367394004687, 1.3587710782750697),
    (12.521844088615007, 1.5222032140277004),
    (5.604734986611753, 1.0801724687178216),
    (19.89800894912669, 1.329981779091866),
    (13.541655235833883, 1.070717811503418),
    (38.842241208313844, 0.7961747410470783),
    (19.448252705894046, 1.2701088125618545),
    (0.003495331806289549, 0.2140486302598268),
    (16.268062924362216, 1.2106900721582141),
    (32.96488277067941, 0.7765767336442331),
    (1.972413310533192, 1.0924585621404976),
    (0.47923778484510327, 1.5313839844795147),
    (5.44025670120643, 1.0106873640075034),
    (0.39072241051495943, 1.28923262942274),
    (8.862625626695806, 1.069379923320148),
    (16.54478531641272, 0.08098927950710125),
    (0.07920594274971382, 1.1242903410695884),
    (3.294078124565563, 1.3824802232559168),
    (9.765234571335407, 0.6648106424395258),
    (4.974026078662739, 0.05632278099348687),
    (0.020315490138784368, 0.8277675282025215),
    (1.5652597367136867, 0.7556663573163226),
    (1.1476182922489686, 1.1003111300230897),
    (0.05255061786314928, 1.4304458068555734),
    (18.896416945058792, 0.05775829213287),
    (0.05893366972784545, 0.6501778501172671),
    (0.001296078888162759, 1.4597738442391281),
    (0.01557293317064436, 1.2587201491989404),
    (9.152484425217475, 0.13063283193402989),
    (1.1823385810586506, 0.242554519025429),
    (1.4729575461927946, 1.0136520573706533),
    (7.449602105452892, 0.06699230671725366),
    (1.059416913108684, 1.305415890222066),
    (8.047946689870804, 0.19175444341880155),
    (16.21699944391891, 1.5185857454662335),
    (14.2689610038847, 0.41816041158909606),
    (0.006053428802240119, 0.6453532887679381),
    (14.626078068009553, 1.1857672547557578),
    (7.243279012932264, 0.7908957372302441),
    (11.686383202353515, 0.1636277733814386),
]
N_POINTS = [
    (0.001, 0.5, 1.0, INF),
    (50.0, 0.9, 0.0001, INF),
    (2.0, -0.999, 1.0, INF),
    (2.0, -0.999, 0.0, 10.0),
    (0.5, 1.0, 1.0, 10.0),
    (0.5, -0.5, 1000.0, INF),
    (5.0, 0.0, 0.0, 0.0001),
    (1.0, 0.3, 2.0, 1e-06),
    (20.0, -0.9, 0.01, 30.0),
    (0.011112516769164844, -0.44358043222380983, 16.65691340975257, INF),
    (0.6880928196749914, -0.5135797977218153, 0.00330046393703965, 2.797902111165944),
    (28.79405660914118, -0.3065813745811372, 0.0, 0.07312957023201032),
    (29.826913238289308, -0.5356444520993274, 20.11014350447451, 11.528979975780103),
    (1.2185123169734502, 0.07897651103983483, 0.029992257497085544, 0.0031571979883558803),
    (0.01155737200647867, -0.45360268645122725, 0.16657127211175826, INF),
    (0.0161113166159232, 0.8906076106030048, 12.372530291440254, 4.687533161145944),
    (0.1668381375532549, 0.6022163923984811, 0.003523787275943381, 0.0519361684620095),
    (2.295637531653158, -0.06288179041901909, 0.0, 13.920589895776127),
    (0.15528910951295066, 0.0411678317406583, 0.06974084650793254, 13.965360646011426),
    (0.016703163729560357, -0.939114297004175, 39.99495905929184, 0.0021939078793665155),
    (1.9089207336932963, -0.8904620772902835, 0.0, INF),
    (0.7931487541775007, -0.7975363529193407, 43.256052681352735, 0.010850538814763243),
    (0.26141870257535754, 0.5693043905879203, 4.60908899673296, 0.0034946863573905446),
    (0.14320331806046596, -0.918074710957223, 1.9684227709521498, INF),
    (7.9062603377118785, 0.5912539554478535, 79.27080040314183, 0.308526510711852),
    (5.735453569027494, -0.3523660502156606, 0.013434335489333874, INF),
    (3.112466499369731, -0.4151045577771416, 0.18863856287351086, INF),
    (2.3997464019440584, -0.06839996853672847, 5.539752587991745, INF),
    (4.443130499910825, -0.2797856103786668, 1.4119536760247404, INF),
    (0.012270117694527514, -0.7332862071784487, 1.4454249603994322, 0.0022356857034518014),
    (56.80933261850829, -0.8962563763991063, 1.5718610172883258, 0.0011484544126221198),
    (0.010156255629583662, 0.6362571056006847, 0.0, INF),
    (0.010455574777154544, -0.37624785685776174, 95.58743655913491, INF),
    (0.4247105903560623, -0.3720540048528892, 12.721061712161498, 0.019159199752295235),
    (29.008756214418145, -0.3354555494215655, 54.231790207496836, INF),
    (0.09907684627632686, -0.247248396858871, 0.016097424855083548, INF),
    (0.014311123641013583, -0.03572257680122182, 0.5745428691331473, INF),
    (0.0394629031629606, -0.5687373747878596, 5.826813294346146, 18.563870477459716),
    (7.0450133006541735, 0.13386468743899993, 0.8188596846426992, INF),
    (0.010654169847139126, -0.5987299918752605, 6.420036668462037, 24.069235512571332),
    (0.28920024291277546, 0.7996158297172284, 5.510347301481435, INF),
    (0.01442666324989428, 0.6738622417074209, 0.0028628930239612367, 20.25735833581568),
    (2.8836410353134236, -0.36143895132749737, 0.0, 0.013448284867111297),
    (1.1751054940150742, 0.25014612706600814, 0.477178679957144, 90.82544084443066),
    (0.38059125728826965, -0.38062642803153435, 6.237722124091527, INF),
    (17.692957516146553, 0.916228593404141, 0.04551743528050308, 0.005802091561019859),
    (0.0766617017448433, -0.29761494530319765, 0.02966254404529836, 0.1044943763065958),
    (0.3330281140382842, -0.7879340707111738, 0.9520692269192286, INF),
    (14.069031244137342, -0.06872701825632566, 0.0831898349784342, 0.43487296366661266),
    (0.7525415486661621, -0.7173103661956526, 0.009234668287570785, 1.2446576195549786),
    (26.964613381983824, 0.13855349913602555, 0.004689536675387003, INF),
    (16.19192769655937, 0.69102071173832, 0.006542365495104507, 0.535354676508618),
    (3.9026319195286456, -0.5710710249305793, 0.0, 0.0014192817068209435),
    (0.17309746471521362, -0.6687968928200596, 7.491398642522881, INF),
    (90.76398044211192, -0.3231744108442288, 0.006290623364147899, 0.014124637251245145),
    (8.454380219338464, 0.1928930648101881, 0.06071675081181993, INF),
    (7.191060913817278, -0.5552123545111111, 0.0010610394039007832, INF),
    (0.1343851496661395, -0.04762378000077094, 28.585085247666804, INF),
    (1.240440066685464, -0.20782021303470488, 60.020116573380754, 0.013402285884021448),
    (9.923623656204446, -0.46755261136291404, 0.6376306318454629, 1.157066232178753),
    (0.34019297850191327, 0.6840827539574519, 0.0033229361556504776, 0.8629150724619179),
    (1.668239203705241, -0.6808723935197698, 0.018384538533475075, 8.542034296475645),
    (25.265614144862624, -0.742017725019656, 0.04457845751630847, 0.005460798994997552),
    (1.3941589543993747, 0.4107835248230072, 3.5450360552843603, INF),
    (0.10256963611607355, 0.5366160057070146, 0.01864726040292921, INF),
    (3.1890506978879207, 0.6665477340248764, 42.10409656850779, 0.00285368656129556),
    (1.0188810610999102, 0.4408711871449835, 0.016490052648224167, 6.5466174266341906),
    (3.5196378763827276, 0.6686026902945117, 0.0016509042131630956, 0.002436922873263307),
    (9.778110338717369, -0.12597744953320966, 0.009185405553812559, 0.020896777263539848),
    (2.88286383864777, -0.8309182462972371, 40.21171147079795, INF),
    (0.3043117878035845, 0.5528525203938477, 2.2524385104380595, INF),
    (0.10972180316657416, -0.8961489931194088, 0.2444614543554708, 1.2242790539864943),
    (0.5260628471610158, 0.39431379652041176, 0.0, 0.01491451231836974),
    (0.33545251571370593, 0.28719511210313775, 84.31503736057599, 16.035293021915496),
    (41.25598656389313, -0.8309013690865772, 0.0047968306934342494, INF),
    (0.8820111865642238, -0.3819529678413598, 0.7401629366905663, INF),
    (0.012263996604784342, 0.3204227297900635, 0.08989077404770246, 0.08237854307652802),
    (5.747038347048788, -0.7347377834702319, 2.8336324825999424, 17.933442451500028),
    (0.017078110902475623, 0.31235072184897983, 0.4696050217613329, 0.13672745581151932),
]
AIRLIGHT_CASES = [
    (0.05, 0.01, 100.0, 10.0, 0.001, 20.0),
    (0.5, 0.0, 1.0, 4.0, 2.8415926535897933, 10.0),
    (0.5, 0.0, 1.0, 4.0, 3.1315926535897933, 10.0),
    (0.2, 0.1, 5.0, 3.0, 3.141591653589793, 7.0),
    (1.0, 1.0, 1.0, 2.0, 0.7, 1e-06),
    (1e-06, 0.0, 1.0, 5.0, 1.0, 30.0),
    (3.0, 2.0, 1.0, 0.01, 2.0, 5.0),
    (0.1, 0.05, 1.0, 50.0, 0.05, 45.0),
    (0.8981879253440267, 0.1438279367242212, 1.0, 15.178583394221011, 1.801030044293104, 2.1110604577950327),
    (0.02138837661257241, 0.03416424586822207, 1.0, 0.6241574397476817, 2.4901345922839653, 19.137159675953484),
    (0.01751995274370203, 0.03484286177200745, 1.0, 0.2951259766371278, 0.8359228340845585, 3.479645420508672),
    (0.5691873172582487, 0.2888113596843166, 1.0, 15.894932396513214, 3.086421079197488, 0.4094387581483732),
    (0.3786555386019801, 0.056694203944363766, 1.0, 0.11448937568256799, 0.6348575051199703, 41.58319147862931),
    (0.1780802654537544, 0.06635378465345473, 1.0, 4.870769136030807, 0.524800716641528, 24.522654939998926),
    (0.2395649556414385, 0.442562175972927, 1.0, 1.4642031262230173, 2.1835722659996275, 10.234072499080746),
    (0.02109915017952441, 0.027576843400446267, 1.0, 1.4533703378028568, 2.3474977301249824, 0.4528392454778905),
    (0.018987068602529904, 0.0319997928944712, 1.0, 0.37820349117095714, 2.4921175942587883, 0.5495736434051227),
    (0.17937422400543365, 0.015163440369070079, 1.0, 8.563777099764152, 1.4260187210825275, 0.19700334826036403),
    (1.9236109504018943, 2.128538972411524, 1.0, 0.2685329137620468, 0.7207842153176794, 14.065143040436926),
    (0.033035396495208924, 0.03422343937741914, 1.0, 0.5063992786348813, 0.7772510277697448, 3.9278766931920726),
    (1.4075589844059895, 2.5140157674255295, 1.0, 30.635179332079208, 0.12414936593984566, 2.59378511760252),
    (0.8402031740923294, 0.9550435782571696, 1.0, 13.886267098493656, 3.076339730647048, 0.14282785223545022),
    (0.08908451928305307, 0.055244786111190235, 1.0, 8.40167936322806, 0.1695120584397844, 4.675511393664134),
]
NEAR_LIGHT_CASES = [
    (2.0, 0.5, 1.0, (0.0, 0.0, 1.0), (0.2873478855663454, 0.0, 0.9578262852211513), (0.5, 0.2, 0.01), INF),
    (1.0, 0.2, 1.0, (0.0, 0.0, 1.0), (0.0, 0.0, 1.0), (0.0, 0.0, 2.0), 5.0),
    (0.5, 0.5, 1.0, (0.0, 0.0, 1.0), (0.9998000599800071, 0.0, 0.01999600119960014), (-3.0, 0.0, 0.05), INF),
    (1.0, 1.0, 1.0, (0.0, 0.0, 1.0), (0.19518001458970663, 0.09759000729485331, 0.9759000729485331), (1.0, 1.0, -0.5), 3.0),
    (1.0, 1.0, 1.0, (0.0, 1.0, 0.0), (0.09534625892455922, 0.9534625892455922, 0.28603877677367767), (2.0, 3.0, 1.0), 1e-05),
    (1.0, 0.01, 1.0, (0.0, 0.0, 1.0), (0.4472135954999579, 0.0, 0.8944271909999159), (0.0, 40.0, 30.0), INF),
    (0.04968216301022346, 0.12157167994586196, 1.0, (0.0, 0.0, 1.0), (0.9432927339329105, 0.27433089273793887, 0.18692613353670218), (0.8505740305414525, -0.44607828205358774, 0.3509960908003635), 0.07582407379528842),
    (0.03969949695268087, 0.11613570762225157, 1.0, (0.0, 0.0, 1.0), (-0.14891655124787942, 0.00934666290504913, 0.988805592953932), (-0.16096015772759337, 0.11003438645488826, 0.06446218786149766), INF),
    (8.293295934569556, 14.969890161242088, 1.0, (0.0, 0.0, 1.0), (0.6253134509346558, 0.4946562329026227, 0.6035712876958098), (0.3042411182141267, -0.014048970939085024, 0.36095867744950405), 1.076214855739866),
    (0.2316397067533543, 0.42609193780688903, 1.0, (0.0, 0.0, 1.0), (0.3240518222586864, 0.06954496242390136, 0.943479684302891), (-0.8928608944357209, 0.7352764388745388, 0.282951605313864), INF),
    (3.1569114449811653, 4.666844308983541, 1.0, (0.0, 0.0, 1.0), (0.12396325813815912, -0.4847364208738208, 0.8658312265737533), (0.49747117033063065, 0.024491239199269616, 0.8148729205095515), 16.98365588983211),
    (0.2744853514219877, 0.2189032480043551, 1.0, (0.0, 0.0, 1.0), (-0.16578682949981102, 0.8790342364977133, 0.4470050762902843), (-0.3509810204820688, 0.5823277569068659, 0.3335696294733953), INF),
    (2.6630137607400934, 5.8313737472231555, 1.0, (0.0, 0.0, 1.0), (-0.39720781320253296, 0.8104016642706289, 0.4306681967341642), (-2.635850159039837, -5.499900399610788, 3.5123322960419436), INF),
    (2.026989357601982, 5.8412033560089665, 1.0, (0.0, 0.0, 1.0), (-0.7064071447714255, -0.3389646232950626, 0.6213629615372311), (0.30827169541207966, -0.05913058399494523, 0.3106467826534761), 0.0391356115381808),
    (1.12964169570853, 2.9655186989458215, 1.0, (0.0, 0.0, 1.0), (0.051964977352589835, -0.9616685233679495, 0.26924578416764955), (-0.030119873344654186, 0.06330735356665897, 0.15883605511085913), INF),
    (0.06802469730053706, 0.15391521703211875, 1.0, (0.0, 0.0, 1.0), (0.14116394321528103, -0.14003881528824286, 0.9800315665061908), (0.41156959567354257, 0.9071372111972104, 0.4034158496146142), 0.08314745971024526),
    (1.117184372469935, 0.23795155670660087, 1.0, (0.0, 0.0, 1.0), (0.019192058080260317, -0.5925269172634848, 0.8053219959897254), (-0.17525637714283399, 0.134398840695731, 0.034362504034493924), 0.3280584873745441),
    (0.10428053751529592, 0.2695964481331759, 1.0, (0.0, 0.0, 1.0), (-0.1653634994263675, -0.14334262129660427, 0.9757601170253292), (-0.6218391606137195, -0.2894049163945838, 0.11671666909532682), INF),
    (5.675799077090874, 2.539577827693618, 1.0, (0.0, 0.0, 1.0), (0.5426478904034712, -0.6791285966512829, 0.49428495450612436), (-0.09929057041789474, 0.07837348251562438, 0.6052046142113974), INF),
    (0.35693585069216216, 0.8520207846893949, 1.0, (0.0, 0.0, 1.0), (-0.41127918203320285, -0.5613445598501257, 0.7181515992830263), (-0.08918667105420268, 0.0433930926146698, 0.09083565981061824), 0.18389819900131713),
    (9.691564325926894, 19.268290791692518, 1.0, (0.0, 0.0, 1.0), (0.08795362182920068, 0.9713838772912838, 0.22062983330836716), (0.15657923732083967, -0.07102971376577873, 0.25007460521659514), 0.4844940349705861),
]

# The surface terms (surface_ref.json): sigma_t = 1/m exactly, so T = distance, at every
# T x theta x exponent of SURFACE_T, SURFACE_THETA, SURFACE_EXPONENTS, then a few off the grid.
PI = 3.141592653589793             # the double nearest pi (1.2e-16 below it)
SURFACE_T = [0.001, 0.1, 1.0, 10.0, 40.0]
SURFACE_THETA = [0.0, 0.3, PIO2, 2.5, PI]
SURFACE_EXPONENTS = [1, 20, 1000]
SURFACE_INPUTS = [("surface" if n == 1 else "surface_specular", 0.75, 0.25, 100.0, T, th, n)
                  for n in SURFACE_EXPONENTS for T in SURFACE_T for th in SURFACE_THETA] + [
    ("surface", 0.02, 0.005, 3.0, 7.5, 1.2, 1),
    ("surface", 2.0, 1.0, 50.0, 0.004, 3.0, 1),
    ("surface", 0.1, 0.0, 1.0, 0.5, 1e-08, 1),
    ("surface", 0.1, 0.0, 1.0, 0.5, PIO2 + 1e-09, 1),
    ("surface_specular", 0.02, 0.005, 3.0, 7.5, 1.2, 5),
    ("surface_specular", 0.3, 0.2, 10.0, 3.0, 0.01, 100),
    ("surface_specular", 0.3, 0.2, 10.0, 3.0, 1.9, 300),
    ("surface_specular", 0.05, 0.01, 80.0, 12.0, 0.7, 2),
]

# The anisotropic cases: every geometry at every asymmetry of HG_G (hg_ref.json).
HG_G = [-0.9, -0.5, 0.0, 0.3, 0.8, 0.95, 0.99]
HG_AIRLIGHT_GEOMETRIES = [
    (0.05, 0.01, 100.0, 10.0, 0.001, 20.0),      # gamma = 1e-3: the forward glow beside the light
    (0.2, 0.1, 5.0, 3.0, 3.141591653589793, 7.0),  # gamma = pi - 1e-6: the backward direction
    (0.5, 0.0, 1.0, 4.0, 2.8415926535897933, 10.0),
    (0.3, 0.1, 1.0, 2.0, 1.0, INF),                # an infinite ray
    (1e-06, 0.0, 1.0, 5.0, 1.0, 30.0),             # almost clear
    (3.0, 2.0, 1.0, 0.01, 2.0, 5.0),               # dense, light close by
]
HG_NEAR_LIGHT_GEOMETRIES = [
    NEAR_LIGHT_CASES[0],                           # thick, grazing light
    NEAR_LIGHT_CASES[1],                           # a slab seen from straight above the light
    NEAR_LIGHT_EXTRA[0],                           # the light on the plane (r = 0: the airlight identity)
    NEAR_LIGHT_EXTRA[2],                           # grazing view, thick
]
HG_AIRLIGHT_INPUTS = [(g,) + c for g in HG_G for c in HG_AIRLIGHT_GEOMETRIES]
HG_NEAR_LIGHT_INPUTS = [(g,) + c for g in HG_G for c in HG_NEAR_LIGHT_GEOMETRIES]

F_INPUTS = F_CORNERS + F_INTERIOR
N_INPUTS = N_POINTS + N_EXTRA
AIRLIGHT_INPUTS = AIRLIGHT_CASES + AIRLIGHT_EXTRA
NEAR_LIGHT_INPUTS = NEAR_LIGHT_CASES + NEAR_LIGHT_EXTRA

# --check recomputes these (file, index into the inputs above) first: the hard points.
CHECK_FIRST = [
    ("F", F_CORNERS.index((1e-09, PIO2))),        # tail ~ 1e-7092591
    ("F", F_CORNERS.index((10000.0, PIO2_M6))),
    ("F", F_CORNERS.index((200.0, PIO4))),         # tail 3.4e-90
    ("F", F_CORNERS.index((0.0, PIO2))),
    ("F", F_CORNERS.index((0.0001, 0.001))),
    ("N", N_INPUTS.index((50.0, 0.9, 0.0001, INF))),  # boundary layer
    ("N", N_INPUTS.index((2.0, -0.999, 1.0, INF))),   # peak
    ("N", N_INPUTS.index((2.0, -0.999, 0.0, 10.0))),  # peak, r = 0 (airlight identity)
    ("N", N_INPUTS.index((2.0, -1.0, 0.5, 1.5))),     # g = -1
    ("N", N_INPUTS.index((0.5, 1.0, 1.0, 10.0))),     # g = 1
    ("N", N_INPUTS.index((5.0, 0.0, 0.0, 0.0001))),   # S -> 0
    ("airlight", 0),                                  # gamma = 1e-3: narrow peak
    ("airlight", 3),                                  # gamma = pi - 1e-6
    ("airlight", len(AIRLIGHT_CASES)),                # gamma = pi
    ("near_light", 0),
    ("near_light", 3),                                # light below the plane: 0
    ("near_light", 4),                                # normal along y, thin slab
    ("near_light", len(NEAR_LIGHT_CASES)),            # light on the plane
    ("F", len(F_CORNERS)),
    ("N", 9),
    ("hg_airlight", HG_AIRLIGHT_INPUTS.index((0.99,) + HG_AIRLIGHT_GEOMETRIES[0])),   # forward peak beside the light
    ("hg_airlight", HG_AIRLIGHT_INPUTS.index((-0.9,) + HG_AIRLIGHT_GEOMETRIES[1])),   # backward, gamma -> pi
    ("hg_near_light", HG_NEAR_LIGHT_INPUTS.index((0.95,) + HG_NEAR_LIGHT_GEOMETRIES[2])),  # r = 0
    ("surface", SURFACE_INPUTS.index(("surface", 0.75, 0.25, 100.0, 40.0, PI, 1))),  # light behind, dense
]


KINDS = ("F", "N", "airlight", "near_light", "hg_airlight", "hg_near_light", "surface")


def check_order(n):
    """The first n (file, index) pairs: CHECK_FIRST, then the rest of each file spread evenly."""
    order = list(CHECK_FIRST)
    sizes = {"F": len(F_INPUTS), "N": len(N_INPUTS), "airlight": len(AIRLIGHT_INPUTS), "near_light": len(NEAR_LIGHT_INPUTS),
             "hg_airlight": len(HG_AIRLIGHT_INPUTS), "hg_near_light": len(HG_NEAR_LIGHT_INPUTS),
             "surface": len(SURFACE_INPUTS)}
    rest = [(k, i) for k in KINDS for i in range(sizes[k]) if (k, i) not in order]
    rest.sort(key=lambda ki: (ki[1] / sizes[ki[0]], ki[0]))
    return (order + rest)[:n]


# --------------------------------------------------------------------------------------------
# Output

def fmt(x):
    """25 significant digits (mpmath's shortest form: fixed or exponent)."""
    return mpmath.nstr(x, OUT_DIGITS)


def json_number(x):
    return "inf" if x == INF else x


def F_record(p):
    return {"u": p["u"], "v": p["v"], "F": fmt(p["F"]), "tail": fmt(p["tail"])}


def N_record(p):
    return {"T": p["T"], "g": p["g"], "r": p["r"], "S": json_number(p["S"]),
            "N": fmt(p["N"]), "H": fmt(p["H"]), "E": fmt(p["E"])}


def physical_record(c):
    out = {}
    for k, v in c.items():
        if k in ("L", "G", "E"):
            out[k] = fmt(v)
        elif k == "length":
            out[k] = json_number(v)
        else:
            out[k] = v
    return out


F_DEFINITION = "F(u,v)=int_0^v exp(-u tan x) dx; tail=int_v^{pi/2} exp(-u tan x) dx (Sun et al. 2005); u, v doubles taken exactly"
N_DEFINITION = ("N(T,g,r,S)=int_0^S exp(-t-h t/(t+T r))/h^2 dt, h^2=t^2+T^2+2tTg; H=int_0^S h^-2 dt; E=N/H "
                "(Gath 2008 4.2); S='inf' = thick")
PHYSICAL_CONVENTIONS = ("airlight: gamma = angle between view direction and direction viewer->light, "
                        "d(x)^2 = x^2 + D^2 - 2 x D cos(gamma); near_light: plane through origin with outward normal, "
                        "medium below, eye_dir from entry point towards viewer, light_pos relative to entry point, "
                        "length = path inside ('inf' = thick), light below the plane gives 0; isotropic phase 1/(4 pi); "
                        "L in W/(m^2 sr) for intensity I0 in W/sr, sigma in 1/m, lengths in m")
HG_CONVENTIONS = ("as physical_ref.json, with the Henyey-Greenstein phase p(theta) = (1 - g^2)/(4 pi (1 + g^2 - "
                  "2 g cos theta)^{3/2}), g = phase_g (> 0 forward), theta between the light's propagation direction "
                  "at the point (light -> point) and the direction from the point to the viewer: airlight cos theta = "
                  "(D cos(gamma) - x)/d(x), near_light cos theta = -(x + eye_dir.light_pos)/d(x)")

SURFACE_CONVENTIONS = ("surface point in an unbounded medium with isotropic phase 1/(4 pi), point light of intensity "
                       "I0 (W/sr) at distance D (m); theta = angle between the normal (quantity surface) or the mirror "
                       "direction rho (surface_specular) and the direction from the point to the light; L_in(omega) = "
                       "airlight along the infinite ray from the point in direction omega; surface: E = int_{n.omega>0} "
                       "L_in n.omega d omega; surface_specular: E = int L_in max(omega.rho, 0)^exponent d omega (no "
                       "horizon clipping, Sun et al. 2005); both W/m^2; G = E 4 pi D/(sigma_s I0), dimensionless")


def compute(kind, i):
    if kind == "F":
        return F_point(*F_INPUTS[i])
    if kind == "N":
        return N_point(*N_INPUTS[i])
    if kind == "airlight":
        return airlight_case(*AIRLIGHT_INPUTS[i])
    if kind == "hg_airlight":
        return hg_airlight_case(*HG_AIRLIGHT_INPUTS[i])
    if kind == "hg_near_light":
        return hg_near_light_case(*HG_NEAR_LIGHT_INPUTS[i])
    if kind == "surface":
        return surface_case(*SURFACE_INPUTS[i])
    return near_light_case(*NEAR_LIGHT_INPUTS[i])


def record(kind, value):
    return {"F": F_record, "N": N_record}.get(kind, physical_record)(value)


def generate_all(log):
    files = {}
    for kind, count in (("F", len(F_INPUTS)), ("N", len(N_INPUTS)), ("airlight", len(AIRLIGHT_INPUTS)),
                        ("near_light", len(NEAR_LIGHT_INPUTS)), ("hg_airlight", len(HG_AIRLIGHT_INPUTS)),
                        ("hg_near_light", len(HG_NEAR_LIGHT_INPUTS)), ("surface", len(SURFACE_INPUTS))):
        t0 = time.time()
        files[kind] = [record(kind, compute(kind, i)) for i in range(count)]
        log("%-10s %4d values  %6.1f s" % (kind, count, time.time() - t0))
    return {
        "F_ref.json": {"definition": F_DEFINITION, "points": files["F"]},
        "N_ref.json": {"definition": N_DEFINITION, "points": files["N"]},
        "physical_ref.json": {"conventions": PHYSICAL_CONVENTIONS, "cases": files["airlight"] + files["near_light"]},
        "hg_ref.json": {"conventions": HG_CONVENTIONS, "cases": files["hg_airlight"] + files["hg_near_light"]},
        "surface_ref.json": {"conventions": SURFACE_CONVENTIONS, "cases": files["surface"]},
    }


def dump(doc):
    return json.dumps(doc, indent=1, ensure_ascii=False) + "\n"


def write_atomically(directory, docs):
    """All files are computed before any is written; each is renamed into place."""
    for name, doc in docs.items():
        fd, tmp = tempfile.mkstemp(prefix="." + name, dir=directory)
        try:
            with os.fdopen(fd, "w", encoding="utf-8") as f:
                f.write(dump(doc))
            os.chmod(tmp, 0o644)
            os.replace(tmp, os.path.join(directory, name))
        except BaseException:
            if os.path.exists(tmp):
                os.unlink(tmp)
            raise


# --------------------------------------------------------------------------------------------
# --check

def committed_entries(directory):
    """The committed files' entries by (kind, index), after checking that their inputs are this
    script's inputs, in the same order."""
    def load(name):
        path = os.path.join(directory, name)
        try:
            with open(path, encoding="utf-8") as f:
                return json.load(f)
        except OSError as exc:
            raise ReferenceError("cannot read %s: %s" % (path, exc))
        except ValueError as exc:
            raise ReferenceError("%s is not valid JSON: %s" % (path, exc))
    def entries(name, key):
        doc = load(name)
        if not isinstance(doc, dict) or not isinstance(doc.get(key), list) or \
                not all(isinstance(e, dict) for e in doc[key]):
            raise ReferenceError("%s: expected an object with a \"%s\" array of objects" % (os.path.join(directory, name), key))
        return doc[key]
    F = entries("F_ref.json", "points")
    N = entries("N_ref.json", "points")
    phys = entries("physical_ref.json", "cases")
    air = [c for c in phys if c.get("quantity") == "airlight"]
    near = [c for c in phys if c.get("quantity") == "near_light"]
    hg = entries("hg_ref.json", "cases")
    hg_air = [c for c in hg if c.get("quantity") == "airlight"]
    hg_near = [c for c in hg if c.get("quantity") == "near_light"]
    surface = entries("surface_ref.json", "cases")
    expected = {
        "F": [{"u": u, "v": v} for u, v in F_INPUTS],
        "N": [{"T": T, "g": g, "r": r, "S": json_number(S)} for T, g, r, S in N_INPUTS],
        "airlight": [dict(zip(("sigma_s", "sigma_a", "intensity", "distance", "gamma", "length"), c)) for c in AIRLIGHT_INPUTS],
        "near_light": [{"sigma_s": c[0], "sigma_a": c[1], "intensity": c[2], "normal": list(c[3]), "eye_dir": list(c[4]),
                        "light_pos": list(c[5]), "length": json_number(c[6])} for c in NEAR_LIGHT_INPUTS],
        "hg_airlight": [dict(zip(("phase_g", "sigma_s", "sigma_a", "intensity", "distance", "gamma", "length"),
                                 c[:6] + (json_number(c[6]),))) for c in HG_AIRLIGHT_INPUTS],
        "hg_near_light": [{"phase_g": c[0], "sigma_s": c[1], "sigma_a": c[2], "intensity": c[3], "normal": list(c[4]),
                           "eye_dir": list(c[5]), "light_pos": list(c[6]), "length": json_number(c[7])}
                          for c in HG_NEAR_LIGHT_INPUTS],
        "surface": [dict(zip(("quantity", "sigma_s", "sigma_a", "intensity", "distance", "theta"), c[:6]),
                         **({"exponent": c[6]} if c[0] == "surface_specular" else {})) for c in SURFACE_INPUTS],
    }
    have = {"F": F, "N": N, "airlight": air, "near_light": near, "hg_airlight": hg_air, "hg_near_light": hg_near,
            "surface": surface}
    names = {"F": "F_ref.json", "N": "N_ref.json", "airlight": "physical_ref.json", "near_light": "physical_ref.json",
             "hg_airlight": "hg_ref.json", "hg_near_light": "hg_ref.json", "surface": "surface_ref.json"}
    for kind, want in expected.items():
        got = have[kind]
        if len(got) != len(want):
            raise ReferenceError("%s: %d %s entries, the script has %d inputs: rerun make_reference.py"
                                 % (names[kind], len(got), kind, len(want)))
        for i, (g, w) in enumerate(zip(got, want)):
            for k, v in w.items():
                if g.get(k) != v:
                    raise ReferenceError("%s: %s entry %d has %s = %r, the script's input is %r: rerun make_reference.py"
                                         % (names[kind], kind, i, k, g.get(k), v))
    return have, names


def run_check(directory, n, log):
    have, names = committed_entries(directory)
    worst = mpf(0)
    failures = []
    t0 = time.time()
    for kind, i in check_order(n):
        fresh = record(kind, compute(kind, i))
        old = have[kind][i]
        for key in ("F", "tail", "N", "H", "E", "L", "G"):
            if key not in fresh:
                continue
            try:
                b = mpf(old[key])
            except (KeyError, TypeError, ValueError):
                failures.append("%s: %s entry %d: %s missing or not a decimal string (%r)"
                                % (names[kind], kind, i, key, old.get(key)))
                continue
            a = mpf(fresh[key])
            e = rel_diff(a, b)
            worst = max(worst, e)
            if e > CHECK_REL:
                failures.append("%s: %s entry %d (%s): %s = %s recomputed, %s committed (relative %s > %g)"
                                % (names[kind], kind, i, json.dumps({k: v for k, v in old.items() if k not in ("F", "tail", "N", "H", "E", "L", "G")}),
                                   key, fresh[key], old[key], mpmath.nstr(e, 3), CHECK_REL))
    log("checked %d points in %.1f s; worst relative difference %s" % (n, time.time() - t0, mpmath.nstr(worst, 3)))
    return failures


def main(argv):
    ap = argparse.ArgumentParser(description="Compute (or --check) the 30-digit reference values of tests/reference.")
    ap.add_argument("--check", action="store_true", help="recompute a subset and compare it with the committed files")
    ap.add_argument("--points", type=int, default=len(CHECK_FIRST), metavar="N",
                    help="--check: how many values to recompute (default %(default)s: the hard points)")
    ap.add_argument("--dir", default=HERE, help="where the JSON files are read and written (default: this script's directory)")
    args = ap.parse_args(argv)
    total = len(F_INPUTS) + len(N_INPUTS) + len(AIRLIGHT_INPUTS) + len(NEAR_LIGHT_INPUTS) + len(HG_AIRLIGHT_INPUTS) + \
        len(HG_NEAR_LIGHT_INPUTS) + len(SURFACE_INPUTS)
    if not 1 <= args.points <= total:
        ap.error("--points: expected an integer in [1, %d], got %d" % (total, args.points))
    mp.dps = WORK_DPS

    def log(msg):
        print(msg, file=sys.stderr if not args.check else sys.stdout, flush=True)

    log("mpmath %s (%s backend), %d digits" % (mpmath.__version__, mpmath.libmp.BACKEND, WORK_DPS))
    try:
        if args.check:
            failures = run_check(args.dir, args.points, log)
            for f in failures:
                print("make_reference.py --check: " + f, file=sys.stderr)
            if failures:
                return 1
            print("make_reference.py --check: %d values agree with the committed files (<= %g relative)" % (args.points, CHECK_REL))
            return 0
        t0 = time.time()
        docs = generate_all(log)
        write_atomically(args.dir, docs)
        for key in sorted(WORST):
            log("worst relative difference, %-55s %s" % (key + ":", mpmath.nstr(WORST[key], 3)))
        log("wrote %s to %s in %.0f s" % (", ".join(docs), args.dir, time.time() - t0))
        return 0
    except ReferenceError as exc:
        print("make_reference.py: %s" % exc, file=sys.stderr)
        return 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
