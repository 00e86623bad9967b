// The spot's scattered surface terms at zero optical depth by a fixed rule (scatterlut/
// spot_surface.hpp, spot_surface_G_thin; docs/SPOT.md "The thin-beam factor"): the integral of
// spot_surface.cpp at T = 0, where the innermost integral (over the angle χ at P) has a closed
// form, by a fixed product rule over the azimuth φ' and the angle γ' at the light — what an
// engine can run per point and spot (at most 16 × 3 × 6 closed-form evaluations).
//
//   G^spot_n(T = 0) = ∫ dφ' ∫ dγ' f(θ(ŵ(φ', γ'))) J_n(φ', γ'),
//   J_n = ∫_0^{π−γ'} max(cos θ cos χ + sin θ cos φ' sin χ, 0)^n dχ = R^n ∫ cos^n u du
//
// with R cos(χ − c) = cos θ cos χ + sin θ cos φ' sin χ (c = atan2(sin θ cos φ', cos θ)), u = χ − c
// over the part of [0, π − γ'] where the cosine is positive, and ∫ cos^n by the reduction
// n I_n = [cos^{n−1} u sin u] + (n − 1) I_{n−2} (every term of one sign on a positive-cosine
// interval up to the boundary terms, no growth of the rounding).
#include "scatterlut/spot_surface.hpp"

#include "require.hpp"

#include <algorithm>
#include <cmath>
#include <string>

extern "C" {
#include "slut_spot.h"
#include "slut_vec3.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

constexpr double kPi = 3.14159265358979323846;
constexpr int kAzimuths = 16; // φ' nodes (trapezoid over a full turn, or Gauss–Legendre in t below)
// 6-point Gauss–Legendre on [−1, 1]: nodes ±x, weights w.
constexpr double kGlX[3] = {0.238619186083196908630501721680712, 0.661209386466264513661399595019906,
                            0.932469514203152027812301554493995};
constexpr double kGlW[3] = {0.467913934572691047389870343989551, 0.360761573048138607569833513837716,
                            0.171324492379170345040296142172733};
// 16-point Gauss–Legendre on [−1, 1] for the azimuths of a beam seen from outside.
constexpr double kGl16X[8] = {0.0950125098376374401853193354249581, 0.281603550779258913230460501460496,
                              0.458016777657227386342419442983578,  0.617876244402643748446671764048791,
                              0.755404408355003033895101194847442,  0.865631202387831743880467897712393,
                              0.944575023073232576077988415534608,  0.989400934991649932596154173450333};
constexpr double kGl16W[8] = {0.189450610455068496285396723208283, 0.182603415044923588866763667969220,
                              0.169156519395002538189312079030360, 0.149595988816576732081501730547479,
                              0.124628971255533872052476282192016, 0.095158511682492784809925107602246,
                              0.062253523938647892862843836994378, 0.027152459411754094851780572456018};

double dot3(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 lin(double a, const Vec3 &x, double b, const Vec3 &y) {
    return {a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2]};
}
double len3(const Vec3 &v) { return slut_vec3_length(slut_vec3_make(v[0], v[1], v[2])); }
Vec3 unit3(const Vec3 &v) { return lin(1.0 / len3(v), v, 0.0, v); }

// ∫_{u0}^{u1} cos^n u du for cos ≥ 0 on [u0, u1] ⊂ [−π/2, π/2], n ≥ 1.
double cos_power_integral(int n, double u0, double u1) {
    const double c0 = std::cos(u0), s0 = std::sin(u0), c1 = std::cos(u1), s1 = std::sin(u1);
    double even = u1 - u0, odd = s1 - s0; // I_0, I_1
    double p0 = 1.0, p1 = 1.0;            // cos^{k−1} at the ends, for k = 1
    for (int k = 2; k <= n; ++k) {
        p0 *= c0;
        p1 *= c1;
        const double next = (p1 * s1 - p0 * s0) / k + (k - 1.0) / k * (k % 2 == 0 ? even : odd);
        (k % 2 == 0 ? even : odd) = next;
    }
    return std::max(n % 2 == 0 ? even : odd, 0.0);
}

struct ThinRule {
    int n = 1;
    double cos_lobe = 1, sin_lobe = 0;
    double mP = 0, m1 = 0, m2 = 0; // the spot's unit axis in the frame (ŵ_P, e1, e2)
    double vers_outer = 0, vers_inner = 0;
    double sin_cone[2] = {0, 0}, cos_cone[2] = {1, 1};
    int cones = 0;

    double falloff(double cos_phi, double sin_phi, double gamma) const {
        const double cg = std::cos(gamma), sg = std::sin(gamma);
        const double x = cg - mP, y = sg * cos_phi - m1, z = sg * sin_phi - m2;
        return slut_spot_falloff(0.5 * (x * x + y * y + z * z), vers_outer, vers_inner);
    }

    // J_n(φ', γ'): the χ integral in closed form.
    double J(double cos_phi, double gamma) const {
        const double A = cos_lobe, B = sin_lobe * cos_phi, R = std::hypot(A, B);
        if (!(R > 0.0)) return 0.0;
        const double c = std::atan2(B, A), X = kPi - gamma;
        double sum = 0.0;
        for (double shift : {-2.0 * kPi, 0.0, 2.0 * kPi}) { // the positive half-period (c − π/2, c + π/2) mod 2π
            const double lo = std::max(0.0, c + shift - 0.5 * kPi), hi = std::min(X, c + shift + 0.5 * kPi);
            if (hi > lo) sum += cos_power_integral(n, lo - c - shift, hi - c - shift);
        }
        return n == 1 ? R * sum : std::pow(R, n) * sum;
    }

    // ∫_0^π f J dγ' on the half great circle of azimuth φ': Gauss–Legendre on each piece
    // between the cones' crossings (closed form, as spot_surface.cpp), the unlit ones skipped.
    double along(double phi) const {
        const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
        double breaks[16] = {0.0, kPi}; // the ends and per cone two crossings (≤ 6 in all)
        int count = 2;
        const double a = mP, b = m1 * cos_phi + m2 * sin_phi, mp = std::fabs(m2 * cos_phi - m1 * sin_phi);
        const double alpha = std::atan2(b, a);
        for (int k = 0; k < cones; ++k) {
            const double room = (sin_cone[k] - mp) * (sin_cone[k] + mp);
            if (!(room >= 0.0)) continue;
            const double delta = std::atan2(std::sqrt(room), cos_cone[k]);
            for (double g : {alpha - delta, alpha + delta})
                for (double shift : {-2.0 * kPi, 0.0, 2.0 * kPi})
                    if (g + shift > 0.0 && g + shift < kPi && count < 16) breaks[count++] = g + shift;
        }
        std::sort(breaks, breaks + count);
        double sum = 0.0;
        for (int i = 0; i + 1 < count; ++i) {
            const double lo = breaks[i], hi = breaks[i + 1];
            if (!(hi > lo) || !(falloff(cos_phi, sin_phi, 0.5 * (lo + hi)) > 0.0)) continue;
            const double mid = 0.5 * (lo + hi), half = 0.5 * (hi - lo);
            for (int j = 0; j < 3; ++j)
                for (double sign : {-1.0, 1.0}) {
                    const double g = mid + sign * half * kGlX[j];
                    const double f = falloff(cos_phi, sin_phi, g);
                    if (f > 0.0) sum += kGlW[j] * half * f * J(cos_phi, g);
                }
        }
        return sum;
    }
};

} // namespace

double spot_surface_G_thin(int exponent, const SpotSurfacePoint &q) {
    require(exponent >= 1 && exponent <= kSurfaceMaxExponent,
            "exponent must be an integer in [1, " + std::to_string(kSurfaceMaxExponent) + "]");
    check_spot_surface_point(q);
    const double outer = std::min(q.light.outer_angle_rad, kPi), inner = std::min(q.light.inner_angle_rad, kPi);
    if (!(outer > 0.0)) return 0.0;
    ThinRule r;
    r.n = exponent;
    // The frame of spot_surface.cpp: ŵ_P from the light to P, e1 the lobe axis' component across it.
    const Vec3 wP = unit3(lin(1.0, q.point_m, -1.0, q.light.position_m)), to_light = lin(-1.0, wP, 0.0, wP);
    const Vec3 lobe = unit3(q.lobe_axis);
    r.cos_lobe = std::clamp(dot3(lobe, to_light), -1.0, 1.0);
    Vec3 across = lin(1.0, lobe, -r.cos_lobe, to_light);
    if (!(len3(across) > 1e-10)) {
        const int k = std::fabs(wP[0]) <= std::fabs(wP[1]) && std::fabs(wP[0]) <= std::fabs(wP[2]) ? 0
                      : (std::fabs(wP[1]) <= std::fabs(wP[2]) ? 1 : 2);
        across = {0, 0, 0};
        across[static_cast<size_t>(k)] = 1.0;
    }
    across = lin(1.0, across, -dot3(across, wP), wP);
    across = lin(1.0, across, -dot3(across, wP), wP);
    const Vec3 e1 = unit3(across);
    const Vec3 e2{wP[1] * e1[2] - wP[2] * e1[1], wP[2] * e1[0] - wP[0] * e1[2], wP[0] * e1[1] - wP[1] * e1[0]};
    r.sin_lobe = std::max(0.0, dot3(lobe, e1));
    const Vec3 m = unit3(q.light.direction);
    r.mP = dot3(m, wP);
    r.m1 = dot3(m, e1);
    r.m2 = dot3(m, e2);
    r.vers_outer = slut_spot_versine(outer);
    r.vers_inner = slut_spot_versine(inner);
    const auto add_cone = [&r](double angle) {
        r.sin_cone[r.cones] = std::sin(angle);
        r.cos_cone[r.cones] = std::cos(angle);
        ++r.cones;
    };
    if (outer < kPi) add_cone(outer);
    if (inner > 0.0 && inner < outer) add_cone(inner);
    // The azimuths: a full turn (trapezoid, periodic) when every half great circle from ŵ_P
    // meets the beam (P inside it, θ_o ≥ π/2, or −ŵ_P inside it); otherwise only those within Φ of
    // the beam's azimuth φ_c, sin Φ = sin θ_o/sin θ_P, by Gauss–Legendre in t with
    // φ' = φ_c + Φ sin t (the √ ends at ±Φ become smooth).
    const double vers_P = 0.5 * ((1.0 - r.mP) * (1.0 - r.mP) + r.m1 * r.m1 + r.m2 * r.m2); // of ŵ_P
    const double vers_back = 0.5 * ((1.0 + r.mP) * (1.0 + r.mP) + r.m1 * r.m1 + r.m2 * r.m2); // of −ŵ_P
    const double Q = std::hypot(r.m1, r.m2);
    if (vers_P <= r.vers_outer || outer >= 0.5 * kPi || vers_back <= r.vers_outer || !(std::sin(outer) < Q)) {
        double sum = 0.0;
        for (int k = 0; k < kAzimuths; ++k) sum += r.along(2.0 * kPi * (k + 0.5) / kAzimuths);
        return sum * 2.0 * kPi / kAzimuths;
    }
    const double centre = std::atan2(r.m2, r.m1), half_width = std::asin(std::sin(outer) / Q);
    double sum = 0.0;
    for (int k = 0; k < 8; ++k)
        for (double sign : {-1.0, 1.0}) {
            const double t = sign * 0.5 * kPi * kGl16X[k];
            sum += kGl16W[k] * 0.5 * kPi * half_width * std::cos(t) * r.along(centre + half_width * std::sin(t));
        }
    return sum;
}

double spot_surface_thin_factor(int exponent, const SpotSurfacePoint &q, double point_G) {
    require(std::isfinite(point_G) && point_G >= 0.0, "point_G must be finite and >= 0");
    if (!(point_G > 0.0)) return 0.0;
    const double D = len3(lin(1.0, q.point_m, -1.0, q.light.position_m));
    const double thin = std::exp(-(q.sigma_s_per_m + q.sigma_a_per_m) * D) * spot_surface_G_thin(exponent, q);
    return std::min(1.0, thin / point_G);
}

} // namespace scatterlut
