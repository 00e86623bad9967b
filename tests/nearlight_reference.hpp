// An independent CPU reference for the near-light integral (docs/PHYSICS.md §1.2), built on
// Boost.Math adaptive Gauss–Kronrod quadrature in long double. It shares no code with
// kernels/slut_nearlight.h (which it must never include): different rule (61-point
// Gauss–Kronrod, adaptive), different precision (x87 long double), break points placed by
// a fixed list instead of the header's panel rules, H by quadrature instead of its closed form.
//
//   N(T, g, r, S) = ∫_0^S exp(−t − ĥ(t)·t/(t + T r)) / ĥ(t)² dt,   ĥ² = t² + T² + 2 t T g
//   H(T, g, S)    = ∫_0^S ĥ^{−2} dt,   E = N/H
//
// Break points: 0; T·4^k (the scale of 1/ĥ² near t = 0 for small T); c·2^k, c = T r (the
// boundary layer of width ≈ c); t* = −T g and t* ± w·2^k, w = T√(1−g²) (the near-singular
// peak when g → −1); 2^k for the e^{−t} decay. Each finite piece [a, b] is integrated as
// ∫_0^1 (b − a) f(a + (b − a) x) dx: Boost's gauss_kronrod compares the error estimate of the
// unscaled rule with tol·|estimate|, so unscaled narrow pieces recurse to max depth
// (docs/POCL.md, "Boost.Math pitfall"). The tail [a, ∞) uses t = a + x/(1 − x).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace slut_ref {

using real = long double;

struct Counter {
    long evals = 0;
};

// ∫_a^b f by 61-point Gauss–Kronrod on [0, 1] after scaling (relative tolerance tol).
template <class F> real integrate_piece(const F &f, real a, real b, real tol, Counter *count) {
    if (!(b > a)) return 0;
    const real len = b - a;
    auto scaled = [&](real x) {
        if (count) ++count->evals;
        return len * f(a + len * x);
    };
    real error = 0;
    return boost::math::quadrature::gauss_kronrod<real, 61>::integrate(scaled, real(0), real(1), 15, tol, &error);
}

// ∫_a^∞ f with t = a + L x/(1 − x), dt = L dx/(1 − x)²: L = 1 for integrands that decay
// like e^{−t}, L = a for algebraic tails (1/t² maps to a constant).
template <class F> real integrate_tail(const F &f, real a, real scale, real tol, Counter *count) {
    auto mapped = [&](real x) {
        if (count) ++count->evals;
        if (x >= 1) return real(0);
        const real one_minus = 1 - x;
        const real t = a + scale * x / one_minus;
        const real v = scale * f(t) / (one_minus * one_minus);
        return std::isfinite(v) ? v : real(0);
    };
    real error = 0;
    return boost::math::quadrature::gauss_kronrod<real, 61>::integrate(mapped, real(0), real(1), 15, tol, &error);
}

// ∫_0^end f (end may be +∞) split at the given break points (those outside (0, end) ignored).
// algebraic_tail: the integrand decays like a power of t, not exponentially (see integrate_tail).
template <class F>
real integrate_with_breaks(const F &f, std::vector<real> pts, real end, real tol, Counter *count,
                           bool algebraic_tail = false) {
    pts.push_back(0);
    const bool infinite = !(end < std::numeric_limits<real>::max());
    if (!infinite) pts.push_back(end);
    std::vector<real> kept;
    for (real p : pts)
        if (p >= 0 && (infinite || p <= end) && std::isfinite(p)) kept.push_back(p);
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    real sum = 0;
    for (size_t i = 0; i + 1 < kept.size(); ++i) sum += integrate_piece(f, kept[i], kept[i + 1], tol, count);
    if (infinite) sum += integrate_tail(f, kept.back(), algebraic_tail ? std::max(kept.back(), real(1)) : real(1), tol, count);
    return sum;
}

// The structural break points of the near-light integrand (see the file comment).
inline std::vector<real> nearlight_breaks(real T, real g, real r, real end) {
    std::vector<real> pts;
    const real span = std::min(end, real(4) * T + real(200));
    for (int k = -6; k <= 8; ++k) pts.push_back(T * std::ldexp(real(1), 2 * k));
    const real c = T * r;
    if (c > 0 && std::isfinite(c))
        for (int k = -8; k <= 60; ++k) {
            const real p = c * std::ldexp(real(1), k);
            if (p > span) break;
            pts.push_back(p);
        }
    if (g < 0) {
        const real t_star = -T * g, w = T * std::sqrt((1 - std::fabs(g)) * (1 + std::fabs(g)));
        pts.push_back(t_star);
        for (int k = 0; k <= 80; ++k) {
            const real off = w * std::ldexp(real(1), k);
            if (off > t_star + span) break;
            pts.push_back(t_star - off);
            pts.push_back(t_star + off);
        }
    }
    for (int k = -3; k <= 7; ++k) pts.push_back(std::ldexp(real(1), k));
    return pts;
}

struct NearLightValue {
    real N, H, E;
    long evals;
};

// N, H and E = N/H by quadrature (relative accuracy ~1e-15 for T ∈ [1e-3, 100],
// g ∈ [−0.999999, 1]). r may be 0 (the integrand is then exp(−t − ĥ)/ĥ² for t > 0) or +∞.
inline NearLightValue nearlight_NHE(double T_in, double g_in, double r_in, double S_in, real tol = 1e-15L) {
    const real T = T_in, g = g_in, r = r_in;
    const real S = std::isinf(S_in) ? std::numeric_limits<real>::infinity() : real(S_in);
    const real sg2 = (1 - std::fabs(g)) * (1 + std::fabs(g)); // 1 − g² without cancellation
    const real c = T * r;
    auto hat_h2 = [=](real t) { const real d = t + T * g; return d * d + T * T * sg2; };
    auto n_integrand = [=](real t) {
        const real h2 = hat_h2(t);
        const real q = (r > 0) ? (std::isinf(c) ? real(0) : t / (t + c)) : real(1);
        return std::exp(-t - std::sqrt(h2) * q) / h2;
    };
    auto h_integrand = [=](real t) { return 1 / hat_h2(t); };
    Counter count;
    const std::vector<real> pts = nearlight_breaks(T, g, r, S);
    NearLightValue v;
    v.N = integrate_with_breaks(n_integrand, pts, S, tol, &count);
    // ĥ^{−2} decays only like 1/t²: its tail is mapped with the algebraic scale.
    v.H = integrate_with_breaks(h_integrand, pts, S, tol, &count, true);
    v.E = v.N / v.H;
    v.evals = count.evals;
    return v;
}

} // namespace slut_ref
