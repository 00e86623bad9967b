// Random spot-light geometries the spot tests share (tests/kernels/test_spot.cpp: the exact
// airlight; tests/runtime/test_spot_rule.cpp: the GPU snippets' rule; tests/shaders/
// test_shaders_spot.cpp: the snippets themselves): the viewer inside the beam, beside it, near
// the axis looking along it, or in the beam looking away from the light (the apex behind the
// viewer); hard cones, soft cones of any width, outer angles beyond π/2; finite and infinite
// rays; directions of any length (the library normalises them).
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <random>

#include "scatterlut/spot.hpp"

extern "C" {
#include "slut_spot_rule.h"
}

namespace spot_geometry {

using scatterlut::SpotQuery;
using scatterlut::Vec3;

constexpr double kPi = 3.14159265358979323846;

// One fixed soft-cone geometry the tests vary a field of at a time: the ray along +x from the
// origin, 20 m, passing under a spot 4 m above it whose beam points down (θ_o 0.6, θ_i 0.3).
inline SpotQuery base_query() {
    SpotQuery q;
    q.sigma_s_per_m = 0.1;
    q.sigma_a_per_m = 0.05;
    q.viewer_m = {0, 0, 0};
    q.view_dir = {1, 0, 0};
    q.length_m = 20;
    q.light.position_m = {5, 0, 4};
    q.light.direction = {0, 0, -1};
    q.light.outer_angle_rad = 0.6;
    q.light.inner_angle_rad = 0.3;
    q.light.intensity_W_per_sr = 3;
    return q;
}

inline double dot(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
inline Vec3 add(const Vec3 &a, double k, const Vec3 &b) { return {a[0] + k * b[0], a[1] + k * b[1], a[2] + k * b[2]}; }
inline Vec3 cross(const Vec3 &a, const Vec3 &b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
inline double norm(const Vec3 &a) { return std::sqrt(dot(a, a)); }
inline Vec3 unit(const Vec3 &a) { return add({0, 0, 0}, 1.0 / norm(a), a); }

enum Kind { kInside = 0, kBeside = 1, kAlong = 2, kApexBehind = 3 };
inline const char *kind_name(int kind) {
    static const char *names[4] = {"inside", "beside", "along", "apex behind"};
    return names[kind];
}

// The ranges a population draws from.
struct Ranges {
    double sigma_s_max = 0.5, sigma_a_max = 0.3; // 1/m: σ_s in [0.01, 0.01 + max], σ_a in [0, max]
    double outer_min = 0.05, outer_max = 2.75;    // θ_o, rad
    double inner_share_max = 0.95;                // θ_i = θ_o·U·max (0: a hard cone every fifth query only)
    double band_min = 0.0, band_max = 0.0;        // > 0: θ_i = θ_o − U(band_min, band_max) instead
    double distance_max = 15.5;                   // the viewer within this of the light, m
    double length_max = 40.2;                     // finite rays' length, m
};

// glTF-like spots (docs/SPOT.md's "typical cones"): θ_o in [0.2, 1.4] rad, bands 0.05–0.4 rad
// wide, fog up to σ_t 0.35/m.
inline Ranges typical_ranges() {
    Ranges typical;
    typical.sigma_s_max = 0.3;
    typical.sigma_a_max = 0.05;
    typical.outer_min = 0.2;
    typical.outer_max = 1.4;
    typical.band_min = 0.05;
    typical.band_max = 0.4;
    return typical;
}

struct Geometry {
    SpotQuery q;
    double g = 0; // a Henyey–Greenstein g for the tests that take one, in [−0.3, 0.85]
    int kind = 0;
};

// Query k: kind k % 4; every third ray infinite; k % 5 == 0 a hard cone; k % 7 == 0 σ_a = 0.
inline Geometry random_geometry(std::mt19937_64 &rng, int k, const Ranges &R = Ranges()) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    auto random_unit = [&] {
        for (;;) {
            const Vec3 v{2 * U(rng) - 1, 2 * U(rng) - 1, 2 * U(rng) - 1};
            if (norm(v) > 0.1 && norm(v) <= 1) return unit(v);
        }
    };
    Geometry G;
    G.kind = k % 4;
    SpotQuery &q = G.q;
    q.sigma_s_per_m = 0.01 + R.sigma_s_max * U(rng);
    q.sigma_a_per_m = (k % 7 == 0) ? 0.0 : R.sigma_a_max * U(rng);
    G.g = -0.3 + 1.15 * U(rng);
    q.light.position_m = {10 * U(rng) - 5, 10 * U(rng) - 5, 10 * U(rng) - 5};
    const Vec3 n = random_unit();
    q.light.direction = add({0, 0, 0}, 0.5 + 3 * U(rng), n); // not unit: the library normalises
    q.light.outer_angle_rad = R.outer_min + (R.outer_max - R.outer_min) * U(rng);
    if (k % 5 == 0) q.light.inner_angle_rad = q.light.outer_angle_rad;
    else if (R.band_max > 0.0)
        q.light.inner_angle_rad =
            std::fmax(0.0, q.light.outer_angle_rad - (R.band_min + (R.band_max - R.band_min) * U(rng)));
    else q.light.inner_angle_rad = q.light.outer_angle_rad * R.inner_share_max * U(rng);
    const Vec3 perp = unit(cross(n, random_unit()));
    const double r = 0.5 + (R.distance_max - 0.5) * U(rng), to = q.light.outer_angle_rad;
    double a = 0; // the viewer's spot angle
    if (G.kind == kInside || G.kind == kApexBehind) a = to * 0.9 * U(rng);
    else if (G.kind == kBeside) a = std::fmin(to + 0.05 + (kPi - to) * U(rng), kPi - 0.01);
    else a = 1e-3 * U(rng);
    q.viewer_m = add(add(q.light.position_m, r * std::cos(a), n), r * std::sin(a), perp);
    const Vec3 from_light = unit(add(q.viewer_m, -1.0, q.light.position_m));
    if (G.kind == kAlong) q.view_dir = unit(add(add({0, 0, 0}, (k % 8 < 4) ? 1.0 : -1.0, n), 0.02 * U(rng), random_unit()));
    else q.view_dir = random_unit();
    if (G.kind == kApexBehind && dot(q.view_dir, from_light) < 0) q.view_dir = add({0, 0, 0}, -1.0, q.view_dir);
    q.length_m = (k % 3 == 0) ? std::numeric_limits<double>::infinity() : 0.2 + (R.length_max - 0.2) * U(rng);
    q.light.intensity_W_per_sr = 0.5 + 10 * U(rng);
    return G;
}

// The GPU rule's stated error (kernels/slut_spot_rule.h, docs/SPOT.md "On the GPU"), from what it
// depends on: the band pieces' optical length Λ = σ_t × how much the light path t + d grows across
// the longer piece (∞ for a piece to an infinite ray's end) and the band's width θ_o − θ_i. For
// Λ ≤ 8, relative to the spot's radiance: 1.5e-3 for bands up to 0.4 rad wide, 1e-2 wider; plus
// 3e-3 for a forward phase (g ≥ 0.5: the peak of ψ_g at small scattering angles, narrower than the
// 4-point rule resolves where a band piece runs towards the light from afar). For Λ > 8 (thick fog,
// long pieces: the rule no longer follows the exponential) 2e-2, and for θ_o > π/2 (beyond glTF's
// range, where the rule subtracts the dark cone's light from the whole ray's) 5e-2 more, both
// relative to the point light's radiance of the whole ray (`relative_to_whole`).
struct RuleTolerance {
    double tol;
    bool relative_to_whole;
};
inline double band_optical_length(const SpotQuery &q) {
    auto v = [](const Vec3 &a) { return slut_vec3_make(a[0], a[1], a[2]); };
    const slut_spot_ray ray = slut_spot_ray_of(v(q.viewer_m), v(q.view_dir), v(q.light.position_m),
                                               v(q.light.direction), q.light.outer_angle_rad,
                                               q.light.inner_angle_rad, q.length_m);
    const slut_spot_interval iv = slut_spot_interval_of(ray);
    const auto path = [&](double t) { return t >= SLUT_INFINITE_ABOVE ? HUGE_VAL : t + std::hypot(t - ray.closest, ray.miss); };
    double L = 0;
    for (const double *p : {&iv.band0_lo, &iv.band1_lo})
        if (p[1] > p[0]) L = std::fmax(L, (q.sigma_s_per_m + q.sigma_a_per_m) * (path(p[1]) - path(p[0])));
    return L;
}
inline RuleTolerance rule_tolerance(const SpotQuery &q, double phase_g) {
    const bool thick = band_optical_length(q) > 8.0, wide = q.light.outer_angle_rad > 0.5 * kPi;
    const double band = q.light.outer_angle_rad - q.light.inner_angle_rad <= 0.4 ? 1.5e-3 : 1e-2;
    return {(thick ? 2e-2 : band) + (phase_g >= 0.5 ? 3e-3 : 0.0) + (wide ? 5e-2 : 0.0), thick || wide};
}

} // namespace spot_geometry
