// The anisotropic airlight table (kind "airlight_Fg"): ln G̃_g(u, w) for one Henyey–Greenstein
// asymmetry g, recorded in the file's extra key "phase.g" (docs/FORMAT.md), and its runtime:
// radiance with the table's phase, per channel (RGB) from one table, and the closed forms.
//
//   G̃_g(u, w) = e^{u cot w} ∫_{π/2−w}^{π/2} ψ_g(2ξ) e^{−u tan ξ} dξ / w,   ψ_g = 4π p_g
//
// (kernels/slut_airlight_hg.h, docs/PHYSICS.md §1.4: in Sun et al. 2005's substitution the
// scattering angle is exactly 2ξ). Axes as the isotropic table: u = σ_t·D·sin γ ∈ [0, u_max]
// (LOG1P warp), w = π/2 − v ∈ [w_min, π/2] (ASINH_COT warp; for g > 0 ASINH_COT_PEAK, whose
// nodes also resolve the forward peak at w → π/2; the sampler reads either from the file); beyond them the asymptotic
// forms of G̃_g (large u: Watson's series; small w: three terms in tan²w), never a clamp.
#pragma once

#include <string>

#include "scatterlut/anisotropic.hpp"
#include "scatterlut/sampler.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

inline constexpr const char *kKindAirlightFg = "airlight_Fg";
inline constexpr uint32_t kAirlightFgQuantityVersion = 1;
inline constexpr const char *kPhaseGKey = "phase.g"; // Table::extra: the table's g, "%.17g"

// The file stem of the anisotropic airlight table of asymmetry g: "airlight_Fg_g0.85" (g
// with the fewest digits that read back as the same double; '-' kept: "airlight_Fg_g-0.5").
std::string airlight_fg_stem(double phase_g);

// A table's recorded g (extra "phase.g"); throws std::invalid_argument when absent or not a
// number in the accepted range (check_phase_g).
double table_phase_g(const Table &table);

class AirlightHgTable {
public:
    // Checks kind, quantity version, axes, channel and "phase.g" (≠ 0); throws std::invalid_argument.
    explicit AirlightHgTable(Table table);

    // G̃_g(u, w): interpolated (bilinear in the warped coordinates, on ln G̃_g) inside the
    // table, the large-u series beyond u_max, the small-w form below w_min.
    double scaled_tail(double u, double w) const;

    // Radiance in W/(m²·sr) with the table's g (same units, limits and checks as
    // airlight_radiance_exact): σ_s/(4π)·I0·(2/D)·e^{−σ_t D}·[w2 G̃_g(u, w2) − e^{−σ_t Δ} w1 G̃_g(u, w1)]/sin γ
    // from two samples where the second term is at most half the first; elsewhere (the two
    // would cancel, or sin γ < 1e-6) the segment's integral itself (slut_hg_airlight_bracket).
    // Never NaN, never negative; +inf through the light.
    double radiance(const AirlightQuery &q) const;

    // Per channel from this one table: q supplies the geometry and I0 (its σ fields are not
    // read), sigma_s / sigma_a one coefficient per channel (1/m).
    Rgb radiance_rgb(const AirlightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m) const;

    // Whether the table serves queries of asymmetry phase_g (its own g, exactly).
    bool serves(double phase_g) const { return phase_g == g_; }

    const Table &table() const { return table_; }
    double phase_g() const { return g_; }
    double u_max() const { return u_max_; }
    double w_min() const { return w_min_; }

private:
    Table table_;
    SamplerCache cache_;
    double g_ = 0, u_max_ = 0, w_min_ = 0;
};

// Closed forms with the phase (no table), each stating its approximation; same units and
// checks as airlight_radiance_exact, never NaN or negative:
//  * thin medium (σ_t·(D + s) ≪ 1): no extinction along either leg,
//      L ≈ σ_s I0 ∫_0^s p_g(θ(x)) / d(x)² dx,
//    exact as σ_t → 0, an overestimate otherwise (by e^{σ_t (D + s)} at most): the
//    extinction-free bracket (1/sin γ)∫_{γ/2}^{v1} ψ_g(2ξ) dξ, which is the isotropic one,
//    (v1 − γ/2)/sin γ, times the mean of ψ_g over the scattering angles θ ∈ [γ, 2v1] the ray
//    sweeps (an incomplete elliptic integral for g ≠ 0: a fixed rule of at most 48 points,
//    within 1e-13 of the adaptive quadrature; kernels/slut_phase_arc.h, the GPU snippet's too).
//  * distant light (D ≫ s: the scattering angle stays γ along the ray, d(x) ≈ D − x cos γ in the
//    exponent and D in 1/d²):
//      L ≈ σ_s p_g(cos γ) I0 e^{−σ_t D}/D²·(1 − e^{−σ_t (1 − cos γ) s})/(σ_t (1 − cos γ)),
//    Gath 2008 eq. 5 with the phase and a light at finite distance.
// Both are kernels/slut_airlight_hg.h's slut_hg_airlight_radiance_thin / _distant (the GPU
// snippet's slut_airlight_hg_radiance_thin / _distant).
double airlight_hg_radiance_thin(const AirlightQuery &q, double phase_g);
double airlight_hg_radiance_distant(const AirlightQuery &q, double phase_g);

} // namespace scatterlut
