"""make_reference.py's isotropic quantities: F(u, v) and its tail (Sun et al. 2005), N, H and E
(Gath 2008 4.2), and the airlight and near-light radiance in physical units, each by two routes."""

import mpmath
from mpmath import mp, mpf, mpc

from ref_common import CLOSED_DPS, INF, WORK_DPS, ReferenceError, agree, panels, quad_gl, quad_ts


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
