// scatterlut runtime — the near light of nearlight.hpp with a Henyey–Greenstein phase
// (docs/PHYSICS.md §1.4, docs/NEARLIGHT.md "Anisotropic tables"):
//   L = σ_s/(4π) · I0 · σ_t · H(T, g, r, S) · E_g(T, g, r, S),
// E_g = the ĥ⁻²-weighted mean of ψ·attenuation, ψ = 4π p_{phase_g}, E_g ∈ (0, ψ_max]. A table
// stores ln(E_g/D) (kind near_light_E3_hg, S = ∞) or ln(E_g/(D·B)) (near_light_E4_hg, B the
// slab table's value base), D = slut_hg_nl_divisor(phase_g, T, g, S): thick, the phase at the
// entry point (for phase_g < 0 blended towards ψ_max at small T); slab, a constant times a
// 16-point estimate of the attenuation-weighted mean of ψ along the path; on the axes of the
// isotropic tables, and
// records its g as the `extra` key "phase.g". D carries the sharp dependence on the near-light
// g near the phase's peak; the stored values have the isotropic tables' ranges, and the sampler
// reads them through NearLightTable (the same front-end, SIMD paths included).
#pragma once

#include <cstddef>
#include <string>

#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

inline constexpr const char *kKindNearLightE3Hg = "near_light_E3_hg"; // E_g(T, g, r), S = ∞
inline constexpr const char *kKindNearLightE4Hg = "near_light_E4_hg"; // E_g(T, g, r, S) on axes (T, g, r, q)
inline constexpr const char *kExtraPhaseG = kPhaseGKey; // Table::extra key: the Henyey–Greenstein g

// The text a table records for `phase_g` ("%.17g": it reads back to the same double).
std::string phase_g_text(double phase_g);
// The file stem of an anisotropic near-light table: its kind and g as the airlight table of
// the same g writes it (airlight_fg_stem: the fewest digits that read back as g), e.g.
// "near_light_E3_hg_g0.85", "near_light_E4_hg_g-0.5".
std::string near_light_hg_file_stem(bool finite_thickness, double phase_g);

// Closed forms with the phase, needing no table (both approximations, stated):
//  - distant: the light's rays are taken parallel over the path (l ≫ the path and its depth
//    below the entry point), so θ is the one angle at the entry point, cos θ = −ω·ω_l, and the
//    isotropic distant-light form (Gath 2008 eq. 5) is multiplied by ψ(θ);
//  - thin: the attenuation mean of the isotropic thin form E_thin(r, S) (Gath 2008 §4.2, exact
//    as σ_t s → 0) times the ĥ⁻²-weighted mean of ψ along the path without attenuation
//    (E_g at σ_t = 0: the plain mean of ψ over the scattering angles the path sweeps,
//    θ from acos(−ω·ω_l) to θ(s/l) — an incomplete elliptic integral, with no elementary form;
//    a fixed rule of at most 48 points within 1e-13 of the adaptive quadrature,
//    slut_hg_nl_thin_psi_mean of kernels/slut_nearlight_hg.h, the GPU snippet's too).
// W/(m²·sr); 0 for a light below the plane; never NaN or negative. phase_g = 0: the isotropic forms.
double near_light_radiance_thin(const NearLightQuery &q, double phase_g);
double near_light_radiance_distant(const NearLightQuery &q, double phase_g);

// A loaded anisotropic near-light table. Outside its domain E_g is integrated exactly
// (slut_hg_nl_E), never clamped. Memory: the table twice (its own kind, and the copy the
// isotropic front-end reads).
class NearLightHgTable {
public:
    explicit NearLightHgTable(Table table); // checks kind, "phase.g", version, axes, channel, values
    double phase_g() const { return phase_g_; }
    bool thick_only() const { return iso_.thick_only(); }
    bool covers(double T, double g, double r, double S) const { return iso_.covers(T, g, r, S); }
    double E(double T, double g, double r, double S) const; // E_g; S = +inf: thick
    // W/(m²·sr) with the table's g (the query's σ: one channel).
    double radiance(const NearLightQuery &q) const;
    // Per channel: q supplies the geometry and intensity (its σ fields are not read), the
    // coefficients come per channel (1/m); one table serves all three (T, S scale with σ_t, r
    // and S/T do not). A clear channel (σ_t = 0) or one outside the domain is integrated exactly.
    Rgb radiance_rgb(const NearLightQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m) const;
    // The same for `count` queries (NearLightTable's batch, then the queries outside the domain
    // exactly); a bad query throws std::invalid_argument naming its index, `out` unchanged.
    void radiance(const NearLightQuery *queries, size_t count, double *out) const;
    void node_params(const size_t *node, double *params) const { iso_.node_params(node, params); }
    double node_E(const size_t *node) const;
    const Table &table() const { return table_; }
    // The isotropic-kind view of the stored values (E_g/D), for the shared measurements.
    const NearLightTable &scaled() const { return iso_; }
    // D at (T, g, S) (slut_hg_nl_divisor, kernels/slut_nearlight_hg.h; S = +inf: thick).
    double divisor(double T, double g, double S) const;

private:
    Table table_;
    double phase_g_ = 0;
    NearLightTable iso_;
};

} // namespace scatterlut
