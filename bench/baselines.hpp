// The per-cell baselines the generators are measured against: Boost.Math
// gauss_kronrod<double, 15> on one thread, one table cell at a time, given the break
// points it needs to be as accurate as the table. Every finite piece [a, b] is integrated
// as ∫_0^1 (b − a) f(a + (b − a)x) dx: Boost compares the unscaled error estimate with
// tol·|estimate|, so narrow pieces integrated directly recurse to max depth
// (docs/POCL.md, "Boost.Math pitfall").
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "nearlight_reference.hpp" // slut_ref::nearlight_breaks: the near-light break points

extern "C" {
#include "slut_nearlight.h" // slut_nl_H_scaled: the closed-form H (E = N/H)
}

namespace slut_bench {

using Rule = boost::math::quadrature::gauss_kronrod<double, 15>;

template <class F> double piece(const F &f, double a, double b, double tol, long *evals) {
    const double h = b - a;
    if (!(h > 0)) return 0.0;
    auto g = [&](double x) {
        ++*evals;
        return f(a + h * x);
    };
    return h * Rule::integrate(g, 0.0, 1.0, 15, tol);
}

// G̃(u, w) = (1/w) ∫_0^∞ e^{−u y}/(1 + (τ + y)²) dy, τ = cot w (slut_airlight.h), per cell.
// Pieces [a, a + h], h = min(2 max(1, τ + a), 20/u): growing with the distance to the poles
// at y = −τ ± i and at most 20 e-folds of e^{−uy} each (break points at multiples of 1/u
// resolve the layer at y = 0 for large u); stop when the remainder bound
// e^{−ua}/(u(1 + (τ + a)²)) is below 1e-17 of the sum.
inline double scaled_tail(double u, double w, double tol, long *evals) {
    if (u == 0) return 1.0;
    const double tau = std::cos(w) / std::sin(w);
    auto f = [&](double y) {
        const double t = tau + y;
        return std::exp(-u * y) / (1.0 + t * t);
    };
    double sum = 0, a = 0;
    for (int p = 0; p < 100000; ++p) {
        const double h = std::min(2.0 * std::max(1.0, tau + a), 20.0 / u);
        sum += piece(f, a, a + h, tol, evals);
        a += h;
        const double t = tau + a;
        if (std::exp(-u * a) / (u * (1.0 + t * t)) < 1e-17 * sum) break;
    }
    return sum / w;
}

// E(T, g, r, S) = N/H per cell: N by pieces between the break points of
// slut_ref::nearlight_breaks (0, T·4^k, multiples of T·r, the peak t* = −T g and
// t* ± T√(1−g²)·2^k, 2^k) and a mapped tail t = a + x/(1 − x) for S = ∞; H in closed form.
inline double nearlight_E(double T, double g, double r, double S, double tol, long *evals) {
    const double sg2 = (1 - std::fabs(g)) * (1 + std::fabs(g));
    const double c = T * r;
    auto f = [=](double t) {
        const double d = t + T * g, h2 = d * d + T * T * sg2;
        const double q = (r > 0) ? t / (t + c) : 1.0;
        return std::exp(-t - std::sqrt(h2) * q) / h2;
    };
    const bool infinite = std::isinf(S);
    std::vector<double> pts{0.0};
    for (long double p : slut_ref::nearlight_breaks(T, g, r, infinite ? std::numeric_limits<long double>::infinity() : S))
        if (p > 0 && (infinite || p < S) && std::isfinite(static_cast<double>(p))) pts.push_back(static_cast<double>(p));
    if (!infinite) pts.push_back(S);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());
    double N = 0;
    for (size_t i = 0; i + 1 < pts.size(); ++i) N += piece(f, pts[i], pts[i + 1], tol, evals);
    if (infinite) {
        const double a = pts.back();
        auto tail = [&](double x) {
            ++*evals;
            if (x >= 1) return 0.0;
            const double om = 1 - x, v = f(a + x / om) / (om * om);
            return std::isfinite(v) ? v : 0.0;
        };
        N += Rule::integrate(tail, 0.0, 1.0, 15, tol);
    }
    const double H = slut_nl_H_scaled(g, infinite ? HUGE_VAL : S / T) / T;
    return N / H;
}

} // namespace slut_bench
