// scatterlut runtime (internal) — the multilinear interpolation of one table cell, in two
// steps: gather_cell loads the cell's 2^n corner values and its n fractions, lerp_cell
// interpolates them. sample_encoded_at_unit is the two back to back; a caller that inlines
// them can compute, between the two, what does not depend on the table while the corners
// arrive (a random cell of a large table misses the caches: NearLightTable's thick radiance
// computes H there).
//
// Multilinear interpolation as successive linear ones: gather the 2^n corner values of the
// cell (corner bit a set = upper node on axis a), then halve the set once per axis, highest
// axis first: 2^n − 1 lerps instead of 2^n products of n weights. A lerp with fraction 0
// (1) returns its lower (upper) value exactly, so a zero-weight corner never enters the
// sum (as a product of weights would guarantee). N is the number of axes: fixed at compile
// time for the tables the library knows (2-D airlight, 3-D and 4-D near light), so that
// the corner loops unroll (the pragmas: GCC's -O2 does not peel them) and the cell's offsets
// stay in registers.
#pragma once

#include <cstddef>

#include "scatterlut/table.hpp"

namespace scatterlut::detail {

inline double lerp_exact_ends(double lower, double upper, double f) {
    return f == 0.0 ? lower : f == 1.0 ? upper : lower + f * (upper - lower);
}

// v[0 .. 2^N): the corners of the cell holding `unit` (one unit coordinate per axis, each
// clamped to [0, 1]) in channel `channel` of all_values (table.values or its float copy);
// frac[0 .. N): the positions in the cell.
template <size_t N, typename Value>
inline void gather_cell(const Table &table, const Value *all_values, const double *unit, size_t channel, double *v,
                        double *frac) {
    constexpr size_t corners = size_t{1} << N;
    size_t offset[corners];
    size_t base = channel, stride = table.channels.size();
    offset[0] = 0;
#pragma GCC unroll 8
    for (size_t a = 0; a < N; ++a) {
        const int count = table.axes[a].map.count;
        int lower;
        slut_cell_from_unit(unit[a], count, &lower, &frac[a]);
        base += static_cast<size_t>(lower) * stride;
        const size_t half = size_t{1} << a;
#pragma GCC unroll 128
        for (size_t c = 0; c < half; ++c) offset[half + c] = offset[c] + stride;
        stride *= static_cast<size_t>(count);
    }
    const Value *values = all_values + base;
#pragma GCC unroll 256
    for (size_t c = 0; c < corners; ++c) v[c] = values[offset[c]];
}

// The interpolated value from gather_cell's corners (overwrites v).
template <size_t N>
inline double lerp_cell(double *v, const double *frac) {
#pragma GCC unroll 8
    for (size_t k = 0; k < N; ++k) { // axis a = N − 1 − k: the highest first
        const size_t a = N - 1 - k, half = size_t{1} << a;
#pragma GCC unroll 128
        for (size_t c = 0; c < half; ++c) v[c] = lerp_exact_ends(v[c], v[c + half], frac[a]);
    }
    return v[0];
}

} // namespace scatterlut::detail
