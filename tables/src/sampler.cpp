#include "scatterlut/sampler.hpp"

#include <cmath>

namespace scatterlut {

double decode(Encoding encoding, double stored) {
    return encoding == Encoding::Log ? std::exp(stored) : stored;
}

SamplerCache make_sampler_cache(const Table &table) {
    SamplerCache c;
    for (size_t a = 0; a < table.axes.size() && a < 8; ++a)
        slut_axis_warped_ends(&table.axes[a].map, &c.g0[a], &c.g1[a]);
    return c;
}

double sample_encoded(const Table &table, const double *params, size_t channel) {
    return sample_encoded(table, make_sampler_cache(table), params, channel);
}

double sample_encoded(const Table &table, const SamplerCache &cache, const double *params, size_t channel) {
    double unit[8];
    for (size_t a = 0; a < table.axes.size() && a < 8; ++a)
        unit[a] = slut_unit_from_warped(&table.axes[a].map, params[a], cache.g0[a], cache.g1[a]);
    return sample_encoded_at_unit(table, unit, channel);
}

// Multilinear interpolation as successive linear ones: gather the 2^n corner values of the
// cell (corner bit a set = upper node on axis a), then halve the set once per axis, highest
// axis first: 2^n − 1 lerps instead of 2^n products of n weights. A lerp with fraction 0
// (1) returns its lower (upper) value exactly, so a zero-weight corner never enters the
// sum (as a product of weights would guarantee).
double sample_encoded_at_unit(const Table &table, const double *unit, size_t channel) {
    const size_t n_axes = table.axes.size() < 8 ? table.axes.size() : 8; // the file format's bound
    double frac[8];
    size_t offset[256];
    double v[256];
    size_t base = channel, stride = table.channels.size();
    offset[0] = 0;
    for (size_t a = 0; a < n_axes; ++a) {
        const slut_axis &map = table.axes[a].map;
        int lower;
        slut_cell_from_unit(unit[a], map.count, &lower, &frac[a]);
        base += static_cast<size_t>(lower) * stride;
        const size_t half = size_t{1} << a;
        for (size_t c = 0; c < half; ++c) offset[half + c] = offset[c] + stride;
        stride *= static_cast<size_t>(map.count);
    }
    const size_t corners = size_t{1} << n_axes;
    const double *values = table.values.data() + base;
    for (size_t c = 0; c < corners; ++c) v[c] = values[offset[c]];
    for (size_t a = n_axes; a-- > 0;) {
        const size_t half = size_t{1} << a;
        const double f = frac[a];
        for (size_t c = 0; c < half; ++c)
            v[c] = f == 0.0 ? v[c] : f == 1.0 ? v[c + half] : v[c] + f * (v[c + half] - v[c]);
    }
    return v[0];
}

double sample(const Table &table, const double *params, size_t channel) {
    return decode(table.channels[channel].encoding, sample_encoded(table, params, channel));
}

double sample(const Table &table, const SamplerCache &cache, const double *params, size_t channel) {
    return decode(table.channels[channel].encoding, sample_encoded(table, cache, params, channel));
}

} // namespace scatterlut
