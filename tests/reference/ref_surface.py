"""make_reference.py's surface terms (Sun et al. 2005; docs/PHYSICS.md 1.5): E_ss and S_n by two
tanh-sinh routes, their closed-form kernels against their definitions."""

import mpmath
from mpmath import mp, mpf

from ref_common import CLOSED_DPS, SURFACE_AGREE_REL, agree, ladder, quad_ts


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
