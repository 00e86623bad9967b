// The spot light's airlight from a point-light airlight table (scatterlut/spot.hpp;
// docs/PHYSICS.md §1.6). The ray is cut as for the exact airlight (spot_ray_pieces): a hard
// piece [t0, t1] is e^{−σ_t t0} times the table's radiance of the sub-segment seen from x(t0);
// a falloff-band piece [a, b] is integrated by parts against the table's radiance of its
// sub-segments, with k the point light's integrand,
//   ∫_a^b f k dt = f(a) R(a) + ∫_a^b R f' dt,  R(t) = ∫_t^b k   (where f(a) ≤ f(b)),
//   ∫_a^b f k dt = f(b) Λ(b) − ∫_a^b Λ f' dt,  Λ(t) = ∫_a^t k   (where f(a) > f(b)),
// so that the boundary term is the smaller end's and, for a monotone f, the two terms add
// instead of cancelling. R and Λ are table radiances (viewer shifted to the sub-segment's
// start); the remaining integral, of a smooth product, is an 8-point Gauss–Legendre rule in the
// piece's angle variable (BandSide: β or χ, in which R and Λ stay smooth however close the
// ray passes the light). Cost: 9 table radiances per band piece (more on pieces many extinction
// lengths long: see band_by_parts).
#include "scatterlut/spot.hpp"

#include "spot_band.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

extern "C" {
#include "slut_gauss_legendre.h"
}

namespace scatterlut {
namespace {

using namespace spot_detail; // spot_band.hpp

constexpr int kBandOrder = 8; // Gauss–Legendre nodes per falloff-band piece

struct BandRule {
    double x[kBandOrder], w[kBandOrder];
    BandRule() { slut_gauss_legendre(kBandOrder, x, w); }
};

// e^{−σ_t t0} times the table radiance of [t0, t1] seen from x(t0); 0 for an empty segment.
template <class Table>
double segment(const Table &table, const SpotQuery &q, const SpotRay &ray, double t0_m, double t1_m) {
    if (!(t1_m > t0_m)) return 0.0;
    const double sigma_t = q.sigma_s_per_m + q.sigma_a_per_m;
    const double attenuation = t0_m == 0.0 ? 1.0 : std::exp(-sigma_t * t0_m);
    if (attenuation == 0.0) return 0.0;
    return attenuation * table.radiance(spot_sub_segment_query(q, ray, t0_m, t1_m));
}

// Long band pieces: the remaining integral's R (or Λ) falls by e^{−σ_t Δt} along the piece, so
// a piece many extinction lengths long is cut into sub-pieces of at most kBandSubDepth optical
// depths (at most kBandMaxSubPieces of them), each with the 8-point rule; one that runs on after
// the closest approach (where both e^{−σ_t (t + d)} and 1/d² only fall) ends kBandTailDepth
// optical depths after its start for the rule, the rest in closed form: there R < e^{−40} R(a)
// (its term is below double rounding) and Λ equals Λ(b) to the same relative 4e-18, so
// ∫ Λ f' = Λ(b)·(f(b) − f(t_cut)). `report` on examples/scenes/fog_spots.toml, view "along"
// (rays from behind the light meeting the beam 1–6 km away): the rule alone was off by up to
// 99 % with one rule over the piece, 8.8e-6 now (docs/SPOT.md, "Long band pieces").
constexpr double kBandSubDepth = 4.0;
constexpr double kBandTailDepth = 40.0;
constexpr int kBandMaxSubPieces = 16;

template <class Table>
double band_by_parts(const Table &table, const SpotQuery &q, const SpotRay &ray, const SpotPiece &piece) {
    static const BandRule rule;
    const BandSide side{&ray, 0.5 * (piece.t0_m + piece.t1_m) > ray.closest_t_m || std::isinf(piece.t1_m)};
    const double a = piece.t0_m, b = piece.t1_m;
    const double ea = side.angle_of(a), eb = side.angle_of(b);
    const double fa = side.falloff(ea), fb = side.falloff(eb);
    const bool from_start = fa <= fb; // R-form: the boundary term at a
    const double whole = segment(table, q, ray, a, b); // R(a) = Λ(b)
    double sum = (from_start ? fa : fb) * whole;
    if (sum == HUGE_VAL) return sum;
    // Where the rule stops (t_end) and into how many sub-pieces it cuts [a, t_end].
    const double sigma_t = q.sigma_s_per_m + q.sigma_a_per_m;
    double t_end = b;
    if (side.after && sigma_t > 0.0 && (b - a) * sigma_t > kBandTailDepth) t_end = a + kBandTailDepth / sigma_t;
    const double depth = sigma_t * (t_end - a);
    const int pieces = depth > kBandSubDepth ? std::min(kBandMaxSubPieces, static_cast<int>(std::ceil(depth / kBandSubDepth))) : 1;
    double parts = 0.0;
    for (int k = 0; k < pieces; ++k) {
        const double t0 = k == 0 ? a : a + (t_end - a) * k / pieces;
        const double t1 = k + 1 == pieces ? t_end : a + (t_end - a) * (k + 1) / pieces;
        const double e0 = side.angle_of(t0), e1 = side.angle_of(t1);
        const double half = 0.5 * (e1 - e0), mid = 0.5 * (e0 + e1); // signed: ∫ … dt = ∫ … dη
        double sub = 0.0;
        for (int i = 0; i < kBandOrder; ++i) {
            const double e = mid + half * rule.x[i];
            const double t = side.depth_of(e);
            const double rate = side.falloff_rate(e); // df/dη
            if (rate == 0.0) continue;
            const double rest = from_start ? segment(table, q, ray, t, b) : segment(table, q, ray, a, t);
            sub += rule.w[i] * rest * rate;
        }
        parts += half * sub;
    }
    if (t_end < b && !from_start) parts += whole * (fb - side.falloff(side.angle_of(t_end))); // Λ = Λ(b) beyond t_end
    return from_start ? sum + parts : sum - parts;
}

template <class Table>
double spot_from_table(const Table &table, const SpotQuery &q) {
    check_spot_query(q);
    if (q.light.inner_angle_rad >= kPi) // the point light
        return table.radiance(airlight_query_from_points(q.viewer_m.data(), q.view_dir.data(),
                                                         q.light.position_m.data(), q.length_m, q.sigma_s_per_m,
                                                         q.sigma_a_per_m, q.light.intensity_W_per_sr));
    if (q.sigma_s_per_m == 0.0 || q.light.intensity_W_per_sr == 0.0 || q.length_m == 0.0) return 0.0;
    const SpotRay ray = spot_ray_pieces(q);
    if (ray.through_lit_light) return HUGE_VAL;
    double sum = 0.0;
    for (const SpotPiece &p : ray.pieces)
        sum += p.kind == SpotPieceKind::band ? band_by_parts(table, q, ray, p)
                                             : p.falloff * segment(table, q, ray, p.t0_m, p.t1_m);
    return sum > 0.0 ? sum : 0.0; // never negative (the by-parts sum of a tiny band may round below 0)
}

} // namespace

double detail::spot_airlight_radiance_from(const PointLightRadiance &point_radiance, const SpotQuery &q) {
    struct Wrapped {
        const PointLightRadiance &f;
        double radiance(const AirlightQuery &a) const { return f(a); }
    };
    return spot_from_table(Wrapped{point_radiance}, q);
}

double spot_airlight_radiance(const AirlightTable &table, const SpotQuery &q) { return spot_from_table(table, q); }

double spot_airlight_radiance(const AirlightHgTable &table, const SpotQuery &q) { return spot_from_table(table, q); }

Rgb spot_airlight_radiance_rgb(const AirlightTable &table, const SpotQuery &q, const Rgb &sigma_s_per_m,
                               const Rgb &sigma_a_per_m) {
    return per_channel(q, sigma_s_per_m, sigma_a_per_m,
                       [&table](const SpotQuery &one) { return spot_from_table(table, one); });
}

Rgb spot_airlight_radiance_rgb(const AirlightHgTable &table, const SpotQuery &q, const Rgb &sigma_s_per_m,
                               const Rgb &sigma_a_per_m) {
    return per_channel(q, sigma_s_per_m, sigma_a_per_m,
                       [&table](const SpotQuery &one) { return spot_from_table(table, one); });
}

// ---------------------------------------------------------------- batches
namespace {
// Every query checked before the first is computed (the first bad one named by its index).
// The RGB forms check each query's geometry with the batch's medium (its own σ fields unread).
void check_spot_queries(const SpotQuery *queries, size_t count, const Rgb *sigma_s = nullptr,
                        const Rgb *sigma_a = nullptr) {
    for (size_t i = 0; i < count; ++i) {
        try {
            SpotQuery q = queries[i];
            if (sigma_s) {
                check_rgb_coefficients(*sigma_s, *sigma_a);
                q.sigma_s_per_m = (*sigma_s)[0];
                q.sigma_a_per_m = (*sigma_a)[0];
            }
            check_spot_query(q);
        } catch (const std::invalid_argument &e) {
            throw std::invalid_argument("query " + std::to_string(i) + ": " + e.what());
        }
    }
}
} // namespace

void spot_airlight_radiance(const AirlightTable &table, const SpotQuery *queries, size_t count, double *out) {
    check_spot_queries(queries, count);
    for (size_t i = 0; i < count; ++i) out[i] = spot_airlight_radiance(table, queries[i]);
}

void spot_airlight_radiance(const AirlightHgTable &table, const SpotQuery *queries, size_t count, double *out) {
    check_spot_queries(queries, count);
    for (size_t i = 0; i < count; ++i) out[i] = spot_airlight_radiance(table, queries[i]);
}

void spot_airlight_radiance_rgb(const AirlightTable &table, const SpotQuery *queries, size_t count,
                                const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m, Rgb *out) {
    check_spot_queries(queries, count, &sigma_s_per_m, &sigma_a_per_m);
    for (size_t i = 0; i < count; ++i) out[i] = spot_airlight_radiance_rgb(table, queries[i], sigma_s_per_m, sigma_a_per_m);
}

void spot_airlight_radiance_rgb(const AirlightHgTable &table, const SpotQuery *queries, size_t count,
                                const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m, Rgb *out) {
    check_spot_queries(queries, count, &sigma_s_per_m, &sigma_a_per_m);
    for (size_t i = 0; i < count; ++i) out[i] = spot_airlight_radiance_rgb(table, queries[i], sigma_s_per_m, sigma_a_per_m);
}

} // namespace scatterlut
