#include "scatterlut/airlight_rational.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "require.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"

extern "C" {
#include "slut_airlight_rational.h" /* and through it slut_airlight.h */
}

namespace scatterlut {
namespace {

using detail::require;

constexpr const char *kWhat = "airlight_rational table";

void check_unit_axis(const Axis &a, const char *name) {
    require(a.name == name, std::string(kWhat) + ": expected the axes (x_m, x_t)");
    require(a.map.warp == SLUT_WARP_LINEAR && a.map.min == 0.0 && a.map.max == 1.0,
            std::string(kWhat) + ": the " + name + " axis must be linear on [0, 1]");
}

} // namespace

AirlightRationalTable::AirlightRationalTable(Table table) : table_(std::move(table)) {
    require(table_.kind == kKindAirlightRational, "not an airlight_rational table (kind '" + table_.kind + "')");
    require(table_.quantity_version == kAirlightRationalQuantityVersion,
            std::string(kWhat) + " quantity version " + std::to_string(table_.quantity_version) +
                " is not the one this library knows (" + std::to_string(kAirlightRationalQuantityVersion) + ")");
    require(table_.axes.size() == 2, std::string(kWhat) + ": expected the axes (x_m, x_t)");
    check_unit_axis(table_.axes[0], "x_m");
    check_unit_axis(table_.axes[1], "x_t");
    require(table_.channels.size() == 1 && table_.channels[0].name == "Hn" &&
                table_.channels[0].encoding == Encoding::Linear,
            std::string(kWhat) + ": expected one linear channel Hn");
    table_.check_consistent();
    for (size_t i = 0; i < table_.values.size(); ++i) {
        const double v = table_.values[i];
        if (!(v >= kAirlightRationalMinValue && v <= kAirlightRationalMaxValue)) // NaN too; the message only when it fails
            throw std::invalid_argument(std::string(kWhat) + ": Hn = " + std::to_string(v) + " at " +
                                        detail::describe_value(table_, i) + " is not finite and in [" +
                                        std::to_string(kAirlightRationalMinValue) + ", " +
                                        std::to_string(kAirlightRationalMaxValue) +
                                        "] (the quantity lies in [0.80, 1.29]): the file is corrupt");
    }
    values32_ = float_values_if_exact(table_);
}

double AirlightRationalTable::sample(double x_m, double x_t) const {
    require(!std::isnan(x_m) && !std::isnan(x_t), "airlight_rational sample: a unit coordinate is NaN");
    const double unit[2] = {x_m, x_t}; // clamped to [0, 1] by the sampler (clamp-to-edge)
    return sample_encoded_at_unit(table_, values32_, unit, 0);
}

double AirlightRationalTable::hn(double u, double t) const {
    require(u >= 0.0, "airlight_rational hn: u must be >= 0 (NaN is not)");
    require(t >= 0.0, "airlight_rational hn: t must be >= 0 (NaN is not; inf allowed)");
    const double m = u > 0.0 ? u * (1.0 + t) : 0.0;                 // u = 0: m = 0 for every t, ∞ included
    const double x_t = std::isinf(t) ? 1.0 : t / (1.0 + t);         // the axis's definition; t = ∞ its edge
    return sample(slut_airlight_rational_x_m(m), x_t);
}

// The tiers' path (tables/shaders/src/airlight.slsl, SLUT_TIER_ACCURATE: the same arithmetic,
// the bilinear done by hand) in double: the algebraic set-up of both ends and the segment, two
// samples, their difference or the segment's rule where it would cancel.
double AirlightRationalTable::radiance(const AirlightQuery &q) const {
    check_airlight_query(q);
    // sin γ and cos γ from the half angle, as the airlight runtime forms them (airlight.cpp).
    const double half = std::fmin(0.5 * q.gamma_rad, SLUT_PIO2_HI);
    double sin_half, cos_half;
    slut_sincos_half_angle(half, &sin_half, &cos_half);
    const slut_airlight_rational_setup r = slut_airlight_rational_setup_of(
        q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m, 2.0 * sin_half * cos_half,
        SLUT_AIRLIGHT_COS_GAMMA(sin_half, cos_half), q.length_m);
    // Zero or divergent radiance needs no sample (and its coordinates may be 0/0: γ = 0 at a
    // distance whose h = D·SLUT_TINY underflows).
    if (r.kind != 0) return slut_airlight_rational_radiance(r, 1.0, 1.0);
    return slut_airlight_rational_radiance(r, sample(r.x_m2, r.x_t2), sample(r.x_m1, r.x_t1));
}

void AirlightRationalTable::radiance(const AirlightQuery *queries, size_t count, double *out) const {
    for (size_t i = 0; i < count; ++i) {
        try {
            check_airlight_query(queries[i]);
        } catch (const std::invalid_argument &e) {
            throw std::invalid_argument("query " + std::to_string(i) + ": " + e.what());
        }
    }
    for (size_t i = 0; i < count; ++i) out[i] = radiance(queries[i]);
}

} // namespace scatterlut
