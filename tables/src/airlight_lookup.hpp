// AirlightTable::ln_gs_at (internal; not installed): ln G̃ at unit coordinates from the float
// copy, inline in both paths that read the table's cells by hand: the portable two-sample
// radiance (airlight.cpp) and the AVX2 path (airlight_avx2.cpp).
#pragma once

#include <cstddef>

#include "scatterlut/airlight.hpp"

namespace scatterlut {

// ln G̃ at unit coordinates from the float copy: sample_encoded_at_unit's 2-D case (the
// same lerps in the same order: identical values) with the u cell given.
inline __attribute__((always_inline)) double AirlightTable::ln_gs_at(int cell_u, double frac_u,
                                                                        double unit_w) const {
    int cell_w;
    double frac_w;
    slut_cell_from_unit(unit_w, count_w_, &cell_w, &frac_w);
    const float *v = values32_.data() + (static_cast<size_t>(cell_w) * static_cast<size_t>(count_u_) +
                                         static_cast<size_t>(cell_u)) * channels_;
    const size_t row = static_cast<size_t>(count_u_) * channels_;
    auto lerp = [](double lower, double upper, double f) {
        return f == 0.0 ? lower : f == 1.0 ? upper : lower + f * (upper - lower);
    };
    const double lower = lerp(v[0], v[row], frac_w), upper = lerp(v[channels_], v[row + channels_], frac_w);
    return lerp(lower, upper, frac_u);
}

} // namespace scatterlut
