// Independent CPU reference for the airlight quantities of docs/PHYSICS.md §1.1.
//
// Header-only, tests only. Deliberately uses NO scatterlut header and none of the
// identities the library relies on: everything is plain adaptive Gauss–Kronrod
// quadrature (Boost.Math gauss_kronrod<double, 61>) over explicit panels whose
// break points follow the integrands' length scales.
//
//   ref_F(u, v)            F(u,v) = ∫_0^v exp(−u tan ξ) dξ                    ≤ 1e-12 relative
//   ref_tail(u, v)         G(u,v) = ∫_v^{π/2} exp(−u tan ξ) dξ                ≤ 1e-12 relative
//                          (0 only when G underflows double; denormal results lose
//                          relative precision as any denormal does)
//   ref_scaled_tail(u, w)  G̃ = e^{u cot w} G(u, π/2 − w) / w ∈ (0, 1]           ≤ 1e-12 relative
//   ref_airlight(σs, σa, I0, D, γ, s)
//                          L = σs/(4π) I0 ∫_0^s e^{−σt (x + d(x))} / d(x)² dx,
//                          d(x)² = x² + D² − 2xD cos γ, by direct quadrature     ≤ 1e-11 relative
//                          (+inf when the ray passes through the light)
//
// Break-point scheme.
//  * F, G, G̃ are all integrals of e^{−u s}/(1 + (τ + s)²) over s (t = tan ξ = τ + s).
//    The integrand has poles at s = −τ ± i and decays on the scale 1/u. Panels start
//    at s = 0 and have width min(max(1, τ + a), K/u) (a = left end): a geometric
//    sequence (×2) in the distance to the poles, capped at K = 8 e-folds, i.e. break
//    points at multiples of 1/u. This resolves the drop of width 1/u at ξ = 0 (large u)
//    and the drop at t ≈ 1/u, i.e. ξ ≈ π/2 − u (tiny u), which plain adaptive
//    quadrature in ξ misses by ~1e-8. An infinite range stops once a rigorous bound
//    on the remainder is below 1e-18 of the sum.
//  * The airlight integrand 1/d² has complex singularities at x* ± i b, x* = D cos γ
//    (closest approach), b = D |sin γ| (closest distance). Break points: x* (if inside
//    [0, s]) and x* ± ℓ·2^k, k = 0, 1, 2, …, with ℓ = max(b, distance from x* to [0, s])
//    (so γ = 0 with s < D still gets a geometric mesh towards the light); every panel
//    is further split to at most K/σt wide. Nodes are formed as offsets from each panel's
//    left end both in x and in y = x − x* (see ref_airlight), so neither a narrow peak far
//    from the viewer nor a very short ray loses digits to rounding of x or x − x*.
//    Past x* the walk stops once the remainder bound is below 1e-18 of the sum.
//  * Every finite panel [a, b] is integrated as ∫_0^1 (b−a) f(a + (b−a)x) dx: Boost's
//    gauss_kronrod compares the unscaled error on [−1, 1] with tol·|estimate|, so a
//    narrow panel integrated directly recurses to max depth (docs/POCL.md, "Boost.Math pitfall").
//    Per-panel tol 1e-14 (Boost's error floor is 2ε of the [−1, 1] value, so a tol
//    below ~1e-15 would always recurse to max depth). |K61 − G30| overestimates the
//    error of K61 by orders of magnitude on these smooth panels.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>

namespace slut_ref {

namespace detail {

constexpr double kPio2Hi = 1.57079632679489655800;              // the double nearest π/2
constexpr long double kPio2LoL = 6.12323399573676603587e-17L;  // π/2 − kPio2Hi
constexpr double kEfolds = 8.0;        // max e-folds of the exponential per panel
constexpr double kPanelTol = 1e-14;    // Boost GK relative tolerance per panel
constexpr double kStopRel = 1e-18;     // drop a remainder below this fraction of the sum
constexpr double kPi = 3.14159265358979323846;

// ∫_a^b f, integrated as ∫_0^1 (b−a) f(a + (b−a)x) dx (see header comment).
template <class Fn>
inline double panel(const Fn &f, double a, double b) {
    const double h = b - a;
    if (!(h > 0)) return 0.0;
    auto g = [&](double x) { return f(a + h * x); };
    return h * boost::math::quadrature::gauss_kronrod<double, 61>::integrate(g, 0.0, 1.0, 15, kPanelTol);
}

// S(u, τ, L) = ∫_0^L e^{−u s} / (1 + (τ + s)²) ds, u > 0, τ ≥ 0, L ∈ (0, ∞].
inline long double scaled_lorentz_exp(double u, double tau, double L) {
    auto f = [u, tau](double s) {
        const double t = tau + s;
        return std::exp(-u * s) / (1.0 + t * t);
    };
    long double sum = 0;
    double a = 0;
    while (a < L) {
        double h = std::max(1.0, tau + a);      // geometric: width = distance scale to the poles
        h = std::min(h, kEfolds / u);           // at most kEfolds e-folds of e^{−us} per panel
        double b = a + h;
        if (!(b < L) || (L - b) < 1e-3 * h) b = L;  // no sliver panel at the end
        sum += panel(f, a, b);
        a = b;
        if (!(a < L)) break;
        // Rigorous remainder bound: ∫_a^∞ e^{−us}/(1+(τ+s)²) ≤ e^{−ua} / (u (1 + (τ+a)²)).
        const double t = tau + a;
        const double R = std::exp(-u * a) / (u * (1.0 + t * t));
        if (R < kStopRel * (double)sum) break;
    }
    return sum;
}

// w = π/2 − v without cancellation (long double), for 0 ≤ v ≤ kPio2Hi.
inline long double pio2_minus(double v) { return (long double)(kPio2Hi - v) + kPio2LoL; }

// tan v, accurately also near π/2 (as cot(π/2 − v)).
inline long double tan_accurate(double v) {
    if (v > 0.78) return 1.0L / std::tan(pio2_minus(v));
    return std::tan((long double)v);
}

inline bool valid_uv(double u, double v) {
    return u >= 0 && v >= 0 && v <= kPio2Hi && !std::isnan(u);
}

} // namespace detail

// F(u, v) = ∫_0^v exp(−u tan ξ) dξ = ∫_0^{tan v} e^{−ut}/(1+t²) dt.
// u ≥ 0, 0 ≤ v ≤ π/2 (the double 1.5707963267948966 included). NaN outside the domain.
inline double ref_F(double u, double v) {
    if (!detail::valid_uv(u, v)) return std::numeric_limits<double>::quiet_NaN();
    if (v == 0) return 0.0;
    if (u == 0) return v;                       // ∫_0^v dξ
    if (std::isinf(u)) return 0.0;
    const double T = (double)detail::tan_accurate(v);  // 1.633e16 at v = kPio2Hi: the e^{−ut} cut-off ends the walk first
    return (double)detail::scaled_lorentz_exp(u, 0.0, T);
}

// G(u, v) = ∫_v^{π/2} exp(−u tan ξ) dξ = e^{−u T} ∫_0^∞ e^{−us}/(1+(T+s)²) ds, T = tan v.
// Relative accuracy ≤ 1e-12 down to DBL_MIN; 0 only when G underflows double.
inline double ref_tail(double u, double v) {
    if (!detail::valid_uv(u, v)) return std::numeric_limits<double>::quiet_NaN();
    const long double w = detail::pio2_minus(v);   // π/2 − v, no cancellation
    if (u == 0) return (double)w;
    if (std::isinf(u)) return 0.0;
    const long double T = detail::tan_accurate(v);
    const long double uT = (long double)u * T;
    // G ≤ e^{−uT} · w ≤ 1.571 e^{−uT} < denorm_min/2 (rounds to 0) once uT > 746.3.
    if (uT > 747.0L) return 0.0;
    const long double S = detail::scaled_lorentz_exp(u, (double)T, std::numeric_limits<double>::infinity());
    return (double)(std::exp(-uT) * S);  // long double: no intermediate underflow; rounds into denormals
}

// G̃(u, w) = e^{u cot w} G(u, π/2 − w) / w = (1/w) ∫_τ^∞ e^{−u(t−τ)}/(1+t²) dt, τ = cot w.
// u ≥ 0, 0 < w ≤ π/2. Never overflows; value in (0, 1].
inline double ref_scaled_tail(double u, double w) {
    if (!(u >= 0) || !(w > 0) || w > detail::kPio2Hi) return std::numeric_limits<double>::quiet_NaN();
    if (u == 0) return 1.0;                      // G(0, π/2 − w) = w
    const double tau = std::max(0.0, (double)(1.0L / std::tan((long double)w)));  // cot(kPio2Hi) ≈ 6e-17
    const long double S = detail::scaled_lorentz_exp(u, tau, std::numeric_limits<double>::infinity());
    return (double)(S / w);
}

// Airlight radiance by direct quadrature of the single-scattering integral
//   L = σs/(4π) I0 ∫_0^s e^{−σt (x + d(x))} / d(x)² dx,  d(x)² = x² + D² − 2xD cos γ,
// γ = angle between the view direction and the direction from the viewer to the light.
// s may be +inf (σt > 0). Returns +inf when the ray passes through the light
// (sin γ = 0, cos γ > 0, s ≥ D) or the light sits at the viewer (D = 0).
inline double ref_airlight(double sigma_s, double sigma_a, double I0, double D, double gamma, double s) {
    const double st = sigma_s + sigma_a;
    if (!(sigma_s >= 0) || !(sigma_a >= 0) || !(D >= 0) || !(s >= 0) || std::isnan(gamma) || std::isnan(I0))
        return std::numeric_limits<double>::quiet_NaN();
    if (s == 0 || sigma_s == 0 || I0 == 0) return 0.0;
    if (D == 0) return std::numeric_limits<double>::infinity();
    const double cg = std::cos(gamma), sg = std::sin(gamma);
    const double xs = D * cg;                 // closest approach along the ray
    const double b = D * std::fabs(sg);       // closest distance
    if (b == 0 && xs >= 0 && s >= xs) return std::numeric_limits<double>::infinity();

    // Panels are delimited in x (so the ray's length s = Σ panel widths exactly), but each
    // node is evaluated both as x = a + h·t and as y = x − x* = (a − x*) + h·t. a − x* is
    // exact for the panels near the peak (Sterbenz), so nodes resolve a peak of width b even
    // when b ≪ x*: forming y = x − x* at every node would move nodes by ε·x*, ~1e-10 of
    // the peak width at γ = 1e-6, and forming x = x* + y would make panel widths near x = 0
    // wrong by ε·x*/s relative (~1e-10 for s = 1e-6). d² = y² + b² (no cancellation near
    // the light). The exponent is taken relative to its minimum σt·D (x + d(x) is
    // nondecreasing and equals D at x = 0): x + d − D = x (1 + (x − 2x*)/(d + D)),
    // since d² − D² = x (x − 2x*).
    auto d2_of = [b](double y) { return y * y + b * b; };
    auto fxy = [&](double x, double y) {
        const double d2 = d2_of(y);
        const double d = std::sqrt(d2);
        const double excess = x * (1.0 + (x - 2.0 * xs) / (d + D));
        return std::exp(-st * excess) / d2;
    };
    auto panel = [&](double a, double bb) {
        const double h = bb - a, y0 = a - xs;
        if (!(h > 0)) return 0.0;
        auto g = [&](double t) { return fxy(a + h * t, y0 + h * t); };
        return h * boost::math::quadrature::gauss_kronrod<double, 61>::integrate(g, 0.0, 1.0, 15, detail::kPanelTol);
    };

    // Break points (in x): 0, x* and x* ± ℓ 2^k inside (0, s), s.
    double dist = 0;                          // distance from x* to [0, s]
    if (xs < 0) dist = -xs; else if (xs > s) dist = xs - s;
    const double ell = std::max(b, dist);
    std::vector<double> pts{0.0};
    if (xs > 0 && xs < s) pts.push_back(xs);
    for (double m = ell; m < 1e300; m *= 2) {
        const double p1 = xs - m, p2 = xs + m;
        if (p1 > 0 && p1 < s) pts.push_back(p1);
        if (p2 > 0 && p2 < s) pts.push_back(p2);
        if (p1 <= 0 && p2 >= s) break;
    }
    if (std::isfinite(s)) pts.push_back(s);
    std::sort(pts.begin(), pts.end());
    pts.erase(std::unique(pts.begin(), pts.end()), pts.end());

    const double cap = st > 0 ? detail::kEfolds / st : std::numeric_limits<double>::infinity();
    long double sum = 0;
    double a = 0;
    std::size_t next = 1;
    while (a < s) {
        double end;
        if (next < pts.size()) end = pts[next];
        else end = a + std::max(a - xs, ell);  // beyond the last break point (s = ∞): keep doubling
        if (end - a > cap) end = a + cap;
        if (!(end < s)) end = s;
        sum += panel(a, end);
        a = end;
        while (next < pts.size() && pts[next] <= a) ++next;
        if (!(a < s)) break;
        if (a > xs) {
            // Remainder bound past the closest approach: d increasing, x + d − D ≥ excess(a) + (x − a),
            //   ∫_a^s ≤ e^{−σt excess(a)} · min(1/(σt d(a)²), 1/(a − x*)).
            const double y = a - xs, d2 = d2_of(y);
            double bound = 1.0 / y;
            if (st > 0) bound = std::min(bound, 1.0 / (st * d2));
            const double R = fxy(a, y) * d2 * bound;
            if (R < detail::kStopRel * (double)sum) break;
        }
    }
    const long double pref = (long double)sigma_s / (4.0L * (long double)detail::kPi) * (long double)I0;
    return (double)(pref * std::exp(-(long double)st * (long double)D) * sum);
}

} // namespace slut_ref
