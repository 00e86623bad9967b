// scatterlut runtime — airlight: a point light seen through a homogeneous medium that
// contains both the viewer and the light (fog around a street lamp).
//
// Sign convention: γ is the angle between the view direction and the direction FROM
// THE VIEWER TO THE LIGHT (γ = 0: looking straight at the light; γ = π: the light is
// behind the viewer). Texts that use the direction back to the viewer have γ' = π − γ.
#pragma once

#include <string>

#include "scatterlut/sampler.hpp"
#include "scatterlut/table.hpp"

struct slut_airlight_geometry; // kernels/slut_airlight.h

namespace scatterlut {

// One airlight query in physical units.
struct AirlightQuery {
    double sigma_s_per_m = 0;      // scattering coefficient σ_s, 1/m
    double sigma_a_per_m = 0;      // absorption coefficient σ_a, 1/m
    double intensity_W_per_sr = 0; // point light intensity I0 (radiant power Φ = 4π I0)
    double distance_m = 0;         // viewer–light distance D
    double gamma_rad = 0;          // angle view direction ↔ direction viewer→light
    double length_m = 0;           // view-ray length s inside the medium (may be +inf)
};

// The same query from positions and a direction (γ from the vectors themselves, so
// γ → 0 and γ → π keep their precision). view_dir need not be normalised.
AirlightQuery airlight_query_from_points(const double viewer_m[3], const double view_dir[3],
                                         const double light_m[3], double length_m,
                                         double sigma_s_per_m, double sigma_a_per_m,
                                         double intensity_W_per_sr);

// Radiance in W/(m²·sr) (for I0 in W/sr). +infinity when the ray passes through the light
// (γ = 0 and s ≥ D: the integral diverges); 0 for σ_s = 0, I0 = 0 or s = 0; never NaN,
// never negative. Throws std::invalid_argument for negative or NaN inputs.
double airlight_radiance_exact(const AirlightQuery &q); // quadrature, ~1e-13 relative

// The closed forms engines use instead of a table (Macklin 2010; kernels/slut_airlight.h):
// the radiance without extinction, σ_s/(4π)·I0·(atan((s + b)/h) − atan(b/h))/h with
// b = −D cos γ, h = D sin γ (exact as σ_t → 0, an overestimate otherwise), and the same
// times e^{−σ_t D} (still ≥ the exact radiance: the extra path x + d(x) − D is ignored).
// Same units, limits and checks as airlight_radiance_exact (+inf through the light, 0 for
// σ_s = 0, I0 = 0 or s = 0, never NaN). Allocation-free and thread-safe.
double airlight_radiance_no_extinction(const AirlightQuery &q);
double airlight_radiance_no_extinction_attenuated(const AirlightQuery &q);

namespace detail {
// The front-end the airlight runtimes share (AirlightTable, AirlightHgTable): the query
// checked (check_airlight_query) and its geometry's near end, unscaled
// (slut_airlight_setup_near_end_unscaled, kernels/slut_airlight.h).
slut_airlight_geometry airlight_query_near_end(const AirlightQuery &q);
} // namespace detail

class AirlightTable;
namespace detail {
// AirlightTable::radiance without its AVX2 + FMA path (libm and the kernels' functions
// alone, as on CPUs without AVX2): the tests compare the two per query.
double airlight_radiance_portable(const AirlightTable &table, const AirlightQuery &q);
// AirlightTable::radiance's AVX2 + FMA path with the one-panel θ-rule on 4 lanes even where
// the CPU has AVX-512 (where radiance takes the 8-lane rule): the tests compare it with the
// portable path. The portable path where the CPU lacks AVX2 or FMA.
double airlight_radiance_four_lanes(const AirlightTable &table, const AirlightQuery &q);
} // namespace detail

// A loaded F table (kind "airlight_F"): axis 0 u ∈ [0, u_max], axis 1 w = π/2 − v ∈
// [w_min, π/2], channel 0 = ln G̃ (see kernels/slut_airlight.h).
class AirlightTable {
public:
    // Checks kind, quantity version, axes and channel; throws std::invalid_argument.
    // Keeps the values as doubles (table()) and, for f16/f32 storage, a float copy that the
    // lookups read: 12 bytes per node.
    explicit AirlightTable(Table table);

    // G̃(u, w) with a = u·cot w given by the caller (exact where the caller has it):
    // interpolated inside the table, asymptotic forms outside (never clamped).
    double scaled_tail(double u, double w, double a) const;
    double scaled_tail(double u, double w) const; // a = u·cot w

    // F(u, v) and the tail G(u, v) from the table: G = e^{−u tan v}·w·G̃(u, w) keeps the
    // table's relative accuracy; F = G(u, 0) − G(u, v) would lose it where F ≪ G(u, 0)
    // (small v·u), so there (G(u, v) > G(u, 0)/2) F is integrated directly instead
    // (slut_F_from_tails, kernels/slut_airlight.h: ~1e-13 relative, any v > 0).
    double F(double u, double v) const;
    double tail(double u, double v) const;

    // Radiance as airlight_radiance_exact: for a segment that one Gauss panel integrates
    // (slut_airlight_theta_fits_one_panel) the θ-integral itself, 6 points in t = tan θ;
    // otherwise from two table samples (or the panel rule where the two ends' terms would
    // cancel).
    double radiance(const AirlightQuery &q) const;

    // The same for `count` queries: out[i] is radiance(queries[i]) to within 1e-12 relative
    // (the same paths and rules; where the CPU has AVX2 and FMA, four queries at a time with
    // glibc's libmvec exp, log, atan, sin and cos, ≤ 4 ulp, in place of libm's). Every query
    // is checked before anything is written: a bad one throws std::invalid_argument naming
    // its index and field, and `out` is left as it was. Allocation-free and thread-safe
    // (const, no state); `out` must not overlap `queries`.
    void radiance(const AirlightQuery *queries, size_t count, double *out) const;

    const Table &table() const { return table_; }
    double u_max() const { return u_max_; }
    double w_min() const { return w_min_; }

private:
    friend struct AirlightBatch;   // the batch radiance (airlight_batch.cpp)
    friend struct AirlightScalar4; // the scalar radiance where the CPU has AVX2 and FMA (airlight_avx2.cpp)
    friend double detail::airlight_radiance_portable(const AirlightTable &table, const AirlightQuery &q);
    friend double detail::airlight_radiance_four_lanes(const AirlightTable &table, const AirlightQuery &q);
    // radiance() without the AVX2 + FMA path: libm and the kernels' functions alone (CPUs
    // without AVX2, and the cases that path leaves: zero or divergent radiance, infinite rays,
    // scales beyond plain products, f64 tables, ends beyond the table).
    double radiance_portable(const AirlightQuery &q) const;
    double unit_u(double u) const;                                     // u's unit coordinate
    double scaled_tail_at(double unit_u, double u, double w, double a) const; // G̃ given it
    // The radiance's two paths (airlight.cpp), from the geometry without its e^{−σ_t D}.
    double radiance_general(const AirlightQuery &q) const;
    double one_panel_radiance(const slut_airlight_geometry &g) const;
    double two_sample_radiance(const slut_airlight_geometry &g) const;
    double ln_gs_at(int cell_u, double frac_u, double unit_w) const; // ln G̃ from values32_ (airlight_lookup.hpp)
    Table table_;
    SamplerCache cache_; // of table_
    std::vector<float> values32_; // table_.values as floats when exact (sample_encoded_at_unit)
    double u_max_ = 0;
    double w_min_ = 0;
    int count_u_ = 0, count_w_ = 0; // nodes per axis
    double inv_span_u_ = 1, inv_span_w_ = 1; // 1/(g1 − g0) of the axes' warped ends (cache_)
    size_t channels_ = 1;
    bool fast_lookup_ = false; // values32_ present and the axes' warps LOG1P (u), ASINH_COT (w)
};

// Throws std::invalid_argument naming the first invalid field.
void check_airlight_query(const AirlightQuery &q);

} // namespace scatterlut
