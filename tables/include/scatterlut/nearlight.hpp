// scatterlut runtime — near light: a point light outside a medium bounded by a plane
// (wax, marble, skin, a smoke slab), seen from outside. docs/PHYSICS.md §1.2 and
// kernels/slut_nearlight.h:
//   L = σ_s/(4π) · I0 · σ_t · N(T, g, r, S),   N = H(T, g, S) · E(T, g, r, S)
// with H in closed form and E ∈ (0, 1] the tabulated ĥ⁻²-weighted mean attenuation.
#pragma once

#include <cstddef>

#include "scatterlut/sampler.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// One near-light query in physical units. The surface plane passes through the entry
// point O of the view ray; the medium lies below it (against `normal`).
struct NearLightQuery {
    double sigma_s_per_m = 0, sigma_a_per_m = 0; // 1/m
    double intensity_W_per_sr = 0;               // I0
    double normal[3] = {0, 0, 1};                // outward unit normal
    double eye_dir[3] = {0, 0, 1};               // unit, from O towards the viewer
    double light_rel_m[3] = {0, 0, 1};           // light position − O, m
    double length_m = 0;                         // path inside (+inf: thick)
    // Eye-side refraction: relative index η = n_medium/n_outside (1: none). With η ≠ 1 the
    // view ray is refracted into the medium and μ_e, g use the refracted direction; with
    // `fresnel` the radiance is multiplied by the unpolarised Fresnel transmittance of
    // the exit (the light side is not refracted: the light path of docs/PHYSICS.md §1.2 is straight).
    double eta = 1.0;
    bool fresnel = false;
};

// Throws std::invalid_argument naming the field: negative/NaN coefficients, a
// non-unit normal or eye direction, a viewer below the surface (ω·n ≤ 0).
void check_near_light_query(const NearLightQuery &q);

// The dimensionless parameters of a query (after eye-side refraction). `light_below` is
// true when no direct light enters the medium (radiance 0). Validates the query.
struct NearLightParams {
    bool light_below = false;
    double T = 0, g = 0, r = 0, S = 0;
};
NearLightParams near_light_params(const NearLightQuery &q);

// W/(m²·sr); 0 for a light below the surface plane; never NaN.
double near_light_radiance_exact(const NearLightQuery &q);
// Closed forms needing no table (docs/PHYSICS.md §1.3): the thin-medium approximation
// N ≈ H·(1 − e^{−(1+c)S})/((1+c)S), c = 1/r (Gath 2008 §4.2), and the distant-light form
// (Gath 2008 eq. 5) with the light's irradiance at O (I0/l²) as L_in.
double near_light_radiance_thin(const NearLightQuery &q);
double near_light_radiance_distant(const NearLightQuery &q);

namespace detail {
// T·H of a thick medium, slut_nl_H_scaled(g, ∞) = θ/sin θ with g = cos θ and sin_g = sin θ
// (slut_nl_sin_from_cos(g)), as the 3-D table's scalar radiance computes it where the CPU has
// AVX2 and FMA (tables/src/angle_over_sine.hpp: one divide and fdlibm's atan polynomial); the
// tests compare it with a long-double reference.
double near_light_angle_over_sine(double g, double sin_g);
} // namespace detail

// A loaded near-light table (quantity version kNearLightEQuantityVersion):
//  - near_light_E3: axes T, g, r; channel 0 = ln E (S = ∞);
//  - near_light_E4: axes T, g, r, q; channel 0 = ln(E/B), B = slut_nl_E_base(T, r, S). Axis q
//    (warp nl_qodds) spans slabs S ∈ [min, max]; its unit coordinate depends on (T, g)
//    (slut_nl_unit_from_S, kernels/slut_nearlight_slab.h; docs/NEARLIGHT.md).
// Outside the table's domain E is integrated exactly (~1 µs), never clamped.
// Memory: the values as doubles (table()) plus, for f16/f32 storage, a float copy that the
// lookups read (half the bytes a random lookup touches): 12 bytes per node.
class NearLightTable {
public:
    explicit NearLightTable(Table table); // checks kind, version, axes, channel
    bool thick_only() const { return table_.axes.size() == 3; }
    bool covers(double T, double g, double r, double S) const;
    double E(double T, double g, double r, double S) const; // S = +inf: thick
    double radiance(const NearLightQuery &q) const;
    // The same for `count` queries: out[i] is radiance(queries[i]) to within 1e-12 relative
    // (where the CPU has AVX2 and FMA, four queries at a time with glibc's libmvec exp,
    // expm1, log and atan, ≤ 4 ulp, in place of libm's; the table cells of four queries
    // fetched together). Every query is checked before anything is written: a bad one
    // throws std::invalid_argument naming its index and field, and `out` is left as it was.
    // Allocation-free and thread-safe (const, no state); `out` must not overlap `queries`.
    void radiance(const NearLightQuery *queries, size_t count, double *out) const;
    // The parameters (T, g, r, S) of a node (S = +inf in a thick table) and E stored there.
    void node_params(const size_t *node, double *params) const;
    double node_E(const size_t *node) const;
    const Table &table() const { return table_; }

private:
    friend struct NearLightBatch; // the batch radiance (nearlight.cpp)
    Table table_;
    SamplerCache cache_; // of table_
    std::vector<float> values32_; // table_.values as floats when exact (sample_encoded_at_unit)
    // The first three axes' constants as 4-lane arrays (lane 3: a linear axis [0, 2] whose
    // parameter is 1), for their unit coordinates as one vector (nearlight.cpp).
    struct AxisLanes {
        alignas(32) double min[4] = {0, 0, 0, 0}, max[4] = {0, 0, 0, 2}, inv_scale[4] = {1, 1, 1, 1};
        alignas(32) double g0[4] = {0, 0, 0, 0}, inv_span[4] = {1, 1, 1, 0.5}; // 1/(g1 − g0)
        long long warp[4] = {0, 0, 0, 0}; // SLUT_WARP_*
        bool runtime_forms = true;        // every axis has slut_axes.h's lane-generic steps
    } axis_lanes_;
};

} // namespace scatterlut
