// The spot airlight's internals shared by the exact and the table paths (spot.cpp,
// spot_table.cpp): vector helpers and a falloff-band piece's angle variable (BandSide).
#pragma once

#include <cmath>

#include "scatterlut/spot.hpp"

extern "C" {
#include "slut_phase.h"
#include "slut_spot.h"
#include "slut_vec3.h"
}

namespace scatterlut::spot_detail {

constexpr double kPi = 3.14159265358979323846;

inline slut_vec3 vec(const Vec3 &v) { return slut_vec3_make(v[0], v[1], v[2]); }

inline bool finite3(const Vec3 &v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// v/|v| (|v| > 0, finite).
inline Vec3 unit(const Vec3 &v) {
    const double n = slut_vec3_length(vec(v));
    return {v[0] / n, v[1] / n, v[2] / n};
}

inline double dot(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }

// a·x + b·y, componentwise.
inline Vec3 combine(double a, const Vec3 &x, double b, const Vec3 &y) {
    return {a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2]};
}

// ---------------------------------------------------------------- the band's integrand
// A band piece lies on one side of the closest approach t* (spot_ray_pieces cuts there). Its
// variable is the angle at the point between the ray and the light, measured so that it stays
// away from π (every quantity below from its sine and cosine, no cancellation):
//  * before t* (light ahead): β = atan2(h, t* − t) ∈ (0, π/2], increasing with t;
//      t = t* − h cot β,  d = h/sin β,  t + d = t* + h tan(β/2),
//      ŵ = −cos β d̂ + sin β ê  (ê the unit vector from the light to the foot of the perpendicular),
//      scattering angle θ_s = β;
//  * after t* (light behind): χ = atan2(h, t − t*) ∈ (0, π/2], decreasing with t;
//      t = t* + h cot χ,  d = h/sin χ,  t + d = t* + h cot(χ/2),  ŵ = cos χ d̂ + sin χ ê,
//      θ_s = π − χ.
// Either way dt/d² = dη/h, so the integrand σ_s p_g f I0 e^{−σ_t (t + d)}/d² dt becomes
// σ_s/(4π)·I0/h·ψ_g(θ_s)·f·e^{−σ_t (t + d)} dη: bounded, and smooth inside the band.
struct BandSide {
    const SpotRay *ray;
    bool after; // χ, else β
    // The angle η of depth t (t = ±inf: 0 after, π/2 … before never reaches −inf).
    double angle_of(double t_m) const {
        if (after) return std::isinf(t_m) ? 0.0 : std::atan2(ray->miss_distance_m, t_m - ray->closest_t_m);
        return std::atan2(ray->miss_distance_m, ray->closest_t_m - t_m);
    }
    double depth_of(double angle) const {
        const double h = ray->miss_distance_m, cot = std::cos(angle) / std::sin(angle);
        return after ? ray->closest_t_m + h * cot : ray->closest_t_m - h * cot;
    }
    Vec3 unit_light_to_point(double angle) const {
        const double c = std::cos(angle), s = std::sin(angle);
        return combine(after ? c : -c, ray->dir, s, ray->unit_foot);
    }
    // dŵ/dη.
    Vec3 unit_light_to_point_rate(double angle) const {
        const double c = std::cos(angle), s = std::sin(angle);
        return combine(after ? -s : s, ray->dir, c, ray->unit_foot);
    }
    double falloff(double angle) const {
        return slut_spot_falloff(slut_spot_versine_of(vec(unit_light_to_point(angle)), vec(ray->axis)),
                                 ray->vers_outer, ray->vers_inner);
    }
    // df/dη (0 outside the band): f'(vers)·dvers/dη, dvers/dη = −n·dŵ/dη (|ŵ| = 1).
    double falloff_rate(double angle) const {
        const double vers = slut_spot_versine_of(vec(unit_light_to_point(angle)), vec(ray->axis));
        return slut_spot_falloff_slope(vers, ray->vers_outer, ray->vers_inner) *
               -dot(ray->axis, unit_light_to_point_rate(angle));
    }
    // σ_s p_g I0 f e^{−σ_t (t + d)}/d² · dt/dη, in W/(m²·sr) per radian.
    double integrand(double angle, double sigma_s, double sigma_t, double intensity, double phase_g) const {
        const double h = ray->miss_distance_m, half = 0.5 * angle;
        const double sh = std::sin(half), ch = std::cos(half);
        const double light_path = ray->closest_t_m + h * (after ? ch / sh : sh / ch); // t + d
        const double psi = after ? slut_hg_psi_half(phase_g, ch * ch, sh * sh) : slut_hg_psi_half(phase_g, sh * sh, ch * ch);
        const double f = falloff(angle);
        if (f == 0.0) return 0.0;
        const double attenuation = sigma_t == 0.0 ? 1.0 : std::exp(-sigma_t * light_path);
        return sigma_s * SLUT_INV_4PI * intensity / h * psi * f * attenuation;
    }
};


} // namespace scatterlut::spot_detail
