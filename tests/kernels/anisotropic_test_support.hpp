// The anisotropic (Henyey–Greenstein) tests' shared references (tests/kernels/test_anisotropic*.cpp):
// Boost.Math Gauss–Kronrod quadrature of the physical integrals in x (long double, break points of
// their own), the queries they share, and their tolerances' bookkeeping.
#pragma once

#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "nearlight_reference.hpp"
#include "reference_data.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/nearlight_hg.hpp"

#include <boost/math/special_functions/ellint_2.hpp>

extern "C" {
#include "slut_airlight_hg.h"
#include "slut_nearlight_hg.h"
}

namespace {

using slut_ref::real;
using scatterlut::Rgb;

constexpr double kPi = 3.14159265358979323846;
constexpr double kPio2 = 1.5707963267948966;
const double kG[] = {-0.99, -0.9, -0.5, 0.3, 0.8, 0.95, 0.99};

double rel(double a, double b) {
    if (a == b) return 0.0;
    return std::fabs(a - b) / std::fabs(b);
}

// ψ_g = 4π p_g in long double from cos θ = −y/d (y = signed offset past the foot point, d the
// distance to the light): 1 + g² − 2g cos θ = (1 − g)² + 2g (d + y)/d, with d + y = b²/(d − y)
// for y < 0 (b² = d² − y²). Written here independently of kernels/slut_phase.h.
real ref_psi(real g, real y, real d, real b2) {
    const real d_plus_y = (y >= 0) ? d + y : b2 / (d - y);
    const real den = (1 - g) * (1 - g) + 2 * g * d_plus_y / d;
    return (1 - g) * (1 + g) / (den * std::sqrt(den));
}

// The anisotropic airlight by quadrature of the physical integral in x,
//   L = σ_s I0 ∫_0^s p_g(θ(x)) e^{−σ_t (x + d(x))} / d(x)² dx,  cos θ(x) = (D cos γ − x)/d(x),
// panels with break points at the closest approach x* = D cos γ and x* ± ℓ 2^k (ℓ the closest
// distance, or the distance from x* to the ray), each at most 8/σ_t wide, 61-point
// Gauss–Kronrod in long double per panel (slut_ref::integrate_piece, tol 1e-17).
double ref_airlight_hg(double sigma_s, double sigma_a, double I0, double D, double gamma, double s, double g) {
    const real st = (real)sigma_s + sigma_a;
    const real cg = std::cos((real)gamma), sgm = std::sin((real)gamma);
    const real xs = D * cg, b = D * std::fabs(sgm), b2 = b * b;
    if (b == 0 && xs >= 0 && s >= xs) return std::numeric_limits<double>::infinity();
    auto f = [&](real x) {
        const real y = x - xs, d2 = y * y + b2, d = std::sqrt(d2);
        const real excess = x * (1 + (x - 2 * xs) / (d + D)); // x + d − D
        return ref_psi(g, y, d, b2) * std::exp(-st * excess) / d2;
    };
    real dist = 0;
    if (xs < 0) dist = -xs; else if (xs > s) dist = xs - s;
    const real ell = std::max(b, dist);
    std::vector<real> pts{0};
    if (xs > 0 && xs < s) pts.push_back(xs);
    for (real m = ell; m < 1e300L; m *= 2) {
        if (xs - m > 0 && xs - m < s) pts.push_back(xs - m);
        if (xs + m > 0 && xs + m < s) pts.push_back(xs + m);
        if (xs - m <= 0 && xs + m >= s) break;
    }
    const bool infinite = !std::isfinite(s);
    if (!infinite) pts.push_back(s);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    const real cap = st > 0 ? 8 / st : std::numeric_limits<real>::infinity();
    const real psi_max = (1 + std::fabs((real)g)) / ((1 - std::fabs((real)g)) * (1 - std::fabs((real)g)));
    real sum = 0, a = 0;
    size_t next = 1;
    for (int panel = 0; panel < 100000 && (infinite || a < (real)s); ++panel) {
        real end = (next < pts.size()) ? pts[next] : a + std::max(a - xs, ell);
        if (end - a > cap) end = a + cap;
        if (!infinite && !(end < (real)s)) end = s;
        sum += slut_ref::integrate_piece(f, a, end, 1e-15L, nullptr);
        a = end;
        while (next < pts.size() && pts[next] <= a) ++next;
        if (a > xs) { // remainder past x*: d grows, x + d − D grows ≥ x − a
            const real y = a - xs, d2 = y * y + b2;
            real bound = 1 / y;
            if (st > 0) bound = std::min(bound, 1 / (st * d2));
            const real fa = std::exp(-st * (a * (1 + (a - 2 * xs) / (std::sqrt(d2) + D)))) / d2;
            if (fa * psi_max * d2 * bound < 1e-19L * sum) break;
        }
    }
    return (double)((real)sigma_s * I0 / (4 * (real)kPi) * std::exp(-st * (real)D) * sum);
}

// G̃_g(u, w) = (1/w) ∫_0^∞ e^{−u y} ψ_g(2ξ) / (1 + t²) dy, t = cot w + y = tan ξ, with
// cos 2ξ = (1 − t²)/(1 + t²) in long double, break points at the peak scales and 2^k/u.
double ref_scaled_tail_hg(double u, double w, double g) {
    const real tau = std::cos((real)w) / std::sin((real)w);
    auto f = [&](real y) {
        const real t = tau + y, t2 = t * t;
        // 1 + g² − 2g cos 2ξ = ((1 − g)² + (1 + g)² t²)/(1 + t²)
        const real den = ((1 - g) * (1 - g) + (1 + g) * (1 + g) * t2) / (1 + t2);
        return std::exp(-(real)u * y) * (1 - g) * (1 + g) / (den * std::sqrt(den)) / (1 + t2);
    };
    std::vector<real> pts;
    const real peak = std::min((real)1, (1 - (real)g) / (1 + (real)g));
    for (int k = -4; k < 90; ++k) {
        pts.push_back(std::ldexp(peak, k));
        pts.push_back(tau * std::ldexp(1.0L, k));
        if (u > 0) pts.push_back(std::ldexp(1.0L, k) / u);
    }
    const real cap = (u > 0) ? 1e3L / u : 1e30L;
    std::vector<real> kept;
    for (real p : pts)
        if (p > 0 && p < cap) kept.push_back(p);
    const real sum = slut_ref::integrate_with_breaks(f, kept, std::numeric_limits<real>::infinity(), 1e-15L, nullptr,
                                                     true);
    return (double)(sum / w);
}

// N_g(T, g_nl, r, S) = ∫_0^S ψ(θ) exp(−t − ĥ t/(t + T r))/ĥ² dt, cos θ = −(t + T g_nl)/ĥ, with
// slut_ref::nearlight_breaks and its quadrature; E_g = N_g/H with H by quadrature as well.
slut_ref::NearLightValue ref_nearlight_hg(double T_in, double gnl_in, double r_in, double S_in, double phase_g) {
    const real T = T_in, gn = gnl_in, r = r_in, G = phase_g;
    const real S = std::isinf(S_in) ? std::numeric_limits<real>::infinity() : real(S_in);
    const real sg2 = (1 - std::fabs(gn)) * (1 + std::fabs(gn));
    const real c = T * r, w2 = T * T * sg2;
    auto n_integrand = [=](real t) {
        const real y = t + T * gn, h2 = y * y + w2, h = std::sqrt(h2);
        const real q = (r > 0) ? (std::isinf(c) ? real(0) : t / (t + c)) : real(1);
        return ref_psi(G, y, h, w2) * std::exp(-t - h * q) / h2;
    };
    auto h_integrand = [=](real t) { const real y = t + T * gn; return 1 / (y * y + w2); };
    const std::vector<real> pts = slut_ref::nearlight_breaks(T, gn, r, S);
    slut_ref::NearLightValue v{};
    v.N = slut_ref::integrate_with_breaks(n_integrand, pts, S, 1e-15L, nullptr);
    v.H = slut_ref::integrate_with_breaks(h_integrand, pts, S, 1e-15L, nullptr, true);
    v.E = v.N / v.H;
    return v;
}

scatterlut::AirlightQuery air_query(double ss, double sa, double I0, double D, double gamma, double s) {
    scatterlut::AirlightQuery q;
    q.sigma_s_per_m = ss;
    q.sigma_a_per_m = sa;
    q.intensity_W_per_sr = I0;
    q.distance_m = D;
    q.gamma_rad = gamma;
    q.length_m = s;
    return q;
}

} // namespace
