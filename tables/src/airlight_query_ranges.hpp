// The airlight query's valid ranges (internal; not installed): check_airlight_query's
// conditions, each field of AirlightQuery in a closed range [lo, hi] (x > 0 as x ≥ the least
// subnormal; NaN is in none), with the message its check throws. Written once as ranges so
// that the batch can check its queries' fields as one flat array of doubles
// (airlight_batch.cpp, every_field_in_range); query_conditions states them as require.hpp's
// Conditions (the scalar check, airlight_query.cpp, and the AVX2 path's one test,
// airlight_avx2.cpp).
#pragma once

#include <array>
#include <cstddef>
#include <limits>
#include <type_traits>

#include "require.hpp"
#include "scatterlut/airlight.hpp"

namespace scatterlut {
namespace {

struct FieldRange {
    double lo, hi;
    const char *message;
};
constexpr double kLargest = std::numeric_limits<double>::max();
constexpr FieldRange kQueryRanges[6] = {
    {0.0, kLargest, "sigma_s must be finite and >= 0 (1/m)"},
    {0.0, kLargest, "sigma_a must be finite and >= 0 (1/m)"},
    {0.0, kLargest, "intensity must be finite and >= 0 (W/sr)"},
    {std::numeric_limits<double>::denorm_min(), kLargest, "distance must be finite and > 0 (m)"},
    {0.0, 3.14159265358979323846 + 1e-15, "gamma must lie in [0, pi] (rad)"},
    {0.0, std::numeric_limits<double>::infinity(), "length must be >= 0 (m; inf allowed)"}};
// The fields in kQueryRanges' order, as the six consecutive doubles of the struct.
static_assert(sizeof(AirlightQuery) == 6 * sizeof(double) && std::is_standard_layout_v<AirlightQuery>);
static_assert(offsetof(AirlightQuery, sigma_s_per_m) == 0 && offsetof(AirlightQuery, sigma_a_per_m) == 8 &&
              offsetof(AirlightQuery, intensity_W_per_sr) == 16 && offsetof(AirlightQuery, distance_m) == 24 &&
              offsetof(AirlightQuery, gamma_rad) == 32 && offsetof(AirlightQuery, length_m) == 40);

inline detail::Condition in_range(double x, const FieldRange &range) {
    const bool holds = (x >= range.lo) & (x <= range.hi); // NaN: false
    return {holds, range.message};
}
inline std::array<detail::Condition, 6> query_conditions(const AirlightQuery &q) {
    return {in_range(q.sigma_s_per_m, kQueryRanges[0]), in_range(q.sigma_a_per_m, kQueryRanges[1]),
            in_range(q.intensity_W_per_sr, kQueryRanges[2]), in_range(q.distance_m, kQueryRanges[3]),
            in_range(q.gamma_rad, kQueryRanges[4]), in_range(q.length_m, kQueryRanges[5])};
}

} // namespace
} // namespace scatterlut
