// The spot's surface terms, exact (scatterlut/spot_surface.hpp; docs/SPOT.md "Surfaces lit by
// a spot"): the scattered irradiance E_ss and the specular lobe S_n of a surface point P lit by
// a glTF spot through the medium, as a triple integral over the medium around the light.
//
// Coordinates. D = |L − P|, ŵ_P = (P − L)/D, ω_l = −ŵ_P (the direction from P to the light).
// A frame (ŵ_P, e1, e2), e1 ⊥ ŵ_P in the plane of ω_l and the lobe axis ℓ, e2 = ŵ_P × e1.
// A scattering point x is given by the plane through L and P it lies in (azimuth φ' about ŵ_P,
// u(φ') = cos φ' e1 + sin φ' e2) and by the angles of the triangle L, P, x: γ' at L (between ŵ_P
// and the direction ŵ = cos γ' ŵ_P + sin γ' u the light emits x's light into) and χ at P (between
// ω_l and the direction ω = cos χ ω_l + sin χ u from P to x), γ' + χ < π. By the law of sines
// d = |x − L| = D sin χ/sin(γ' + χ), r = |x − P| = D sin γ'/sin(γ' + χ), and the volume element
// is dV = d² r² dγ' dχ dφ'/D. Sun et al. 2005's E_ss (or S_n) is the integral over the medium of
// σ_s/(4π) · I0 f(θ(ŵ)) e^{−σ_t (d + r)}/(d² r²) · max(ℓ·ω, 0)^n dV, hence
//
//   G^spot_n = ∫_0^{2π} dφ' ∫_0^π dγ' f(ŵ(φ', γ')) ∫_0^{π−γ'} e^{−T s(γ', χ)} max(ℓ·ω(φ', χ), 0)^n dχ
//   T = σ_t D,  s = (d + r)/D = (sin χ + sin γ')/sin(γ' + χ) ≥ 1,  ℓ·ω = cos θ cos χ + sin θ sin χ cos φ'
//
// (θ the angle between ℓ and ω_l). The integrand is bounded (≤ 1): the 1/r² and 1/d² of the
// point light are gone, so the only features are where f, the lobe or the extinction change
// fast. f depends on (φ', γ') only: for each φ' the half great circle ŵ(φ', ·) enters and leaves
// the outer and the inner cones at angles in closed form, so the middle integral is cut there
// and the pieces outside the outer cone are dropped. The outer integral is cut at the azimuths
// where those great circles graze the cones (√-type ends, smoothed by the smoothstep map of
// gauss_kronrod15.hpp), the inner where ℓ·ω changes sign and around a narrow lobe.
#include "scatterlut/spot_surface.hpp"

#include "gauss_kronrod15.hpp"
#include "require.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include "slut_spot.h"
#include "slut_surface_frontend.h" /* slut_surface_scattered_scale */
#include "slut_vec3.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp
using gk15::Piece;

constexpr double kPi = 3.14159265358979323846;
constexpr double kAngleMax = kPi + 1e-15; // the double nearest π and rounding above it

// The tolerance: a first pass at kCoarse (relative, every level) estimates G; the second pass
// asks each level for an absolute error of kTol·G spread over its range (the summed
// |K15 − G7|, which overestimates K15's own error by orders of magnitude on smooth pieces:
// the result is ~1e-8 relative, tests/kernels/test_spot_surface.cpp measures it).
constexpr double kTol = 1e-7, kCoarse = 1e-3;
constexpr double kExtinctionCut = 50.0; // T (s − 1) beyond which the inner integral stops
constexpr int kInnerPanels = 200, kMiddlePanels = 200, kOuterPanels = 400;

double dot(const Vec3 &a, const Vec3 &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
Vec3 cross(const Vec3 &a, const Vec3 &b) {
    return {a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
}
Vec3 combine(double a, const Vec3 &x, double b, const Vec3 &y) {
    return {a * x[0] + b * y[0], a * x[1] + b * y[1], a * x[2] + b * y[2]};
}
double length(const Vec3 &v) { return slut_vec3_length(slut_vec3_make(v[0], v[1], v[2])); }
Vec3 unit(const Vec3 &v) {
    const double n = length(v);
    return {v[0] / n, v[1] / n, v[2] / n};
}
bool finite3(const Vec3 &v) { return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]); }

// Keeps the angles of `candidates` that lie strictly inside (lo, hi).
void keep_inside(std::vector<double> &out, std::initializer_list<double> candidates, double lo, double hi) {
    for (double c : candidates)
        if (c > lo && c < hi) out.push_back(c);
}
// The same for angles defined modulo 2π (each candidate also shifted by ±2π).
void keep_inside_mod(std::vector<double> &out, std::initializer_list<double> candidates, double lo, double hi) {
    for (double c : candidates)
        for (double shift : {-2.0 * kPi, 0.0, 2.0 * kPi})
            if (c + shift > lo && c + shift < hi) out.push_back(c + shift);
}

// Sorted, unique break points → pieces.
std::vector<Piece> pieces_of(std::vector<double> &breaks) {
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    std::vector<Piece> out;
    for (size_t i = 0; i + 1 < breaks.size(); ++i) out.push_back({breaks[i], breaks[i + 1]});
    return out;
}

// The geometry of one evaluation in the frame (ŵ_P, e1, e2) (see the top of this file).
struct Geometry {
    int n = 1;                           // the lobe's exponent
    double T = 0;                        // σ_t D
    double cos_lobe = 1, sin_lobe = 0;   // θ: the lobe axis ℓ against ω_l
    double lobe_width = 1;               // 1/√(n + 1), rad
    double mP = 0, m1 = 0, m2 = 0;       // the spot's unit axis in the frame
    double vers_outer = 0, vers_inner = 0;
    double sin_cone[2] = {0, 0};         // sin θ_o, sin θ_i
    double cos_cone[2] = {1, 1};         // cos θ_o, cos θ_i
    int cones = 0;                       // how many of the two cones have an edge (0 < θ < π)
    // The current pass's tolerances: relative on every level, absolute on the inner and middle.
    double rel_tol = kCoarse, inner_abs = 0, middle_abs = 0;

    double falloff(double cos_phi, double sin_phi, double cos_g, double sin_g) const {
        const double x = cos_g - mP, y = sin_g * cos_phi - m1, z = sin_g * sin_phi - m2;
        return slut_spot_falloff(0.5 * (x * x + y * y + z * z), vers_outer, vers_inner);
    }

    // The lobe's weight max(ℓ·ω, 0)^n from cos χ and sin χ.
    double lobe_weight(double cos_phi, double cos_chi, double sin_chi) const {
        const double lobe = cos_lobe * cos_chi + sin_lobe * sin_chi * cos_phi;
        if (!(lobe > 0.0)) return 0.0;
        return n == 1 ? lobe : std::pow(lobe, n);
    }

    // The innermost integrand: e^{−T s} max(ℓ·ω, 0)^n at (φ', γ', χ).
    double inner(double cos_phi, double sin_g, double gamma, double chi) const {
        const double sin_chi = std::sin(chi), w = lobe_weight(cos_phi, std::cos(chi), sin_chi);
        if (T == 0.0 || w == 0.0) return w;
        const double s = (sin_chi + sin_g) / std::sin(gamma + chi);
        return s > 0.0 ? w * std::exp(-T * s) : 0.0; // s ≤ 0 only where rounding meets γ' + χ = π
    }

    // The angle χ at P of the point on the ray from the light at polar angle γ' whose light
    // path d + r is S·D (S ≥ 1): the ellipse with foci L and P meets the ray at
    // d = D (S² − 1)/(2 (S − cos γ')), and tan χ = d sin γ'/(D − d cos γ').
    static double chi_of_path(double S, double cos_g, double sin_g) {
        const double d = (S - 1.0) * (S + 1.0) / (2.0 * (S - cos_g)); // in units of D
        return std::atan2(d * sin_g, 1.0 - d * cos_g);
    }

    // ∫_0^{π−γ'} inner dχ. Without extinction in χ. With it, in two parts: χ up to the light
    // path 2D (S = s ≤ 2), and beyond in z = ln S up to T (S − 1) = kExtinctionCut, where
    // dχ = 2 sin γ'/(S² − 2S cos γ' + 1) dS (from chi_of_path): e^{−T S} falls smoothly in z
    // however small T is, where in χ it would fall within a sliver below π − γ'.
    double inner_integral(double cos_phi, double gamma) const {
        const double sin_g = std::sin(gamma), cos_g = std::cos(gamma);
        const double A = cos_lobe, B = sin_lobe * cos_phi, centre = std::atan2(B, A);
        // ℓ·ω's zero crossings and a narrow lobe's flanks, as angles χ (mod 2π).
        const auto lobe_breaks = [&](std::vector<double> &out, double lo, double hi) {
            keep_inside_mod(out, {centre - 0.5 * kPi, centre + 0.5 * kPi}, lo, hi);
            if (n > 1) keep_inside_mod(out, {centre - 4.0 * lobe_width, centre + 4.0 * lobe_width}, lo, hi);
        };
        const auto in_chi = [&](double chi) { return inner(cos_phi, sin_g, gamma, chi); };
        if (T == 0.0) {
            std::vector<double> breaks{0.0, kPi - gamma};
            lobe_breaks(breaks, 0.0, kPi - gamma);
            return gk15::integrate(in_chi, pieces_of(breaks), false, rel_tol, inner_abs, kInnerPanels);
        }
        const double S_end = 1.0 + kExtinctionCut / T, S_split = std::min(2.0, S_end);
        const double chi_split = chi_of_path(S_split, cos_g, sin_g);
        std::vector<double> near{0.0, chi_split};
        lobe_breaks(near, 0.0, chi_split);
        for (double k : {1.0, 4.0, 16.0})
            if (1.0 + k / T < S_split) near.push_back(chi_of_path(1.0 + k / T, cos_g, sin_g));
        double sum = gk15::integrate(in_chi, pieces_of(near), false, rel_tol, inner_abs, kInnerPanels);
        if (!(S_end > S_split)) return sum;
        std::vector<double> far{std::log(S_split), std::log(S_end)};
        std::vector<double> far_chi;
        lobe_breaks(far_chi, chi_split, kPi - gamma);
        for (double chi : far_chi) {
            const double S = (std::sin(chi) + sin_g) / std::sin(gamma + chi);
            if (S > S_split && S < S_end) far.push_back(std::log(S));
        }
        const auto in_z = [&](double z) {
            const double S = std::exp(z), Sc = S - cos_g, q = Sc * Sc + sin_g * sin_g; // q = S² − 2S cos γ' + 1
            const double d = (S - 1.0) * (S + 1.0) / (2.0 * Sc), x = 1.0 - d * cos_g, y = d * sin_g;
            const double rho = std::hypot(x, y); // r/D
            const double w = lobe_weight(cos_phi, x / rho, y / rho);
            return w > 0.0 ? w * std::exp(-T * S) * 2.0 * sin_g * S / q : 0.0;
        };
        sum += gk15::integrate(in_z, pieces_of(far), false, rel_tol, inner_abs, kInnerPanels);
        return sum;
    }

    // ∫_0^π f ∫ inner dχ dγ' on the half great circle of azimuth φ'.
    double middle_integral(double phi) const {
        const double cos_phi = std::cos(phi), sin_phi = std::sin(phi);
        std::vector<double> breaks{0.0, kPi};
        // The cones' edges: m·ŵ = a cos γ' + b sin γ' = R cos(γ' − α) with R² = 1 − (m·p)², p = ŵ_P × u
        // the great circle's pole; it crosses the cone of half-angle θ_c where cos(γ' − α) = cos θ_c/R:
        // γ' = α ± Δ, Δ = atan2(√(sin²θ_c − (m·p)²), cos θ_c) (no cancellation for narrow cones).
        const double a = mP, b = m1 * cos_phi + m2 * sin_phi, mp = std::fabs(m2 * cos_phi - m1 * sin_phi);
        const double alpha = std::atan2(b, a);
        for (int c = 0; c < cones; ++c) {
            const double room = (sin_cone[c] - mp) * (sin_cone[c] + mp);
            if (!(room >= 0.0)) continue;
            const double delta = std::atan2(std::sqrt(room), cos_cone[c]);
            keep_inside_mod(breaks, {alpha - delta, alpha + delta}, 0.0, kPi);
        }
        // Where the χ range [0, π − γ'] ends on the lobe's features.
        const double centre = std::atan2(sin_lobe * cos_phi, cos_lobe);
        if (T == 0.0) keep_inside_mod(breaks, {kPi - (centre - 0.5 * kPi), kPi - (centre + 0.5 * kPi)}, 0.0, kPi);
        if (n > 1)
            keep_inside_mod(breaks, {kPi - (centre - 4.0 * lobe_width), kPi - (centre + 4.0 * lobe_width)}, 0.0, kPi);
        // The pieces outside the outer cone carry nothing.
        std::vector<Piece> lit;
        for (const Piece &p : pieces_of(breaks)) {
            const double mid = 0.5 * (p.a + p.b);
            if (falloff(cos_phi, sin_phi, std::cos(mid), std::sin(mid)) > 0.0) lit.push_back(p);
        }
        if (lit.empty()) return 0.0;
        return gk15::integrate(
            [&](double gamma) {
                const double f = falloff(cos_phi, sin_phi, std::cos(gamma), std::sin(gamma));
                return f > 0.0 ? f * inner_integral(cos_phi, gamma) : 0.0;
            },
            lit, true, rel_tol, middle_abs, kMiddlePanels);
    }

    // Two passes: kCoarse everywhere for an estimate of G, then the absolute tolerances.
    double integral() {
        std::vector<double> breaks{0.0, kPi, 2.0 * kPi};
        // Azimuths where the great circles graze a cone: |m·p(φ')| = sin θ_c with
        // m·p = m2 cos φ' − m1 sin φ' = Q cos(φ' + ψ).
        const double Q = std::hypot(m1, m2), psi = std::atan2(m1, m2);
        for (int c = 0; c < cones; ++c) {
            if (!(sin_cone[c] < Q)) continue;
            for (double sign : {1.0, -1.0}) {
                const double base = std::acos(sign * sin_cone[c] / Q);
                keep_inside_mod(breaks, {-psi + base, -psi - base}, 0.0, 2.0 * kPi);
            }
        }
        if (n > 1 && sin_lobe > 0.0)
            for (double k : {4.0, 12.0}) {
                const double half = k * lobe_width / sin_lobe;
                if (half < kPi) keep_inside(breaks, {half, 2.0 * kPi - half}, 0.0, 2.0 * kPi);
            }
        const std::vector<Piece> pieces = pieces_of(breaks);
        const auto outer = [this](double phi) { return middle_integral(phi); };
        rel_tol = kCoarse;
        inner_abs = middle_abs = 0.0;
        const double estimate = gk15::integrate(outer, pieces, true, kCoarse, 0.0, kOuterPanels);
        if (!(estimate > 0.0)) return 0.0;
        rel_tol = 0.0;
        inner_abs = kTol * estimate / (2.0 * kPi * kPi); // per unit of φ' and γ'
        middle_abs = kTol * estimate / (2.0 * kPi);      // per unit of φ'
        return gk15::integrate(outer, pieces, true, 0.0, kTol * estimate, kOuterPanels);
    }
};

Geometry geometry_of(int exponent, const SpotSurfacePoint &q) {
    Geometry g;
    g.n = exponent;
    g.lobe_width = 1.0 / std::sqrt(exponent + 1.0);
    const Vec3 to_point = combine(1.0, q.point_m, -1.0, q.light.position_m);
    const double D = length(to_point);
    g.T = (q.sigma_s_per_m + q.sigma_a_per_m) * D;
    const Vec3 wP = unit(to_point), to_light = combine(-1.0, wP, 0.0, wP), lobe = unit(q.lobe_axis);
    g.cos_lobe = std::clamp(dot(lobe, to_light), -1.0, 1.0);
    g.sin_lobe = length(cross(lobe, to_light));
    // e1: the lobe axis' component across ω_l (any direction across it when ℓ ∥ ω_l).
    Vec3 across = combine(1.0, lobe, -g.cos_lobe, to_light);
    if (!(length(across) > 1e-10)) {
        const int k = std::fabs(wP[0]) <= std::fabs(wP[1]) && std::fabs(wP[0]) <= std::fabs(wP[2]) ? 0
                      : (std::fabs(wP[1]) <= std::fabs(wP[2]) ? 1 : 2);
        across = {0, 0, 0};
        across[k] = 1.0;
    }
    across = combine(1.0, across, -dot(across, wP), wP); // exactly across ŵ_P (twice: rounding)
    across = combine(1.0, across, -dot(across, wP), wP);
    const Vec3 e1 = unit(across), e2 = cross(wP, e1);
    const Vec3 m = unit(q.light.direction);
    g.mP = dot(m, wP);
    g.m1 = dot(m, e1);
    g.m2 = dot(m, e2);
    const double outer = std::min(q.light.outer_angle_rad, kPi), inner = std::min(q.light.inner_angle_rad, kPi);
    g.vers_outer = slut_spot_versine(outer);
    g.vers_inner = slut_spot_versine(inner);
    // The cones with an edge: the outer for 0 < θ_o < π, the inner for 0 < θ_i < min(θ_o, π).
    const auto add_cone = [&g](double angle) {
        g.sin_cone[g.cones] = std::sin(angle);
        g.cos_cone[g.cones] = std::cos(angle);
        ++g.cones;
    };
    if (outer > 0.0 && outer < kPi) add_cone(outer);
    if (inner > 0.0 && inner < outer) add_cone(inner);
    return g;
}

} // namespace

void check_spot_surface_point(const SpotSurfacePoint &q) {
    const SpotLight &l = q.light;
    require(std::isfinite(q.sigma_s_per_m) && q.sigma_s_per_m >= 0.0, "sigma_s must be finite and >= 0 (1/m)");
    require(std::isfinite(q.sigma_a_per_m) && q.sigma_a_per_m >= 0.0, "sigma_a must be finite and >= 0 (1/m)");
    require(finite3(q.point_m), "point must hold finite coordinates (m)");
    require(finite3(q.lobe_axis) && length(q.lobe_axis) > 0.0, "lobe_axis (normal or mirror direction) must be "
                                                                "finite and non-zero");
    require(finite3(l.position_m), "light position must hold finite coordinates (m)");
    require(finite3(l.direction) && length(l.direction) > 0.0, "spot direction must be finite and non-zero");
    require(l.outer_angle_rad >= 0.0 && l.outer_angle_rad <= kAngleMax, "outer_angle must lie in [0, pi] (rad)");
    require(l.inner_angle_rad >= 0.0 && l.inner_angle_rad <= kAngleMax, "inner_angle must lie in [0, pi] (rad)");
    require(l.inner_angle_rad <= l.outer_angle_rad, "inner_angle must not exceed outer_angle");
    require(std::isfinite(l.intensity_W_per_sr) && l.intensity_W_per_sr >= 0.0,
            "intensity must be finite and >= 0 (W/sr)");
    const double D = length(combine(1.0, q.point_m, -1.0, q.light.position_m));
    require(D > 0.0 && std::isfinite(D), "the surface point must not sit on the light (distance 0)");
}

double spot_surface_G_exact(int exponent, const SpotSurfacePoint &q) {
    require(exponent >= 1 && exponent <= kSurfaceMaxExponent,
            "exponent must be an integer in [1, " + std::to_string(kSurfaceMaxExponent) + "]");
    check_spot_surface_point(q);
    if (!(q.light.outer_angle_rad > 0.0)) return 0.0;
    Geometry g = geometry_of(exponent, q);
    if (!(std::exp(-g.T) > 0.0)) return 0.0; // every light path is ≥ D: G ≤ π³ e^{−T} underflows
    return std::max(g.integral(), 0.0);
}

double spot_surface_irradiance_exact(const SpotSurfacePoint &q) { return spot_surface_specular_exact(q, 1); }

double spot_surface_specular_exact(const SpotSurfacePoint &q, int exponent) {
    require(exponent >= 1 && exponent <= kSurfaceMaxExponent,
            "exponent must be an integer in [1, " + std::to_string(kSurfaceMaxExponent) + "]");
    check_spot_surface_point(q);
    const double D = length(combine(1.0, q.point_m, -1.0, q.light.position_m));
    const double scale = slut_surface_scattered_scale(q.sigma_s_per_m, q.light.intensity_W_per_sr, D);
    if (!(scale > 0.0)) return 0.0;
    return scale * spot_surface_G_exact(exponent, q);
}

} // namespace scatterlut
