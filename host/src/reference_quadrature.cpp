#include "reference_quadrature.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <boost/math/quadrature/exp_sinh.hpp>
#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace scatterlut {
namespace {

using real = long double;
constexpr real kTolerance = 1e-15L;
constexpr unsigned kMaxDepth = 15;

// ∫_a^b f by adaptive `Points`-point Gauss–Kronrod on [0, 1] after scaling: Boost compares the
// error estimate of the unscaled rule with tol·|estimate|, so a narrow unscaled piece would
// recurse to the maximum depth.
template <class Real, unsigned Points, class F>
Real scaled_piece(const F &f, Real a, Real b, unsigned max_depth, Real tolerance) {
    if (!(b > a)) return 0;
    const Real len = b - a;
    auto scaled = [&](Real x) { return len * f(a + len * x); };
    Real error = 0;
    return boost::math::quadrature::gauss_kronrod<Real, Points>::integrate(scaled, Real(0), Real(1), max_depth,
                                                                           tolerance, &error);
}

// The airlight's and near light's pieces: 61 points in long double.
template <class F> real piece(const F &f, real a, real b) { return scaled_piece<real, 61>(f, a, b, kMaxDepth, kTolerance); }

// ∫_a^∞ f with t = a + L x/(1 − x), dt = L dx/(1 − x)²: L the scale of the decay.
template <class F> real tail(const F &f, real a, real scale) {
    auto mapped = [&](real x) {
        if (x >= 1) return real(0);
        const real one_minus = 1 - x;
        const real v = scale * f(a + scale * x / one_minus) / (one_minus * one_minus);
        return std::isfinite(v) ? v : real(0);
    };
    real error = 0;
    return boost::math::quadrature::gauss_kronrod<real, 61>::integrate(mapped, real(0), real(1), kMaxDepth,
                                                                       kTolerance, &error);
}

// ∫_0^end f (end may be +∞) over the pieces between the break points inside (0, end), the
// last piece of an infinite range mapped with `tail_scale` (0: the last break point).
template <class F> real integrate(const F &f, std::vector<real> breaks, real end, real tail_scale) {
    const bool infinite = !(end < std::numeric_limits<real>::max());
    std::vector<real> kept = {0};
    for (real p : breaks)
        if (p > 0 && std::isfinite(p) && (infinite || p < end)) kept.push_back(p);
    if (!infinite) kept.push_back(end);
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    real sum = 0;
    for (size_t i = 0; i + 1 < kept.size(); ++i) sum += piece(f, kept[i], kept[i + 1]);
    if (infinite) sum += tail(f, kept.back(), tail_scale > 0 ? tail_scale : std::max(kept.back(), real(1)));
    return sum;
}

// Break points from `from` growing by 4× up to `to`.
void geometric(std::vector<real> &breaks, real from, real to) {
    for (real p = from; p < to && breaks.size() < 4096; p *= 4) breaks.push_back(p);
}

} // namespace

double reference_scaled_tail(double u_in, double w_in) {
    const real u = u_in, w = w_in;
    const real tau = std::cos(w) / std::sin(w);
    // Scales: the Lorentzian 1/(1 + (τ + y)²) varies over 1 + τ, e^{−u y} over 1/u.
    const real lorentz = 1 + tau, decay = u > 0 ? 1 / u : std::numeric_limits<real>::infinity();
    std::vector<real> breaks;
    const real smallest = std::min(lorentz, decay) / 64;
    const real largest = u > 0 ? 48 * decay : 64 * lorentz;
    geometric(breaks, smallest, largest);
    auto f = [=](real y) { const real x = tau + y; return std::exp(-u * y) / (1 + x * x); };
    // Beyond 48/u the integrand is below e^{−48}: its tail decays over 1/u; with u = 0 it
    // decays like 1/y², mapped with the last break point as the scale.
    const real integral = integrate(f, breaks, std::numeric_limits<real>::infinity(), u > 0 ? decay : 0);
    return static_cast<double>(integral / w);
}

double reference_near_light_E(double T_in, double g_in, double r_in, double S_in, double phase_g) {
    const real T = T_in, g = g_in, r = r_in, G = phase_g;
    const real S = std::isinf(S_in) ? std::numeric_limits<real>::infinity() : real(S_in);
    const real sg2 = (1 - std::fabs(g)) * (1 + std::fabs(g)); // 1 − g² without cancellation
    const real c = T * r;                                      // the boundary layer t ~ T r of t/(t + T r)
    auto h2 = [=](real t) { const real d = t + T * g; return d * d + T * T * sg2; };
    auto n = [=](real t) {
        const real hh = h2(t);
        const real share = r > 0 ? (std::isinf(c) ? real(0) : t / (t + c)) : real(1);
        const real att = std::exp(-t - std::sqrt(hh) * share) / hh;
        if (G == 0) return att;
        // ψ_G(θ) from sin²(θ/2) = (η + d)/(2η), cos²(θ/2) = (η − d)/(2η), d = t + T g, η = ĥ: the
        // one that cancels as (T² (1 − g²))/(η ∓ d)/(2η).
        const real d = t + T * g, eta = std::sqrt(hh), perp = T * T * sg2;
        const real s2 = d >= 0 ? (eta + d) / (2 * eta) : perp / (eta - d) / (2 * eta);
        const real c2 = d >= 0 ? perp / (eta + d) / (2 * eta) : (eta - d) / (2 * eta);
        const real q = G >= 0 ? (1 - G) * (1 - G) + 4 * G * s2 : (1 + G) * (1 + G) - 4 * G * c2;
        return att * (1 - G) * (1 + G) / (q * std::sqrt(q));
    };
    auto h = [=](real t) { return 1 / h2(t); };
    const real span = std::min(S, 4 * T + 200);
    std::vector<real> breaks;
    geometric(breaks, T / 4096, std::min(span, 64 * T)); // 1/ĥ² near t = 0 varies over T
    if (c > 0 && std::isfinite(c)) geometric(breaks, c / 256, std::min(span, 256 * c));
    if (g < 0) { // the peak of 1/ĥ² at t* = −gT, of width T √(1 − g²)
        const real t_star = -T * g, width = T * std::sqrt(sg2);
        breaks.push_back(t_star);
        for (real off = width; off < t_star + span && breaks.size() < 4096; off *= 4) {
            breaks.push_back(t_star - off);
            breaks.push_back(t_star + off);
        }
    }
    geometric(breaks, real(1) / 16, std::min(span, real(256))); // e^{−t}
    const real N = integrate(n, breaks, S, 1);
    const real H = integrate(h, breaks, S, 0); // ĥ^{−2} decays like 1/t²
    return static_cast<double>(N / H);
}

} // namespace scatterlut

namespace scatterlut {

double reference_scaled_tail_hg(double u_in, double w_in, double g_in) {
    if (g_in == 0.0) return reference_scaled_tail(u_in, w_in);
    const real u = u_in, w = w_in, g = g_in;
    const real tau = std::cos(w) / std::sin(w);
    // Scales: the peak (1 − g)/(1 + g) in t (g > 0) or (1 + g)/(1 − g) (g < 0: the backward
    // peak in ξ as t grows), the decay 1/(1 + τ) of the tail, e^{−u y} over 1/u.
    const real peak = g > 0 ? (1 - g) / (1 + g) : (1 + g) / (1 - g);
    const real decay = u > 0 ? 1 / u : std::numeric_limits<real>::infinity();
    std::vector<real> breaks;
    const real smallest = std::min(std::min(peak, 1 + tau), decay) / 64;
    const real largest = u > 0 ? 48 * decay : 64 * (1 + tau) / std::min(peak, real(1));
    geometric(breaks, smallest, largest);
    auto f = [=](real y) {
        const real t = tau + y, gm = 1 - g, gp = 1 + g;
        const real q = gm * gm + gp * gp * t * t;
        return std::exp(-u * y) * gm * gp * std::sqrt(1 + t * t) / (q * std::sqrt(q));
    };
    const real integral = integrate(f, breaks, std::numeric_limits<real>::infinity(), u > 0 ? decay : 0);
    return static_cast<double>(integral / w);
}

} // namespace scatterlut

namespace scatterlut {
namespace {

// The surface reference works in double with its own rules (its integrand is itself an
// integral, so the airlight's long-double rule per γ would take seconds per node): Boost.Math's
// exp_sinh for the airlight along each ray, adaptive 31-point Gauss–Kronrod over γ and φ.
constexpr double kSurfaceTolerance = 1e-10;
constexpr unsigned kSurfaceMaxDepth = 12;
constexpr double kPi = 3.141592653589793238462643383279502884;

// ∫_a^b f by adaptive 31-point Gauss–Kronrod in double.
template <class F> double surface_piece(const F &f, double a, double b) {
    return scaled_piece<double, 31>(f, a, b, kSurfaceMaxDepth, kSurfaceTolerance);
}

// ∫ f over [lo, hi] split at the `breaks` inside it.
template <class F> double surface_pieces(const F &f, std::vector<double> breaks, double lo, double hi) {
    std::vector<double> kept = {lo, hi};
    for (double p : breaks)
        if (p > lo && p < hi) kept.push_back(p);
    std::sort(kept.begin(), kept.end());
    kept.erase(std::unique(kept.begin(), kept.end()), kept.end());
    double sum = 0;
    for (size_t i = 0; i + 1 < kept.size(); ++i) sum += surface_piece(f, kept[i], kept[i + 1]);
    return sum;
}

// w·G̃(u, w) = ∫_0^∞ e^{−u y}/(1 + (τ + y)²) dy, τ = cot w ≥ 0, by Boost.Math's exp_sinh
// (double-exponential on the half line; the integrand decays like e^{−u y}/y²).
double ray_airlight(double u, double w) {
    const double tau = std::cos(w) / std::sin(w);
    auto f = [=](double y) { const double x = tau + y; return std::exp(-u * y) / (1 + x * x); };
    // Not const: Boost 1.74 declares integrate const but defines it without (one per thread).
    thread_local boost::math::quadrature::exp_sinh<double> rule;
    double error = 0, l1 = 0;
    return rule.integrate(f, kSurfaceTolerance, &error, &l1, nullptr);
}

// K_n(θ, γ) = 2 ∫_0^{φ_end} (a + b cos φ)^n dφ, a = cos θ cos γ, b = sin θ sin γ: the integrand is
// positive up to φ_end (π when a ≥ b, acos(−a/b) when |a| < b) and peaked at φ = 0 with the
// width √((a + b)/(n b)) (its Gaussian form); breaks at 1, 4, 16 times that width.
double azimuthal_kernel(int n, double theta, double gamma) {
    const double a = std::cos(theta) * std::cos(gamma), b = std::fabs(std::sin(theta) * std::sin(gamma));
    if (a + b <= 0) return 0;
    if (b == 0) return 2 * kPi * std::pow(a, n);
    const double end = a >= b ? kPi : std::acos(std::max(-1.0, std::min(1.0, -a / b)));
    auto f = [=](double phi) { return std::pow(std::max(0.0, a + b * std::cos(phi)), n); };
    const double width = std::sqrt((a + b) / (n * b));
    return 2 * surface_pieces(f, {width, 4 * width, 16 * width}, 0.0, end);
}

} // namespace

double reference_surface_G(int n, double T, double theta) {
    // A(T, γ) sin γ = 2 e^{−T} w2 G̃(T sin γ, w2): the airlight arriving along the ray from the
    // surface point at angle γ from the direction to the light (γ = 0: towards the light).
    auto f = [=](double gamma) {
        const double w2 = (kPi - gamma) / 2;
        if (!(w2 > 0)) return 0.0;
        return 2 * std::exp(-T) * ray_airlight(T * std::sin(gamma), w2) * azimuthal_kernel(n, theta, gamma);
    };
    // Where the ring of directions at γ meets the horizon (|π/2 − θ|, π − that), the lobe
    // (θ, θ ± 1, 3, 10 widths 1/√n) and the near-light scale of A sin γ (1, 4, 16, 64 × 1/T).
    const double edge = std::fabs(kPi / 2 - theta);
    std::vector<double> breaks = {edge, kPi - edge};
    if (n > 1) {
        const double width = 1 / std::sqrt(double(n));
        breaks.push_back(theta);
        for (double k : {1.0, 3.0, 10.0}) {
            breaks.push_back(theta - k * width);
            breaks.push_back(theta + k * width);
        }
    }
    if (T > 1)
        for (double k : {1.0, 4.0, 16.0, 64.0}) breaks.push_back(k / T);
    return surface_pieces(f, breaks, 0.0, kPi);
}

} // namespace scatterlut
