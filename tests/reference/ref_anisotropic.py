"""make_reference.py's anisotropic quantities: the airlight and near-light radiance with a
Henyey-Greenstein phase (docs/PHYSICS.md 1.4), each by two routes plus an identity."""

import mpmath
from mpmath import mp, mpf

from ref_common import INF, ReferenceError, agree, panels, quad_gl, quad_ts
from ref_isotropic import dot, unit


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
