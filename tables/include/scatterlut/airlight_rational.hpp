// scatterlut runtime — the airlight's tail on rational axes (kind "airlight_rational"): the
// table the GPU snippets' fast tier samples with one filtered fetch per end of the ray
// (kernels/slut_airlight_rational.h, docs/FORMAT.md "airlight_rational").
//
// In the tangent variable t = tan v = cot w the tail of Sun et al. 2005's F, scaled by its
// exponential, is H(u, t) = ∫_0^∞ e^{−u y}/(1 + (t + y)²) dy (u = σ_t D sin γ); the table
// stores the normalised Ĥ = H·N, N = t + 2/π + u (1 + t²), in [0.80, 1.29], at the unit
// coordinates
//
//   x_m = (m/(m + K))^{1/4},  m = u (1 + t),  K = SLUT_AIRLIGHT_RATIONAL_M_SCALE (4)   (axis 0)
//   x_t = t/(1 + t)                                                               (axis 1)
//
// both linear on [0, 1], node i at i/(count − 1), the edges x_m = 1 (u = ∞: Ĥ = 1) and
// x_t = 1 (t = ∞: Ĥ = e^m E_2(m)(1 + m)) included. AirlightRationalTable samples it exactly as
// a GPU's bilinear filter does at the texel-centre coordinates (x·(count − 1) + 0.5)/count
// with clamp-to-edge, and computes the radiance as the snippets' tiers do, in double.
#pragma once

#include <cstddef>
#include <vector>

#include "scatterlut/airlight.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// The range a loader accepts for a stored Ĥ (the quantity lies in [0.80, 1.29]; anything
// outside [0.5, 2] is no airlight_rational value: the file is corrupt).
inline constexpr double kAirlightRationalMinValue = 0.5;
inline constexpr double kAirlightRationalMaxValue = 2.0;

// A loaded airlight_rational table. Thread-safe (const), allocation-free after construction.
class AirlightRationalTable {
public:
    // Checks the table: kind, quantity version, two linear axes (x_m, x_t) on [0, 1], one
    // Linear channel Hn, every value finite and in [kAirlightRationalMinValue,
    // kAirlightRationalMaxValue] (std::invalid_argument naming the node otherwise: a loader
    // distrusts its file). Keeps a float copy of f16/f32 values, which the samples read.
    explicit AirlightRationalTable(Table table);

    const Table &table() const { return table_; }
    int m_count() const { return table_.axes[0].map.count; } // the texture's width
    int t_count() const { return table_.axes[1].map.count; } // its height

    // Ĥ at unit coordinates (x_m, x_t), each clamped to [0, 1]: bilinear between the nodes,
    // as a GPU's linear filter at texel centres. std::invalid_argument for NaN.
    double sample(double x_m, double x_t) const;
    // Ĥ(u, t) for u ≥ 0, t ∈ [0, ∞] (t = ∞: the edge x_t = 1): the axis maps, then sample().
    double hn(double u, double t) const;

    // Airlight radiance in W/(m²·sr) for the query of airlight_radiance_exact (the same checks,
    // std::invalid_argument; +∞ through the light, 0 for σ_s = 0, I0 = 0 or s = 0, never
    // negative), by the snippets' tiers' path in double (kernels/slut_airlight_rational.h:
    // slut_airlight_rational_setup_of, two samples, slut_airlight_rational_radiance): the two
    // ends' terms' difference, with at most 2G − 1 times the samples' relative error (G =
    // SLUT_AIRLIGHT_RATIONAL_GAIN), or the short segment's rule where that would cancel. The
    // query as that set-up serves it: D within [SLUT_SQUARABLE_MIN, SLUT_SQUARABLE_MAX] (1e∓150;
    // clamped there), a length beyond SLUT_SQUARABLE_MAX an infinite ray, σ_s·I0 a finite double
    // (beyond, its scale is ∞·e^{−σ_t D}: NaN where that exponential underflows).
    double radiance(const AirlightQuery &q) const;
    // The same for `count` queries (a loop over radiance()): every query is checked before
    // anything is written (std::invalid_argument naming the first bad query's index and field,
    // `out` left as it was).
    void radiance(const AirlightQuery *queries, size_t count, double *out) const;

private:
    Table table_;
    std::vector<float> values32_; // table_.values as floats when exact (f16/f32 storage)
};

} // namespace scatterlut
