// The near end of the airlight geometry, lane-generic (internal; not installed): the set-up
// the AVX2 scalar path (airlight_avx2.cpp, AirlightScalar4: one query, Real = double) and the
// batch (airlight_batch.cpp, AirlightBatch: four queries, Real = simd4::v4d) share, written once
// so that both compute the same expressions, so the same values.
#pragma once

#include <algorithm>
#include <cmath>

#include "simd4.hpp"

extern "C" {
#include "slut_airlight.h"
}

#if SLUT_HAVE_SIMD4
namespace scatterlut {
namespace {

// The elementwise functions the set-up below needs, for one query (double) and four (v4d).
inline double sqrt_of(double x) { return std::sqrt(x); }
inline double abs_of(double x) { return std::fabs(x); }
inline double max_of(double x, double y) { return std::max(x, y); }
SLUT_SIMD4_TARGET inline simd4::v4d sqrt_of(simd4::v4d x) { return simd4::sqrt4(x); }
SLUT_SIMD4_TARGET inline simd4::v4d abs_of(simd4::v4d x) { return simd4::abs4(x); }
SLUT_SIMD4_TARGET inline simd4::v4d max_of(simd4::v4d x, double y) { return simd4::max4(x, simd4::splat(y)); }

// slut_airlight_setup_near_end_unscaled's geometry from the sine and cosine of γ/2 (moderate
// lengths: s, D ≤ 1e100; its formulas from kernels/slut_airlight_geometry.h's SLUT_AIRLIGHT_*
// macros) for the scalar call's vector path (AirlightScalar4, Real = double) and the batch
// (AirlightBatch, four queries in a v4d): the same expressions, so the same values.
template <class Real>
struct NearEnd {
    Real sin_gamma, cos_gamma; // of γ, sin γ ≥ 1e-300 (on the axis: the one-panel rule's length / sin γ stays finite)
    Real u, c;                 // σ_t D sin γ; 2 σ_t D sin(γ/2)
    Real d_far;                // the far end's distance from the light, m
    Real x, ds;                // the far end: x = s − D cos γ (> 0: past the light's foot), ds = D sin γ
    Real y, ss;                // the light: y = D − s cos γ (> 0: ahead of the far end), ss = s sin γ
    Real dx, dy;               // d + |x|, d + |y|: d + x for x ≥ 0 and d − x below (never cancels)
};
template <class Real>
SLUT_SIMD4_TARGET inline NearEnd<Real> near_end(Real optical_distance, Real D, Real s, Real sin_half, Real cos_half) {
    NearEnd<Real> g;
    g.sin_gamma = max_of(2.0 * sin_half * cos_half, SLUT_TINY);
    g.cos_gamma = SLUT_AIRLIGHT_COS_GAMMA(sin_half, cos_half);
    g.u = optical_distance * g.sin_gamma;
    g.c = 2.0 * optical_distance * sin_half;
    g.d_far = sqrt_of(SLUT_AIRLIGHT_FAR_DISTANCE2(s, D, sin_half));
    g.x = s - D * g.cos_gamma;
    g.ds = D * g.sin_gamma;
    g.y = D - s * g.cos_gamma;
    g.ss = s * g.sin_gamma;
    g.dx = g.d_far + abs_of(g.x);
    g.dy = g.d_far + abs_of(g.y);
    return g;
}
// σ_t Δ ≥ 0 (the far end's extra attenuation e^{−σ_t Δ}, SLUT_AIRLIGHT_DELTA).
template <class Real>
SLUT_SIMD4_TARGET inline Real optical_delta_of(Real sigma_t, Real D, Real s, const NearEnd<Real> &g) {
    return sigma_t * max_of(SLUT_AIRLIGHT_DELTA(s, D, g.cos_gamma, g.d_far), 0.0);
}

} // namespace
} // namespace scatterlut
#endif
