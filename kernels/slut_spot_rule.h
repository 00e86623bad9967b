/* scatterlut — the spot light's airlight from the point light's, as the GPU snippets compute it
 * (docs/SPOT.md "On the GPU", docs/SHADERS.md "Spot lights"): written once, compiled as C++ in
 * double (scatterlut::detail::spot_airlight_radiance_gpu_rule, the tests' reference of the same
 * rule) and as GLSL/HLSL/WGSL in float (the snippets' slut_airlight_spot_radiance_points and
 * slut_airlight_hg_spot_radiance_points).
 *
 * Sign conventions as kernels/slut_spot.h (θ between the spot's axis n and the direction from
 * the light to the point; f(θ) glTF KHR_lights_punctual's falloff) and the point light's
 * (γ between the view direction and the direction from the viewer to the light; the
 * Henyey–Greenstein scattering angle between light → point and point → viewer, g > 0 forward).
 *
 * The rule. The spot's edges (the outer and the inner cone) bound convex cones (slut_spot.h's
 * slut_spot_cone_of: the lit side for a half-angle ≤ π/2, the dark side beyond), so the ray's
 * line meets each in one interval (slut_spot_convex_span). ONE interval I of the ray holds all
 * the light: for θ_o ≤ π/2 (glTF's range) the outer cone's span, for θ_o > π/2 the whole ray.
 * On it, with T the point light's airlight of the sub-segment I seen from x(lo) (the tier's own
 * radiance: the interval's ends are the crossings of the cone, two more ends of the ray, with
 * the tier's rule where the two would cancel), and k the point light's integrand,
 *
 *   L = e^{−σ_t lo} · (T − ∫_D (1 − f) k)     where the ray reaches the inner cone (f = 1 on a
 *                                             part of I): the table gives the light, the rule
 *                                             only what the falloff takes away;
 *   L = e^{−σ_t lo} · T · ∫_D f k / ∫_D k      where it does not (D = I): the rule's ratio, a
 *                                             mean of f in [0, 1], keeps T's accuracy however
 *                                             the rule errs on the weights (a constant f exactly),
 *
 * D the part of I where f < 1 (at most two pieces, cut where f has a corner: the inner cone's
 * edge, or where f peaks on a ray that misses the inner cone; for θ_o > π/2 D holds the dark
 * cone too, f = 0, reached through the C¹ outer edge of a soft cone). Each piece by a 4-point
 * Gauss–Legendre rule in ρ = tan(η/2), η the angle at the point between the ray and the light
 * (η = atan2(h, |t − t*|), t* the closest approach, h the light's distance from the line; across
 * t* in ζ = tan(φ/2), φ = ±(π/2 − η)): k dt = σ_s/(4π) I0 ψ_g(θ_s) e^{−σ_t (t + d)} dη/h, so the
 * 1/d² peak is gone and an infinite ray ends at ρ = 0; every node's geometry rational in ρ.
 *
 * Cost: one point-light radiance (two table samples in the tiers), two exps for e^{−σ_t lo}
 * and the scale, 8 nodes of the rule (an exp and three divides each), the cones' crossings (two
 * quadratics). No branch: selects only (llvmpipe runs both sides of a branch, and a loop's body
 * once, whatever its lanes take).
 *
 * The rule's error (measured against the exact spot airlight, docs/SPOT.md) is the band's: it
 * grows with how much e^{−σ_t (t + d)} falls across a band piece (thick fog, long pieces: wide
 * bands seen edge-on, rays that run inside the band) and, for θ_o > π/2, where most of the ray's
 * light would come through the dark cone (the difference T − ∫_D k cancels).
 *
 * Shared subset (kernels/slut_compat.h): structs by value, no arrays in structs.
 */
#ifndef SLUT_SPOT_RULE_H
#define SLUT_SPOT_RULE_H

#include "slut_compat.h"
#include "slut_vec3.h"
#include "slut_phase.h"
#include "slut_spot.h"

/* 4-point Gauss–Legendre on [−1, 1]: node j and its weight. */
#define SLUT_SPOT_NODE(j) (((j) == 0) ? -0.861136311594052575 : (((j) == 1) ? -0.339981043584856265 : (((j) == 2) ? 0.339981043584856265 : 0.861136311594052575)))
#ifndef SLUT_SPOT_SPLIT_OPTICAL
#define SLUT_SPOT_SPLIT_OPTICAL 2.0
#endif
#define SLUT_SPOT_WEIGHT(j) (((j) == 0 || (j) == 3) ? 0.347854845137453857 : 0.652145154862546143)

/* The view ray against the spot's two cones. Lengths in m along the ray from the viewer. */
SLUT_STRUCT_BEGIN(slut_spot_ray)
    slut_vec3 dir;     /* d, the unit view direction                                          */
    slut_vec3 foot;    /* ê, the unit vector from the light to the line's closest point (0: h = 0) */
    slut_vec3 axis;    /* m_o = ±n, the outer edge's convex cone's axis                        */
    double closest;    /* t* = d·(L − o), m (< 0: the light behind the viewer)                 */
    double miss;       /* h, m                                                                 */
    double ray_length; /* s, m, at most SLUT_INFINITE_ABOVE (that: an infinite ray)           */
    double nu_outer;   /* versine of the outer convex cone's half-angle about m_o             */
    double nu_inner;   /* versine of θ_i about m_o (2 sin²(θ_i/2) for m_o = n, 2 cos²(θ_i/2) for −n) */
    double inv_band;   /* 1/(nu_outer − nu_inner), 0 for a hard cone: f = clamp((ν_o − ν)·inv_band, 0, 1)² */
    double outer_lo;   /* the line ∩ the outer convex cone, in t (empty: both SLUT_INFINITE_ABOVE) */
    double outer_hi;
    double inner_lo;   /* the line ∩ the inner convex cone, in t                              */
    double inner_hi;
    int outer_lit;     /* 1: θ_o ≤ π/2, the outer convex cone is the lit side; 0: the dark side */
    int inner_lit;     /* likewise for θ_i                                                     */
SLUT_STRUCT_END(slut_spot_ray);

/* v/|v| (0 < |v|, |v|² within the working type's range: coordinates below 1e18 in float). */
SLUT_FN slut_vec3 slut_spot_unit(slut_vec3 v) {
    double k = 1.0 / sqrt(slut_vec3_dot(v, v));
    return slut_vec3_make(v.x * k, v.y * k, v.z * k);
}

/* The line ∩ a convex cone of the spot, in t: slut_spot_convex_span shifted by t*. */
SLUT_FN slut_spot_span slut_spot_span_along(slut_spot_cone c, slut_vec3 n, slut_vec3 d, slut_vec3 foot,
                                            double miss, double closest) {
    slut_vec3 m = slut_vec3_make(c.axis_sign * n.x, c.axis_sign * n.y, c.axis_sign * n.z);
    slut_spot_span j = slut_spot_convex_span(c.nu, slut_spot_versine_of(d, m), slut_spot_versine_of(foot, m), miss);
    j.lo = SLUT_SELECT(j.lo >= SLUT_INFINITE_ABOVE, SLUT_INFINITE_ABOVE, closest + j.lo);
    j.hi = SLUT_SELECT(j.hi >= SLUT_INFINITE_ABOVE, SLUT_INFINITE_ABOVE, closest + j.hi);
    return j;
}

/* The ray from positions: viewer o, view_dir (any length > 0), light L, spot_dir (the beam's
 * axis, any length > 0), the cone half-angles θ_o ≥ θ_i in [0, π] (rad) and the ray's length
 * (≥ SLUT_INFINITE_ABOVE or +inf: infinite). */
SLUT_FN slut_spot_ray slut_spot_ray_of(slut_vec3 viewer, slut_vec3 view_dir, slut_vec3 light, slut_vec3 spot_dir,
                                       double outer_angle, double inner_angle, double ray_length) {
    slut_spot_ray r;
    slut_vec3 n = slut_spot_unit(spot_dir);
    slut_vec3 w0 = slut_vec3_make(viewer.x - light.x, viewer.y - light.y, viewer.z - light.z);
    slut_spot_cone co = slut_spot_cone_of(outer_angle);
    slut_spot_cone ci = slut_spot_cone_of(inner_angle);
    r.dir = slut_spot_unit(view_dir);
    r.closest = -slut_vec3_dot(r.dir, w0);
    slut_vec3 e = slut_vec3_make(w0.x + r.closest * r.dir.x, w0.y + r.closest * r.dir.y, w0.z + r.closest * r.dir.z);
    r.miss = sqrt(slut_vec3_dot(e, e));
    double inv_miss = SLUT_SELECT(r.miss > 0.0, 1.0 / r.miss, 0.0);
    r.foot = slut_vec3_make(e.x * inv_miss, e.y * inv_miss, e.z * inv_miss);
    r.axis = slut_vec3_make(co.axis_sign * n.x, co.axis_sign * n.y, co.axis_sign * n.z);
    r.ray_length = fmin(ray_length, SLUT_INFINITE_ABOVE);
    r.nu_outer = co.nu;
    r.nu_inner = SLUT_SELECT(co.axis_sign == ci.axis_sign, ci.nu, 2.0 - ci.nu); /* θ_i ≤ π/2 < θ_o: 2 cos²(θ_i/2) ≥ 1 */
    r.inv_band = SLUT_SELECT(r.nu_outer != r.nu_inner, 1.0 / (r.nu_outer - r.nu_inner), 0.0);
    slut_spot_span jo = slut_spot_span_along(co, n, r.dir, r.foot, r.miss, r.closest);
    slut_spot_span ji = slut_spot_span_along(ci, n, r.dir, r.foot, r.miss, r.closest);
    r.outer_lo = jo.lo;
    r.outer_hi = jo.hi;
    r.inner_lo = ji.lo;
    r.inner_hi = ji.hi;
    r.outer_lit = (co.axis_sign > 0.0) ? 1 : 0;
    r.inner_lit = (ci.axis_sign > 0.0) ? 1 : 0;
    return r;
}

/* The interval that holds the light and what the point light's radiance of it needs. */
SLUT_STRUCT_BEGIN(slut_spot_interval)
    double lo;         /* [lo, hi] along the ray, m (empty: lo = hi = 0)                     */
    double hi;
    double distance;   /* D' = |x(lo) − L|, m (at least SLUT_SQUARABLE_MIN)                  */
    double sin_gamma;  /* γ' at x(lo): the view direction ↔ the direction from x(lo) to L     */
    double cos_gamma;
    double sub_length; /* hi − lo, m (SLUT_INFINITE_ABOVE: an infinite ray)                  */
    double band0_lo;   /* D's two pieces in I (each may be empty: hi = lo)                   */
    double band0_hi;
    double band1_lo;
    double band1_hi;
    int has_core;      /* 1: f = 1 on part of I (the ray reaches the inner cone there)       */
SLUT_STRUCT_END(slut_spot_interval);

/* The interval I (the outer cone's span for θ_o ≤ π/2, the ray for θ_o > π/2), D's pieces in it
 * (f = 1 on the inner cone's span for θ_i ≤ π/2, off it for θ_i > π/2), and x(lo) as a viewer. */
SLUT_FN slut_spot_interval slut_spot_interval_of(slut_spot_ray r) {
    slut_spot_interval iv;
    double lo = SLUT_SELECT(r.outer_lit != 0, fmax(0.0, r.outer_lo), 0.0);
    double hi = SLUT_SELECT(r.outer_lit != 0, fmin(r.ray_length, r.outer_hi), r.ray_length);
    int empty = (hi > lo) ? 0 : 1;
    lo = SLUT_SELECT(empty != 0, 0.0, lo);
    hi = SLUT_SELECT(empty != 0, 0.0, hi);
    iv.lo = lo;
    iv.hi = hi;
    /* θ_i ≤ π/2: D = I minus the inner span (before and after it). θ_i > π/2: D = I on the inner
     * (dark) span, cut where the ray leaves the outer (dark) cone's middle. */
    double ilo = fmin(hi, fmax(lo, r.inner_lo)), ihi = fmax(ilo, fmin(hi, r.inner_hi));
    double dark_mid = slut_clamp(0.5 * (fmax(r.outer_lo, -SLUT_SQUARABLE_MAX) + fmin(r.outer_hi, SLUT_SQUARABLE_MAX)), ilo, ihi);
    iv.band0_lo = SLUT_SELECT(r.inner_lit != 0, lo, ilo);
    iv.band0_hi = SLUT_SELECT(r.inner_lit != 0, ilo, dark_mid);
    iv.band1_lo = SLUT_SELECT(r.inner_lit != 0, ihi, dark_mid);
    iv.band1_hi = SLUT_SELECT(r.inner_lit != 0, hi, ihi);
    iv.has_core = SLUT_SELECT(r.inner_lit != 0, ihi > ilo, ilo > lo || hi > ihi) ? 1 : 0;
    /* A ray that misses the inner cone has all of I in D, where f rises and falls again: cut it
     * where f peaks, so that both pieces are monotone. Along the line m_o·ŵ = (m_o·d) sin φ +
     * (m_o·ê) cos φ (t = t* + h tan φ) is extreme at tan φ = a'/b' (a' = ±m_o·d, b' = ±m_o·ê, the
     * sign of inv_band: f grows as m_o·ŵ does for a lit outer cone, falls for a dark one); b' ≤ 0
     * leaves f monotone on the line. */
    double growth = SLUT_SELECT(r.inv_band >= 0.0, 1.0, -1.0);
    double a1 = growth * slut_vec3_dot(r.axis, r.dir), b1 = growth * slut_vec3_dot(r.axis, r.foot);
    double peak = SLUT_SELECT(b1 > 0.0 && fabs(a1) * r.miss < SLUT_INFINITE_ABOVE * b1, r.closest + r.miss * (a1 / b1),
                              SLUT_SELECT(a1 > 0.0, SLUT_INFINITE_ABOVE, -SLUT_INFINITE_ABOVE));
    double cut = slut_clamp(peak, lo, hi);
    iv.band0_lo = SLUT_SELECT(iv.has_core != 0, iv.band0_lo, lo);
    iv.band0_hi = SLUT_SELECT(iv.has_core != 0, iv.band0_hi, cut);
    iv.band1_lo = SLUT_SELECT(iv.has_core != 0, iv.band1_lo, cut);
    iv.band1_hi = SLUT_SELECT(iv.has_core != 0, iv.band1_hi, hi);
    /* x(lo) − L = e + τ d as the sub-segment's viewer; at the light (the ray leaves the apex lit)
     * γ' = 0 at a distance the point light's radiance takes (its +∞ through the light, 0 for an
     * empty interval). */
    double tau = lo - r.closest;
    double dist = sqrt(tau * tau + r.miss * r.miss);
    double inv_dist = SLUT_SELECT(dist > 0.0, 1.0 / dist, 0.0);
    iv.distance = fmax(dist, SLUT_SQUARABLE_MIN);
    iv.sin_gamma = r.miss * inv_dist;
    iv.cos_gamma = SLUT_SELECT(dist > 0.0, -tau * inv_dist, 1.0);
    iv.sub_length = SLUT_SELECT(hi >= SLUT_INFINITE_ABOVE, SLUT_INFINITE_ABOVE, hi - lo);
    return iv;
}

/* The light path less t*, y = t + d − t* = τ + √(τ² + h²) (h²/(d − τ) for τ < 0: no cancellation). */
SLUT_FN double slut_spot_path_at(double tau, double miss) {
    double d = sqrt(tau * tau + miss * miss);
    return SLUT_SELECT(tau >= 0.0, tau + d, SLUT_SELECT(d - tau > 0.0, miss * (miss / (d - tau)), 0.0));
}

/* ρ = tan(η/2) at the point τ = t − t* of the ray, η the angle there between the ray and the
 * light: h/(d + |τ|) on either side of t* (d = √(τ² + h²); the path y = t + d − t* is hρ before
 * t*, h/ρ after it). */
SLUT_FN double slut_spot_rho(double tau, double miss) {
    double d = sqrt(tau * tau + miss * miss);
    return SLUT_SELECT(d > 0.0, miss / (d + fabs(tau)), 1.0);
}

/* The spot's airlight on the interval, W/(m²·sr), from `point_radiance`, the point light's
 * radiance of the sub-segment (iv.distance, iv.sin_gamma, iv.cos_gamma, iv.sub_length; the
 * medium and I0 as the spot's; phase_g the phase of both): see the top. Never negative, never
 * NaN for a point_radiance that is neither; +∞ where point_radiance is (the ray through the lit
 * apex).
 *
 * Each piece of D gets a 4-point Gauss–Legendre rule in ρ = tan(η/2) on one side of t*
 * (dη = 2 dρ/(1 + ρ²)) or ζ = tan(φ/2) across it (dφ = 2 dζ/(1 + ζ²); ρ alone has a corner at
 * t*). A node's geometry from ρ and its side: the path y = hρ before t*, h/ρ after; sin η =
 * 2ρ/(1 + ρ²), cos η = (1 − ρ²)/(1 + ρ²), ŵ = ±cos η d + sin η ê (light → point); the scattering
 * angle θ_s = η before t*, π − η after: sin²(θ_s/2) = ρ²/(1 + ρ²) before, 1/(1 + ρ²) after. */
SLUT_FN double slut_spot_interval_radiance(slut_spot_ray r, slut_spot_interval iv, double point_radiance,
                                           double sigma_s, double sigma_t, double intensity, double phase_g) {
    double h = fmax(fmax(r.miss, SLUT_SPOT_MIN_MISS * (fabs(r.closest) + iv.distance)), SLUT_TINY);
    double weight_sum = 0.0, lit_sum = 0.0, deficit_sum = 0.0;
    /* Where one piece is empty, the other gets both rules: cut where the light path has grown
     * by SLUT_SPOT_SPLIT_OPTICAL/σ_t past its start (or at half its optical length, if that is
     * less), so that the near part, which carries most of the light, has its own rule. */
    int lone = (iv.band1_hi > iv.band1_lo) ? 0 : ((iv.band0_hi > iv.band0_lo) ? 1 : 0);
    double only_lo = SLUT_SELECT(lone != 0, iv.band0_lo, 0.0), only_hi = SLUT_SELECT(lone != 0, iv.band0_hi, 0.0);
    double ya = slut_spot_path_at(only_lo - r.closest, h), yb = slut_spot_path_at(only_hi - r.closest, h);
    double grow = fmin(SLUT_SPOT_SPLIT_OPTICAL, 0.5 * sigma_t * fmin(yb - ya, SLUT_INFINITE_ABOVE));
    double ym = SLUT_SELECT(sigma_t > 0.0, ya + grow / sigma_t, 0.5 * (ya + fmin(yb, SLUT_SQUARABLE_MAX)));
    double split = slut_clamp(r.closest + (ym - h) * (ym + h) / (2.0 * fmax(ym, SLUT_TINY)), only_lo, only_hi);
    for (int piece = 0; piece < 2; ++piece) {
        double a = SLUT_SELECT(lone != 0, SLUT_SELECT(piece == 0, only_lo, split), SLUT_SELECT(piece == 0, iv.band0_lo, iv.band1_lo)) - r.closest;
        double b = SLUT_SELECT(lone != 0, SLUT_SELECT(piece == 0, split, only_hi), SLUT_SELECT(piece == 0, iv.band0_hi, iv.band1_hi)) - r.closest; /* τ = t − t* */
        double rho_a = slut_spot_rho(a, h), rho_b = slut_spot_rho(b, h);
        double side_a = SLUT_SELECT(a >= 0.0, 1.0, -1.0), side_b = SLUT_SELECT(b >= 0.0, 1.0, -1.0);
        double zeta_a = side_a * (1.0 - rho_a) / (1.0 + rho_a), zeta_b = side_b * (1.0 - rho_b) / (1.0 + rho_b);
        int same_side = (side_a == side_b) ? 1 : 0;
        double half_extent = 0.5 * SLUT_SELECT(same_side != 0, fabs(rho_b - rho_a), fabs(zeta_b - zeta_a));
        for (int j = 0; j < 4; ++j) {
            double u = 0.5 + 0.5 * SLUT_SPOT_NODE(j);
            double zeta = zeta_a + (zeta_b - zeta_a) * u;
            double k = 1.0 / (1.0 + fabs(zeta)); /* across t*: ρ = (1 − |ζ|)/(1 + |ζ|), dη/dζ = 4k²/(1 + ρ²)·… */
            double rho = SLUT_SELECT(same_side != 0, rho_a + (rho_b - rho_a) * u, (1.0 - fabs(zeta)) * k);
            double side = SLUT_SELECT(same_side != 0, side_a, SLUT_SELECT(zeta >= 0.0, 1.0, -1.0));
            double rho2 = rho * rho;
            double one = 1.0 / (fmax(rho, SLUT_TINY) * (1.0 + rho2)); /* 1/(ρ (1 + ρ²)): both reciprocals */
            double inv = rho * one;                                    /* 1/(1 + ρ²) */
            /* the path y − t* (hρ before t*, h/ρ after) in the light path's exponent, relative to
             * the sub-segment's start (t + d at lo, which the scale carries) */
            double y = SLUT_SELECT(side > 0.0, h * (1.0 + rho2) * one, h * rho);
            /* ŵ (light → point), its versine about m_o, f */
            double sn = 2.0 * rho * inv, cs = side * (1.0 - rho) * (1.0 + rho) * inv;
            double wx = cs * r.dir.x + sn * r.foot.x - r.axis.x;
            double wy = cs * r.dir.y + sn * r.foot.y - r.axis.y;
            double wz = cs * r.dir.z + sn * r.foot.z - r.axis.z;
            double q = slut_clamp((r.nu_outer - 0.5 * (wx * wx + wy * wy + wz * wz)) * r.inv_band, 0.0, 1.0);
            double f = q * q;
            /* the integrand per unit η, less σ_s/(4π) I0/h, times the node's share (dη = 2 dρ/(1 + ρ²),
             * or 2 dζ/(1 + ζ²) = 4k² dζ/(2(1 + ρ²))·2 across t*) */
            double psi = SLUT_SELECT(phase_g == 0.0, 1.0,
                                     slut_hg_psi_half(phase_g, SLUT_SELECT(side > 0.0, inv, rho2 * inv), SLUT_SELECT(side > 0.0, rho2 * inv, inv)));
            double jacobian = SLUT_SELECT(same_side != 0, 2.0 * inv, 4.0 * inv * k * k);
            double weight = SLUT_SPOT_WEIGHT(j) * half_extent * jacobian * psi *
                            exp(-sigma_t * fmin(r.closest + y, SLUT_INFINITE_ABOVE));
            weight_sum += weight;
            lit_sum += weight * f;
            deficit_sum += weight * (1.0 - f);
        }
    }
    /* the rule's sums in W/(m²·sr): σ_s/(4π) I0/h (the nodes' exponents are the whole light
     * path t + d from the viewer); the table's T is the sub-segment's seen from x(lo) */
    double attenuation = SLUT_SELECT(iv.lo > 0.0, exp(-sigma_t * iv.lo), 1.0);
    double scale = (sigma_s * SLUT_INV_4PI) * intensity / h;
    double lit = attenuation * point_radiance;
    double corrected = SLUT_SELECT(iv.has_core != 0, lit - scale * deficit_sum,
                                   SLUT_SELECT(weight_sum > 0.0 && lit_sum > 0.0, lit * (lit_sum / weight_sum), 0.0));
    return SLUT_SELECT(lit > 0.0 && corrected > 0.0, fmin(corrected, lit), 0.0);
}

#endif /* SLUT_SPOT_RULE_H */
