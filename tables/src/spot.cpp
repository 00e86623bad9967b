// The spot light's airlight, exact (scatterlut/spot.hpp; docs/PHYSICS.md §1.6): the view ray
// cut by the cone (kernels/slut_spot.h), the point light's exact airlight on each piece inside
// the inner cone, adaptive Gauss–Kronrod on the falloff band.
#include "scatterlut/spot.hpp"

#include "require.hpp"
#include "gauss_kronrod15.hpp"
#include "spot_band.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace scatterlut {
namespace {

using detail::require; // require.hpp
using namespace spot_detail; // spot_band.hpp

constexpr double kAngleMax = kPi + 1e-15; // the double nearest π and rounding above it

// ---------------------------------------------------------------- adaptive Gauss–Kronrod
// G7–K15 (QUADPACK's qk15 nodes), global adaptive: the panel with the largest |K15 − G7| is
// halved until the sum of those differences is below 1e-13 of the integral (|K15 − G7|
// bounds the 7-point rule's error; K15's own is far smaller on smooth integrands).
// The qk15 nodes and weights, once for the library (gauss_kronrod15.hpp).
using gk15::kWg;
using gk15::kWgk;
using gk15::kXgk;

struct Panel {
    double a, b, value, error;
    bool operator<(const Panel &o) const { return error < o.error; }
};

template <class F>
Panel kronrod15(const F &f, double a, double b) {
    const double c = 0.5 * (a + b), r = 0.5 * (b - a);
    const double fc = f(c);
    double k = kWgk[7] * fc, g = kWg[3] * fc;
    for (int j = 0; j < 7; ++j) {
        const double sum = f(c - r * kXgk[j]) + f(c + r * kXgk[j]);
        k += kWgk[j] * sum;
        if (j % 2 == 1) g += kWg[j / 2] * sum;
    }
    return {a, b, k * r, std::fabs((k - g) * r)};
}

template <class F>
double adaptive_kronrod(const F &f, double a, double b) {
    std::vector<Panel> heap{kronrod15(f, a, b)};
    double total = heap[0].value, error = heap[0].error;
    for (int step = 0; step < 4000 && error > 1e-13 * std::fabs(total) && error > 0.0; ++step) {
        std::pop_heap(heap.begin(), heap.end());
        const Panel worst = heap.back();
        heap.pop_back();
        const double mid = 0.5 * (worst.a + worst.b);
        if (!(mid > worst.a && mid < worst.b)) break; // at the resolution of doubles
        const Panel left = kronrod15(f, worst.a, mid), right = kronrod15(f, mid, worst.b);
        total += left.value + right.value - worst.value;
        error += left.error + right.error - worst.error;
        heap.push_back(left);
        std::push_heap(heap.begin(), heap.end());
        heap.push_back(right);
        std::push_heap(heap.begin(), heap.end());
    }
    total = 0.0; // the sum afresh (no drift from the updates)
    for (const Panel &p : heap) total += p.value;
    return total;
}

// The pieces' classification: f at a point inside [a, b] (b may be +inf).
double inside_depth(double a, double b, double scale) {
    return std::isinf(b) ? a + std::fmax(scale, std::fabs(a)) : 0.5 * (a + b);
}

} // namespace

void check_spot_query(const SpotQuery &q) {
    const SpotLight &l = q.light;
    require(q.sigma_s_per_m >= 0.0 && std::isfinite(q.sigma_s_per_m), "sigma_s must be finite and >= 0 (1/m)");
    require(q.sigma_a_per_m >= 0.0 && std::isfinite(q.sigma_a_per_m), "sigma_a must be finite and >= 0 (1/m)");
    require(finite3(q.viewer_m), "viewer must hold finite coordinates (m)");
    require(finite3(q.view_dir), "view_dir must hold finite components");
    require(slut_vec3_length(vec(q.view_dir)) > 0.0, "view_dir must be non-zero");
    require(q.length_m >= 0.0, "length must be >= 0 (m; inf allowed)");
    require(finite3(l.position_m), "light_pos must hold finite coordinates (m)");
    require(finite3(l.direction), "spot_dir must hold finite components");
    require(slut_vec3_length(vec(l.direction)) > 0.0, "spot_dir must be non-zero");
    require(l.outer_angle_rad >= 0.0 && l.outer_angle_rad <= kAngleMax, "outer_angle must lie in [0, pi] (rad)");
    require(l.inner_angle_rad >= 0.0 && l.inner_angle_rad <= kAngleMax, "inner_angle must lie in [0, pi] (rad)");
    require(l.inner_angle_rad <= l.outer_angle_rad, "inner_angle must not exceed outer_angle");
    require(l.intensity_W_per_sr >= 0.0 && std::isfinite(l.intensity_W_per_sr),
            "intensity must be finite and >= 0 (W/sr)");
}

SpotQuery spot_query_from_points(const double viewer_m[3], const double view_dir[3], const double light_m[3],
                                 const double spot_dir[3], double outer_angle_rad, double inner_angle_rad,
                                 double length_m, double sigma_s_per_m, double sigma_a_per_m,
                                 double intensity_W_per_sr) {
    SpotQuery q;
    q.sigma_s_per_m = sigma_s_per_m;
    q.sigma_a_per_m = sigma_a_per_m;
    q.viewer_m = {viewer_m[0], viewer_m[1], viewer_m[2]};
    q.view_dir = {view_dir[0], view_dir[1], view_dir[2]};
    q.length_m = length_m;
    q.light.position_m = {light_m[0], light_m[1], light_m[2]};
    q.light.direction = {spot_dir[0], spot_dir[1], spot_dir[2]};
    q.light.outer_angle_rad = outer_angle_rad;
    q.light.inner_angle_rad = inner_angle_rad;
    q.light.intensity_W_per_sr = intensity_W_per_sr;
    check_spot_query(q);
    return q;
}

SpotRay spot_ray_pieces(const SpotQuery &q) {
    check_spot_query(q);
    SpotRay r;
    r.origin = q.viewer_m;
    r.dir = unit(q.view_dir);
    r.light = q.light.position_m;
    r.axis = unit(q.light.direction);
    r.vers_outer = slut_spot_versine(std::fmin(q.light.outer_angle_rad, kPi));
    r.vers_inner = slut_spot_versine(std::fmin(q.light.inner_angle_rad, kPi));
    const Vec3 light_to_viewer = combine(1.0, r.origin, -1.0, r.light);
    r.closest_t_m = -dot(r.dir, light_to_viewer);
    const Vec3 foot = combine(1.0, light_to_viewer, r.closest_t_m, r.dir); // light → closest point
    r.miss_distance_m = slut_vec3_length(vec(foot));
    const double s = q.length_m, tc = r.closest_t_m;
    if (s == 0.0 || !(r.vers_outer > 0.0)) return r;
    if (r.miss_distance_m == 0.0) {
        // The ray's line passes through the apex: θ is constant on either side of it.
        const double f_before = slut_spot_falloff(slut_spot_versine_of(vec(combine(-1.0, r.dir, 0.0, r.dir)), vec(r.axis)),
                                                  r.vers_outer, r.vers_inner);
        const double f_after = slut_spot_falloff(slut_spot_versine_of(vec(r.dir), vec(r.axis)), r.vers_outer, r.vers_inner);
        if (tc >= 0.0 && tc <= s && ((tc > 0.0 && f_before > 0.0) || (tc < s && f_after > 0.0))) {
            r.through_lit_light = true;
            return r;
        }
        if (tc > 0.0 && f_before > 0.0) r.pieces.push_back({0.0, std::fmin(tc, s), SpotPieceKind::hard, f_before});
        if (tc < s && f_after > 0.0) r.pieces.push_back({std::fmax(tc, 0.0), s, SpotPieceKind::hard, f_after});
        return r;
    }
    r.unit_foot = {foot[0] / r.miss_distance_m, foot[1] / r.miss_distance_m, foot[2] / r.miss_distance_m};
    std::vector<double> breaks{0.0};
    if (std::isfinite(s)) breaks.push_back(s);
    if (tc > 0.0 && tc < s) breaks.push_back(tc);
    const double cone_angle[2] = {q.light.outer_angle_rad, q.light.inner_angle_rad};
    for (int c = 0; c < (r.vers_inner > 0.0 && r.vers_inner < r.vers_outer ? 2 : 1); ++c) {
        // The edge as the convex cone it bounds (slut_spot_cone_of: its versine and axis ±n);
        // the roots in τ = t − t* (slut_spot_cone_roots: versine differences, both nappes).
        const slut_spot_cone cone = slut_spot_cone_of(std::fmin(cone_angle[c], kPi));
        if (!(cone.nu > 0.0)) continue; // θ = π: no edge
        const Vec3 m = combine(cone.axis_sign, r.axis, 0.0, r.axis);
        double roots[2];
        const int n = slut_spot_cone_roots(cone.nu, slut_spot_versine_of(vec(r.dir), vec(m)),
                                           slut_spot_versine_of(vec(r.unit_foot), vec(m)), r.miss_distance_m, roots);
        for (int k = 0; k < n; ++k) {
            const double t = tc + roots[k];
            if (t > 0.0 && t < s && std::fabs(roots[k]) < SLUT_INFINITE_ABOVE) breaks.push_back(t);
        }
    }
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    if (std::isinf(s)) breaks.push_back(s);
    const double scale = std::fmax(r.miss_distance_m, std::fabs(tc));
    for (size_t i = 0; i + 1 < breaks.size(); ++i) {
        const double a = breaks[i], b = breaks[i + 1];
        const double m = inside_depth(a, b, scale);
        const double f = spot_falloff_at(r, m);
        if (f == 0.0) continue;
        const bool hard = f == 1.0;
        // Neighbouring hard pieces (split at t* or on the other nappe) are one.
        if (hard && !r.pieces.empty() && r.pieces.back().kind == SpotPieceKind::hard && r.pieces.back().t1_m == a &&
            r.pieces.back().falloff == 1.0)
            r.pieces.back().t1_m = b;
        else r.pieces.push_back({a, b, hard ? SpotPieceKind::hard : SpotPieceKind::band, hard ? 1.0 : 0.0});
    }
    return r;
}

double spot_falloff(const SpotLight &light, const Vec3 &point_m) {
    require(finite3(point_m), "point must hold finite coordinates (m)");
    SpotQuery q; // the light's own checks (position, axis, angles, intensity)
    q.light = light;
    check_spot_query(q);
    const Vec3 w = combine(1.0, point_m, -1.0, light.position_m);
    const double vers_outer = slut_spot_versine(std::fmin(light.outer_angle_rad, kPi));
    const double vers_inner = slut_spot_versine(std::fmin(light.inner_angle_rad, kPi));
    if (!(slut_vec3_length(vec(w)) > 0.0)) return light.inner_angle_rad >= kPi ? 1.0 : 0.0;
    return slut_spot_falloff(slut_spot_versine_of(vec(unit(w)), vec(unit(light.direction))), vers_outer, vers_inner);
}

double spot_falloff_at(const SpotRay &ray, double t_m) {
    const double along = t_m - ray.closest_t_m, h = ray.miss_distance_m;
    const Vec3 w = combine(along, ray.dir, h, ray.unit_foot);
    return slut_spot_falloff(slut_spot_versine_of(vec(unit(w)), vec(ray.axis)), ray.vers_outer, ray.vers_inner);
}

AirlightQuery spot_sub_segment_query(const SpotQuery &q, const SpotRay &ray, double t0_m, double t1_m) {
    const Vec3 start = combine(1.0, ray.origin, t0_m, ray.dir);
    return airlight_query_from_points(start.data(), ray.dir.data(), ray.light.data(), t1_m - t0_m, q.sigma_s_per_m,
                                      q.sigma_a_per_m, q.light.intensity_W_per_sr);
}

namespace detail {
// The band piece's integral by adaptive Gauss–Kronrod in its angle (BandSide).
double spot_band_exact(const SpotQuery &q, const SpotRay &ray, const SpotPiece &piece, double phase_g) {
    const BandSide side{&ray, 0.5 * (piece.t0_m + piece.t1_m) > ray.closest_t_m || std::isinf(piece.t1_m)};
    const double e0 = side.angle_of(piece.t0_m), e1 = side.angle_of(piece.t1_m);
    const double sigma_t = q.sigma_s_per_m + q.sigma_a_per_m;
    const auto f = [&](double angle) {
        return side.integrand(angle, q.sigma_s_per_m, sigma_t, q.light.intensity_W_per_sr, phase_g);
    };
    return adaptive_kronrod(f, std::fmin(e0, e1), std::fmax(e0, e1));
}
} // namespace detail

double spot_airlight_radiance_exact(const SpotQuery &q, double phase_g) {
    check_phase_g(phase_g);
    check_spot_query(q);
    if (q.light.inner_angle_rad >= kPi) // the point light
        return airlight_radiance_exact(
            airlight_query_from_points(q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), q.length_m,
                                       q.sigma_s_per_m, q.sigma_a_per_m, q.light.intensity_W_per_sr),
            phase_g);
    if (q.sigma_s_per_m == 0.0 || q.light.intensity_W_per_sr == 0.0 || q.length_m == 0.0) return 0.0;
    const SpotRay ray = spot_ray_pieces(q);
    if (ray.through_lit_light) return HUGE_VAL;
    const double sigma_t = q.sigma_s_per_m + q.sigma_a_per_m;
    double sum = 0.0;
    for (const SpotPiece &p : ray.pieces) {
        if (p.kind == SpotPieceKind::band) {
            sum += detail::spot_band_exact(q, ray, p, phase_g);
            continue;
        }
        const double attenuation = p.t0_m == 0.0 ? 1.0 : std::exp(-sigma_t * p.t0_m); // viewer → x(t0)
        if (attenuation == 0.0) continue;
        sum += p.falloff * attenuation * airlight_radiance_exact(spot_sub_segment_query(q, ray, p.t0_m, p.t1_m), phase_g);
    }
    return sum;
}

Rgb spot_airlight_radiance_exact_rgb(const SpotQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                     double phase_g) {
    return per_channel(q, sigma_s_per_m, sigma_a_per_m,
                       [phase_g](const SpotQuery &one) { return spot_airlight_radiance_exact(one, phase_g); });
}

} // namespace scatterlut
