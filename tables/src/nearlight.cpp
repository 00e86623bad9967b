#include "scatterlut/nearlight.hpp"

#include "require.hpp"

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "scatterlut/io.hpp"
#include "sampler_cell.hpp"
#include "scatterlut/sampler.hpp"
#include "angle_over_sine.hpp"
#include "nearlight_query.hpp"
#include "simd4.hpp"

extern "C" {
#include "slut_nearlight.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

// |v|² = 1 within 1e-9. The norm by explicit fma: the same double in the check below and in
// the scalar radiance's fast path (compiled for FMA, where the compiler would contract a
// written-out sum there and not here), so that a query at the tolerance's edge is accepted
// or refused by both.
bool unit_vector(const double *v) {
    const double n2 = std::fma(v[0], v[0], std::fma(v[1], v[1], v[2] * v[2]));
    return std::fabs(n2 - 1.0) < 1e-9;
}

// check_near_light_query's conditions (require.hpp's Condition), each with the message it
// throws; NaN fails every one. The check takes them one by one; the scalar radiance's fast
// path all at once.
inline std::array<detail::Condition, 10> query_conditions(const NearLightQuery &q) {
    constexpr double largest = std::numeric_limits<double>::max();
    const auto finite_nonnegative = [](double x) -> bool { return (x >= 0.0) & (x <= largest); };
    const auto finite_positive = [](double x) -> bool { return (x > 0.0) & (x <= largest); };
    const auto finite = [](double x) -> bool { return std::fabs(x) <= largest; };
    return {{{finite_nonnegative(q.sigma_s_per_m), "sigma_s must be finite and >= 0 (1/m)"},
             {finite_nonnegative(q.sigma_a_per_m), "sigma_a must be finite and >= 0 (1/m)"},
             {finite_nonnegative(q.intensity_W_per_sr), "intensity must be finite and >= 0 (W/sr)"},
             {q.length_m >= 0.0, "length must be >= 0 (m; inf for a thick medium)"},
             {unit_vector(q.normal), "normal must be a unit vector"},
             {unit_vector(q.eye_dir), "eye_dir must be a unit vector"},
             {finite_positive(q.eta), "eta (relative index of refraction) must be finite and > 0"},
             {finite(q.light_rel_m[0]), "light_pos must be finite"},
             {finite(q.light_rel_m[1]), "light_pos must be finite"},
             {finite(q.light_rel_m[2]), "light_pos must be finite"}}};
}

using detail::near_light_exit_transmittance;
using detail::near_light_params_unchecked;

slut_nl_params params_unchecked(const NearLightQuery &q) { return near_light_params_unchecked(q); }

slut_nl_params params(const NearLightQuery &q) {
    check_near_light_query(q);
    return params_unchecked(q);
}

slut_vec3 vec3(const double *v) { return slut_vec3_make(v[0], v[1], v[2]); }

// The viewer sees the medium (eye_dir · normal > 0): near_light_params_unchecked throws otherwise.
bool viewer_above(const NearLightQuery &q) { return slut_vec3_dot(vec3(q.eye_dir), vec3(q.normal)) > 0.0; }

// The kernel's function, inline in the radiance's fast path (through the exported
// detail::near_light_exit_transmittance it was a call, and eight registers spilled around it).
double exit_transmittance(const NearLightQuery &q) {
    return slut_exit_transmittance(vec3(q.normal), vec3(q.eye_dir), q.eta, q.fresnel ? 1 : 0);
}

// σ_s/(4π)·I0·E·(T·H)/l with the exit's Fresnel factor (slut_nl_assemble); the factor only
// where the assembly uses it.
double assemble(const NearLightQuery &q, const slut_nl_params &p, double E) {
    if (p.kind != SLUT_NL_OK) return 0.0;
    return slut_nl_assemble(p, q.sigma_s_per_m, q.intensity_W_per_sr, q.length_m, exit_transmittance(q), E);
}

} // namespace

// (T, g, r, S) of the query: slut_nl_params_seen (the eye ray refracted where eta ≠ 1), the
// front-end the near-light snippet calls too.
slut_nl_params detail::near_light_params_unchecked(const NearLightQuery &q) {
    require(viewer_above(q), "the viewer is below the surface (eye_dir . normal <= 0)");
    return slut_nl_params_seen(vec3(q.normal), vec3(q.eye_dir), vec3(q.light_rel_m), q.sigma_s_per_m + q.sigma_a_per_m,
                               q.length_m, q.eta);
}

double detail::near_light_exit_transmittance(const NearLightQuery &q) { return exit_transmittance(q); }

#if SLUT_HAVE_SIMD4
namespace {
// The form e3_radiance takes (one lane of simd4::v2d, compiled for AVX2 and FMA).
SLUT_SIMD4_TARGET double angle_over_sine_simd(double g, double sin_g) {
    return detail::angle_over_sine(simd4::v2d{g, g}, simd4::v2d{sin_g, sin_g})[0];
}
} // namespace
#endif

double detail::near_light_angle_over_sine(double g, double sin_g) {
#if SLUT_HAVE_SIMD4
    if (simd4::available()) return angle_over_sine_simd(g, sin_g);
#endif
    return angle_over_sine(g, sin_g);
}

void check_near_light_query(const NearLightQuery &q) {
    detail::require_each(query_conditions(q));
}

NearLightParams near_light_params(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    NearLightParams out;
    out.light_below = p.kind != SLUT_NL_OK;
    out.T = p.T;
    out.g = p.g;
    out.r = p.r;
    out.S = p.S;
    return out;
}

double near_light_radiance_exact(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    return assemble(q, p, p.T > 0.0 ? slut_nl_E(p.T, p.g, p.r, p.S) : 1.0);
}

double near_light_radiance_thin(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    return assemble(q, p, slut_nl_E_thin(p.r, p.S));
}

double near_light_radiance_distant(const NearLightQuery &q) {
    const slut_nl_params p = params(q);
    if (p.kind != SLUT_NL_OK || !(p.distance_m > 0.0)) return 0.0;
    const double irradiance = q.intensity_W_per_sr / (p.distance_m * p.distance_m); // W/m² at normal incidence
    return exit_transmittance(q) *
           slut_distant_light_radiance(q.sigma_s_per_m, q.sigma_a_per_m, irradiance, p.mu_e, p.mu_l, q.length_m);
}

NearLightTable::NearLightTable(Table table) : table_(std::move(table)) {
    const bool e3 = table_.kind == kKindNearLightE3, e4 = table_.kind == kKindNearLightE4;
    require(e3 || e4, "not a near-light table (kind '" + table_.kind + "')");
    require(table_.quantity_version == kNearLightEQuantityVersion,
            "near-light table quantity version " + std::to_string(table_.quantity_version) + " is not the one (" +
                std::to_string(kNearLightEQuantityVersion) + ") this library knows: regenerate the table");
    require(table_.axes.size() == (e3 ? 3u : 4u), "near-light table has the wrong number of axes");
    require(table_.axes[0].name == "T" && table_.axes[1].name == "g" && table_.axes[2].name == "r" &&
                (e3 || table_.axes[3].name == "q"),
            "near-light table axes must be (T, g, r) or (T, g, r, q)");
    for (size_t a = 0; a < 3; ++a)
        require(table_.axes[a].map.warp != SLUT_WARP_NL_QODDS, "near-light axis " + table_.axes[a].name +
                                                                   " cannot use the slab warp 'nl_qodds'");
    require(e3 || table_.axes[3].map.warp == SLUT_WARP_NL_QODDS, "near-light axis q must use the warp 'nl_qodds'");
    const char *channel = e3 ? "ln_E" : "ln_E_over_B";
    require(!table_.channels.empty() && table_.channels[0].name == channel &&
                table_.channels[0].encoding == Encoding::Log,
            std::string("near-light table channel 0 must be ") + channel + " (log encoded)");
    table_.check_consistent();
    // E ∈ (0, 1] (an attenuation mean): ln E ≤ 0 for E3; E4 stores ln(E/B) with
    // B ≥ e^{−T} (slut_nl_E_base), so ln(E/B) ≤ T at the node's T. Beyond rounding, or
    // below −1e6, a value is no near-light value.
    const size_t stride = table_.channels.size(), n_T = static_cast<size_t>(table_.axes[0].map.count);
    for (size_t i = 0; i < table_.values.size(); i += stride) {
        const double T = slut_axis_node(&table_.axes[0].map, static_cast<int>((i / stride) % n_T));
        const double hi = (e3 ? 0.0 : T) + kLnRoundingSlack;
        if (!(table_.values[i] >= kMinStoredLn && table_.values[i] <= hi)) // the message only when it fails
            throw std::invalid_argument(std::string("near-light table: ") + channel + " = " +
                                        std::to_string(table_.values[i]) + " at " + detail::describe_value(table_, i) +
                                        " is outside the quantity's range (E in (0, 1]: " +
                                        (e3 ? "ln E <= 0" : "ln(E/B) <= T") + "): the file is corrupt");
    }
    cache_ = make_sampler_cache(table_);
    for (size_t a = 0; a < 3; ++a) {
        const slut_axis &axis = table_.axes[a].map;
        axis_lanes_.min[a] = axis.min;
        axis_lanes_.max[a] = axis.max;
        axis_lanes_.g0[a] = cache_.g0[a];
        axis_lanes_.inv_scale[a] = 1.0 / axis.scale;
        axis_lanes_.inv_span[a] = 1.0 / (cache_.g1[a] - cache_.g0[a]);
        axis_lanes_.warp[a] = axis.warp;
        axis_lanes_.runtime_forms = axis_lanes_.runtime_forms && SLUT_WARP_HAS_RUNTIME_FORM(axis.warp);
    }
    values32_ = float_values_if_exact(table_);
}

bool NearLightTable::covers(double T, double g, double r, double S) const {
    const bool e3 = thick_only();
    return slut_nl_table_covers(table_.axes[0].map, table_.axes[1].map, table_.axes[2].map,
                                table_.axes[e3 ? 0 : 3].map /* E3: unused */, e3 ? 1 : 0, T, g, r, S) != 0;
}

double NearLightTable::E(double T, double g, double r, double S) const {
    if (!covers(T, g, r, S)) return T > 0.0 ? slut_nl_E(T, g, r, S) : 1.0;
    double unit[4];
    const double p[3] = {T, g, r};
    for (size_t a = 0; a < 3; ++a) unit[a] = slut_unit_from_warped_runtime(&table_.axes[a].map, p[a], cache_.g0[a], cache_.g1[a]);
    if (thick_only()) return std::exp(sample_encoded_at_unit(table_, values32_, unit, 0));
    unit[3] = slut_nl_unit_from_S(&table_.axes[3].map, T, g, S);
    return std::exp(sample_encoded_at_unit(table_, values32_, unit, 0)) * slut_nl_E_base(T, r, S);
}

void NearLightTable::node_params(const size_t *node, double *params) const {
    for (size_t a = 0; a < 3; ++a) params[a] = slut_axis_node(&table_.axes[a].map, static_cast<int>(node[a]));
    params[3] = thick_only() ? HUGE_VAL
                             : slut_nl_S_node(&table_.axes[3].map, params[0], params[1], static_cast<int>(node[3]));
}

double NearLightTable::node_E(const size_t *node) const {
    double p[4];
    node_params(node, p);
    const double stored = std::exp(table_.values[table_.index(node)]);
    return thick_only() ? stored : stored * slut_nl_E_base(p[0], p[2], p[3]);
}


#if SLUT_HAVE_SIMD4
namespace {
bool radiance_simd(const NearLightTable &table, const NearLightQuery &q, double *L);
} // namespace
#endif

double NearLightTable::radiance(const NearLightQuery &q) const {
#if SLUT_HAVE_SIMD4
    double L;
    if (simd4::available() && radiance_simd(*this, q, &L)) return L;
#endif
    const slut_nl_params p = params(q);
    if (p.kind != SLUT_NL_OK) return 0.0;
    return assemble(q, p, p.T > 0.0 ? E(p.T, p.g, p.r, p.S) : 1.0);
}

// ------------------------------------------------------------------ batch radiance

#if SLUT_HAVE_SIMD4
// Four queries at a time: each query's parameters (T, g, r, S) lane by lane (dot products
// and a sqrt: slut_nl_params_from_geometry), then in 4-lane vectors what costs: the axis
// warps (one vector log per log-type axis), H (the 3-D table's θ/sin θ by angle_over_sine,
// as the scalar call; a slab's by one vector atan), for the 4-D table the slab coordinate
// (slut_nl_unit_from_S: six vector atans and two vector logs) and the value base
// (slut_nl_E_base: a vector exp and two vector expm1), the decoding exp; the cells of the four
// queries are gathered together (the 3-D table's inline). The value base takes the kernel's lane-generic expressions
// (SLUT_NL_THIN_*, SLUT_NL_BASE_OF_THIN) and the axis warps slut_axes.h's (SLUT_WARP_X,
// SLUT_WARP_ARG, SLUT_WARPED_GIVEN, SLUT_UNIT_OF_WARPED: slut_unit_from_warped_runtime's
// steps) and slut_nl_inv_square_integral's (SLUT_NL_ISQ_*); the tests compare every query with
// the scalar call. Queries the vectors do not serve (zero radiance, the light at the entry
// point, T = 0, outside the table, an axis warp without a vector form) take the scalar
// radiance(q).
struct NearLightBatch {
    using v4d = simd4::v4d;
    using v4l = simd4::v4l;

    const NearLightTable &table;
    const NearLightQuery *queries;
    double *out;

    // slut_nl_inv_square_integral(len, hh2, d, w) lane-wise: the kernel's lane-generic steps
    // (SLUT_NL_ISQ_*, kernels/slut_nearlight_closed.h) around one vector atan. The tests compare
    // every vector query with the scalar path.
    SLUT_SIMD4_TARGET static v4d inv_square_integral4(v4d len, v4d hh2, v4d d, v4d w) {
        const v4d den = SLUT_NL_ISQ_DEN(len, hh2, d);
        const v4d x = SLUT_NL_ISQ_NUM(len, w) / simd4::abs4(den), a = simd4::atan4(x); // a once: the
        return SLUT_NL_ISQ_OF_ATAN(len, den, w, x, a); // macro names it twice, libmvec's call is not CSE'd
    }

    // slut_unit_from_warped_runtime for four queries on one axis (slut_axes.h's lane-generic
    // steps, the warp a scalar); false for the warps without those steps.
    SLUT_SIMD4_TARGET static bool unit4(const slut_axis &a, double g0, double g1, v4d p, v4d *unit) {
        const int warp = a.warp;
        if (!SLUT_WARP_HAS_RUNTIME_FORM(warp)) return false;
        const v4d x = SLUT_WARP_X(warp, p, a.min, a.scale), arg = SLUT_WARP_ARG(warp, p, x);
        const v4d t = warp == SLUT_WARP_SQRT1P ? simd4::sqrt4(simd4::max4(arg, simd4::splat(0.0)))
                      : warp == SLUT_WARP_LINEAR ? arg
                                                 : simd4::log4(arg);
        *unit = SLUT_UNIT_OF_WARPED(p, SLUT_WARPED_GIVEN(warp, p, x, arg, t), a.min, a.max, g0, g1);
        return true;
    }

    // The unit coordinates of one query's (T, g, r) on the table's first three axes, the axes
    // as lanes (slut_axes.h's lane-generic steps, the warps a lane vector): one vector log and
    // one vector sqrt for the three. The two divides by axis constants (x = num/s and the
    // span g1 − g0) as products with reciprocals computed once per table: an ulp or two from
    // the scalar form, two divides fewer on the path to the cell (BM_NearLightRadiance/3
    // 75 → 72 ns in a throw-away driver over the bench's geometries, thread CPU time, minimum
    // of 1000 rounds, three interleaved runs). The vector sqrt's fourth lane, which no axis
    // uses, takes √extra_sqrt_arg into *extra_root (the 3-D call's sin θ: one square root fewer
    // on its path). False where an axis has a warp without those steps.
    SLUT_SIMD4_TARGET static bool units3(const NearLightTable &t, double T, double g, double r, double *unit,
                                         double extra_sqrt_arg = 0.0, double *extra_root = nullptr) {
        const NearLightTable::AxisLanes &lanes = t.axis_lanes_;
        if (!lanes.runtime_forms) return false;
        const v4d p = {T, g, r, 1.0}, p_min = simd4::load4(lanes.min), p_max = simd4::load4(lanes.max);
        const v4l warp = {lanes.warp[0], lanes.warp[1], lanes.warp[2], lanes.warp[3]};
        const v4d x = SLUT_WARP_X_TIMES_SCALE(warp, p, p_min) * simd4::load4(lanes.inv_scale);
        const v4d arg = SLUT_WARP_ARG(warp, p, x);
        const v4l takes_sqrt = warp == SLUT_WARP_SQRT1P, takes_log = !takes_sqrt && warp != SLUT_WARP_LINEAR;
        v4d root_arg = simd4::max4(arg, simd4::splat(0.0));
        root_arg[3] = extra_sqrt_arg;
        const v4d ln = simd4::log4(takes_log ? arg : 1.0), root = simd4::sqrt4(root_arg);
        if (extra_root) *extra_root = root[3];
        const v4d t_arg = takes_log ? ln : takes_sqrt ? root : arg;
        const v4d warped = SLUT_WARPED_GIVEN(warp, p, x, arg, t_arg);
        const v4d u = SLUT_UNIT_CLAMPED(p, p_min, p_max, (warped - simd4::load4(lanes.g0)) * simd4::load4(lanes.inv_span));
        unit[0] = u[0];
        unit[1] = u[1];
        unit[2] = u[2];
        return true;
    }

    // slut_nl_depth_odds_over_TH(g, sg, L) lane-wise.
    SLUT_SIMD4_TARGET static v4d depth_odds_over_TH4(v4d g, v4d sg, v4d L) {
        const v4d d = L + g;
        return inv_square_integral4(L, simd4::splat(1.0), g, sg) /
               inv_square_integral4(simd4::splat(HUGE_VAL), d * d + sg * sg, d, sg);
    }

    // slut_nl_E_base(T, r, S) lane-wise, S finite: the kernel's lane-generic expressions
    // (SLUT_NL_THIN_X, SLUT_NL_THIN_NEEDS_EXPM1, SLUT_NL_THIN_OF_X_WITHOUT_EXPM1,
    // SLUT_NL_BASE_OF_THIN; kernels/slut_nearlight_approx.h and _slab.h, written once for a
    // scalar, the table kernel's double16 and these vectors: GCC's ?: and && select per lane),
    // with the vector exp and expm1.
    SLUT_SIMD4_TARGET static v4d E_base4(v4d T, v4d r, v4d S) {
        const v4d floor_T = simd4::exp4(-T), rise_T = -simd4::expm1_4(-T);
        const v4d S_eff = S * (T / (S + T)); // slut_nl_base_depth, S finite
        const v4d x = SLUT_NL_THIN_X(r, S_eff);
        const v4d thin_mid = -simd4::expm1_4(-x) / x;
        v4d thin = SLUT_NL_THIN_NEEDS_EXPM1(x) ? thin_mid : SLUT_NL_THIN_OF_X_WITHOUT_EXPM1(x);
        thin = simd4::select(S_eff > 0.0, simd4::select(r > 0.0, thin, simd4::splat(0.0)), simd4::splat(1.0));
        return SLUT_NL_BASE_OF_THIN(floor_T, rise_T, thin);
    }

    // θ/sin θ lane-wise: angle_over_sine on two v2d halves (its template is compiled for the
    // baseline ISA, whose ABI a 4-lane vector would change).
    SLUT_SIMD4_TARGET static v4d angle_over_sine4(v4d g, v4d sg) {
        const simd4::v2d lo = detail::angle_over_sine(simd4::v2d{g[0], g[1]}, simd4::v2d{sg[0], sg[1]});
        const simd4::v2d hi = detail::angle_over_sine(simd4::v2d{g[2], g[3]}, simd4::v2d{sg[2], sg[3]});
        return v4d{lo[0], lo[1], hi[0], hi[1]};
    }

    // The 3-D table's stored value at `unit` (sample_encoded_at_unit's interpolation, inline).
    SLUT_SIMD4_TARGET static double lerp_thick(const NearLightTable &t, const double *unit) {
        double corner[8], frac[3];
        if (t.values32_.empty()) detail::gather_cell<3>(t.table_, t.table_.values.data(), unit, 0, corner, frac);
        else detail::gather_cell<3>(t.table_, t.values32_.data(), unit, 0, corner, frac);
        return detail::lerp_cell<3>(corner, frac);
    }

    SLUT_SIMD4_TARGET void block(const size_t *index, int lanes) {
        const NearLightTable &t = table;
        const bool e4 = !t.thick_only();
        v4d T, g, r, S, S_over_T, scale, sg;
        bool vector_lane[4] = {false, false, false, false};
        for (int l = 0; l < 4; ++l) {
            const NearLightQuery &q = queries[index[l < lanes ? l : 0]];
            const slut_nl_params p = params_unchecked(q);
            T[l] = p.T;
            g[l] = p.g;
            r[l] = p.r;
            S[l] = p.S;
            S_over_T[l] = p.S_over_T;
            sg[l] = slut_nl_sin_from_cos(p.g);
            scale[l] = exit_transmittance(q) * q.sigma_s_per_m * SLUT_INV_4PI * q.intensity_W_per_sr / p.distance_m;
            vector_lane[l] = l < lanes && p.kind == SLUT_NL_OK && q.sigma_s_per_m > 0.0 && q.intensity_W_per_sr > 0.0 &&
                             q.length_m > 0.0 && p.distance_m > 0.0 && p.T > 0.0 && t.covers(p.T, p.g, p.r, p.S);
        }
        // Lanes the vectors do not serve repeat a served lane's parameters (never stored).
        int served = -1;
        for (int l = 0; l < 4; ++l)
            if (vector_lane[l]) served = l;
        if (served >= 0)
            for (int l = 0; l < 4; ++l)
                if (!vector_lane[l]) {
                    T[l] = T[served];
                    g[l] = g[served];
                    r[l] = r[served];
                    S[l] = S[served];
                    S_over_T[l] = S_over_T[served];
                    sg[l] = sg[served];
                    scale[l] = scale[served];
                }
        v4d unit[4];
        bool vectors = served >= 0;
        for (int a = 0; a < 3 && vectors; ++a) {
            const v4d p = a == 0 ? T : a == 1 ? g : r;
            vectors = unit4(t.table_.axes[static_cast<size_t>(a)].map, t.cache_.g0[a], t.cache_.g1[a], p, &unit[a]);
        }
        if (vectors) {
            // T·H: θ/sin θ for the 3-D table's thick queries (angle_over_sine.hpp, as the
            // scalar call: one divide, blends), the inverse-square integral to s/l for slabs.
            const v4d H_scaled = e4 ? inv_square_integral4(S_over_T, simd4::splat(1.0), g, sg) : angle_over_sine4(g, sg);
            v4d base = simd4::splat(1.0);
            if (e4) { // slut_nl_unit_from_S_between(T, g, S, S_min, S_max)
                const slut_axis &axis_q = t.table_.axes[3].map;
                const v4d lo = depth_odds_over_TH4(g, sg, axis_q.min / T), hi = depth_odds_over_TH4(g, sg, axis_q.max / T);
                unit[3] = simd4::log4(depth_odds_over_TH4(g, sg, S / T) / lo) / simd4::log4(hi / lo);
                base = E_base4(T, r, S);
            }
            v4d stored;
            for (int l = 0; l < 4; ++l) {
                const double at[4] = {unit[0][l], unit[1][l], unit[2][l], e4 ? unit[3][l] : 0.0};
                stored[l] = e4 ? sample_encoded_at_unit(t.table_, t.values32_, at, 0) : lerp_thick(t, at);
            }
            const v4d L = scale * (simd4::exp4(stored) * base) * H_scaled;
            for (int l = 0; l < lanes; ++l)
                if (vector_lane[l] && std::isfinite(H_scaled[l])) out[index[l]] = L[l];
                else vector_lane[l] = false;
        }
        for (int l = 0; l < lanes; ++l)
            if (!vectors || !vector_lane[l]) out[index[l]] = t.radiance(queries[index[l]]);
    }

    SLUT_SIMD4_TARGET void run(size_t count) {
        for (size_t first = 0; first < count; first += 4) {
            const size_t index[4] = {first, first + 1, first + 2, first + 3};
            block(index, static_cast<int>(count - first < 4 ? count - first : 4));
        }
    }

    // One 3-D query (the scalar radiance): the general path's arithmetic (E's unit coordinates
    // and cell, H, slut_nl_assemble) with the three axis warps as one vector call
    // (units3) and in an order that lets the CPU overlap the cell's memory latency with H (the
    // corners gathered, then H, then the lerps), H = slut_nl_H_scaled(g, ∞) as θ/sin θ in one
    // divide (angle_over_sine.hpp; with libmvec's 4-lane atan and the three vector divides
    // around it the call took 1.02–1.04× the time: 6 interleaved rounds of
    // `scatterlut_bench --benchmark_filter=NearLightRadiance/3`, a 2-core AMD EPYC (Zen) VM),
    // its selects as blends (the v2d form: GCC made branches of the scalar form's, and g is
    // random per query), sin θ from units3's spare square-root lane (the same value as
    // slut_nl_sin_from_cos). The same values as assemble(q, p, E(...)) to libmvec's log against
    // libm's, the atan's ≤ 4 ulp, FMA contraction and the assembly's order (E last). False
    // (nothing computed) where that path must answer: outside the table, T = 0, zero radiance,
    // the light at the entry point, f64 values.
    SLUT_SIMD4_TARGET static bool e3_radiance(const NearLightTable &t, const NearLightQuery &q, const slut_nl_params &p,
                                              double *L) {
        if (t.values32_.empty() || !(q.sigma_s_per_m > 0.0) || !(q.intensity_W_per_sr > 0.0) || !(q.length_m > 0.0) ||
            !(p.distance_m > 0.0) || !(p.T > 0.0) || !t.covers(p.T, p.g, p.r, p.S))
            return false;
        double unit[3], sg;
        const double ag = std::fabs(p.g); // sg = √((1 − |g|)(1 + |g|)): slut_nl_sin_from_cos(g), |g| ≤ 1
        if (!units3(t, p.T, p.g, p.r, unit, (1.0 - ag) * (1.0 + ag), &sg)) return false;
        double corner[8], frac[3];
        detail::gather_cell<3>(t.table_, t.values32_.data(), unit, 0, corner, frac);
        const double H_scaled = angle_over_sine_simd(p.g, sg);
        // slut_nl_assemble_given_H with E = 1, times E: the assembly's multiplies and divide
        // run beside the cell's loads and the decoding exp instead of after them (and its
        // 1/l beside H).
        const double scale = slut_nl_assemble_given_H(p, q.sigma_s_per_m, q.intensity_W_per_sr, q.length_m,
                                                      exit_transmittance(q), 1.0, H_scaled);
        *L = scale * std::exp(detail::lerp_cell<3>(corner, frac));
        return true;
    }

    // One 4-D query (the scalar radiance): its independent transcendentals packed into lanes
    // of the same vector calls. The slab coordinate's seven inverse-square integrals (inside
    // and outside at S, S_min and S_max, and H at s/l) as two vector atans, the three axis
    // warps (units3: their logs and sqrt as one vector log and one vector sqrt) and the
    // coordinate's two logs as one more, the decoding exp with e^{−T}, and the value base's two
    // expm1: 6 vector calls (and a vector sqrt) for 7 atan, 5 log, 2 exp and 2 expm1. The
    // same arithmetic as NearLightTable::E and assemble otherwise. False (nothing computed)
    // where the scalar path must answer: outside the table, zero radiance, H infinite.
    SLUT_SIMD4_TARGET static bool e4_radiance(const NearLightTable &t, const NearLightQuery &q, const slut_nl_params &p,
                                              double *L) {
        if (!(q.sigma_s_per_m > 0.0) || !(q.intensity_W_per_sr > 0.0) || !(q.length_m > 0.0) || !(p.distance_m > 0.0) ||
            !(p.T > 0.0) || !t.covers(p.T, p.g, p.r, p.S))
            return false;
        double unit[4];
        if (!units3(t, p.T, p.g, p.r, unit)) return false;
        const slut_axis &axis_q = t.table_.axes[3].map;
        const double T = p.T, g = p.g, sg = slut_nl_sin_from_cos(g);
        const v4d lengths = {p.S / T, axis_q.min / T, axis_q.max / T, p.S_over_T};
        const v4d inside = inv_square_integral4(lengths, simd4::splat(1.0), simd4::splat(g), simd4::splat(sg));
        const v4d d = lengths + g;
        const v4d outside = inv_square_integral4(simd4::splat(HUGE_VAL), d * d + sg * sg, d, simd4::splat(sg));
        const double H_scaled = inside[3];
        if (!std::isfinite(H_scaled)) return false;
        const v4d odds = inside / outside; // lanes 0–2: S, S_min, S_max
        const v4d ratio_logs = simd4::log4(v4d{odds[0] / odds[1], odds[2] / odds[1], 1.0, 1.0});
        unit[3] = ratio_logs[0] / ratio_logs[1];
        const double stored = sample_encoded_at_unit(t.table_, t.values32_, unit, 0);
        // slut_nl_E_base(T, r, S): floor e^{−T}, rise −expm1(−T), E_thin(r, S_eff)
        const double r = p.r, S_eff = slut_nl_base_depth(T, p.S);
        const double x = (r > SLUT_INFINITE_ABOVE) ? S_eff : S_eff * ((1.0 + r) / r);
        const v4d e = simd4::exp4(v4d{stored, -T, 0.0, 0.0});
        const v4d em1 = simd4::expm1_4(v4d{-T, -x, 0.0, 0.0});
        double thin;
        if (!(S_eff > 0.0)) thin = 1.0;
        else if (!(r > 0.0)) thin = 0.0;
        else thin = SLUT_NL_THIN_NEEDS_EXPM1(x) ? -em1[1] / x : SLUT_NL_THIN_OF_X_WITHOUT_EXPM1(x);
        const double E = e[0] * SLUT_NL_BASE_OF_THIN(e[1], -em1[0], thin);
        *L = slut_nl_assemble_given_H(p, q.sigma_s_per_m, q.intensity_W_per_sr, q.length_m, exit_transmittance(q), E,
                                      H_scaled);
        return true;
    }
};

namespace {
// The scalar radiance where the CPU has AVX2 and FMA, from the query to the radiance in one
// function compiled for them: query_conditions (check_near_light_query's) as one test, the
// front-end (slut_nl_params_seen) inlined, then e3_radiance or e4_radiance. False (nothing
// computed) where NearLightTable::radiance's general path must answer: a query that fails a
// check (that path throws, naming the field), no light reaching the medium, the cases
// e3_radiance and e4_radiance leave. Flattened: the front-end and the table's checks inline
// (as calls they were ~10 % of the call's samples in `perf record`).
SLUT_SIMD4_TARGET __attribute__((flatten)) bool radiance_simd(const NearLightTable &table, const NearLightQuery &q, double *L) {
    if (!detail::all_hold(query_conditions(q))) return false;
    const slut_nl_params p = slut_nl_params_seen(vec3(q.normal), vec3(q.eye_dir), vec3(q.light_rel_m),
                                                 q.sigma_s_per_m + q.sigma_a_per_m, q.length_m, q.eta);
    if (p.kind != SLUT_NL_OK) return false;
    return table.thick_only() ? NearLightBatch::e3_radiance(table, q, p, L) : NearLightBatch::e4_radiance(table, q, p, L);
}
} // namespace
#endif

namespace {
// Every query's conditions (check_near_light_query's and the viewer above the surface, the
// one near_light_params_unchecked throws on) at once (require_every_query), the first failing
// query named by its index (check_near_light_query and the front-end per query, as before,
// took the 3-D batch from ~101 to ~123 ns per query: `scatterlut_bench
// --benchmark_filter=RadianceBatch/3`, 2-core AMD EPYC VM).
void check_near_light_queries(const NearLightQuery *queries, size_t count) {
    detail::require_every_query(
        queries, count,
        [](const NearLightQuery &q) { return detail::all_hold(query_conditions(q)) & viewer_above(q); },
        [](const NearLightQuery &q) {
            check_near_light_query(q);
            params_unchecked(q);
        });
}
} // namespace

void NearLightTable::radiance(const NearLightQuery *queries, size_t count, double *out) const {
    check_near_light_queries(queries, count);
#if SLUT_HAVE_SIMD4
    if (simd4::available()) {
        NearLightBatch{*this, queries, out}.run(count);
        return;
    }
#endif
    for (size_t i = 0; i < count; ++i) out[i] = radiance(queries[i]);
}

} // namespace scatterlut
