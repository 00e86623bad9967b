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

double sample_encoded_at_unit(const Table &table, const double *unit, size_t channel) {
    const size_t n_axes = table.axes.size();
    const size_t n_channels = table.channels.size();
    // Per axis: lower node and fraction. At most 8 axes (the file format's bound).
    int lower[8];
    double frac[8];
    size_t stride[8];
    size_t s = n_channels;
    for (size_t a = 0; a < n_axes && a < 8; ++a) {
        const slut_axis &map = table.axes[a].map;
        slut_cell_from_unit(unit[a], map.count, &lower[a], &frac[a]);
        stride[a] = s;
        s *= static_cast<size_t>(map.count);
    }
    // Sum over the 2^n corners of the cell.
    double value = 0.0;
    const size_t corners = size_t{1} << n_axes;
    for (size_t corner = 0; corner < corners; ++corner) {
        double weight = 1.0;
        size_t index = channel;
        for (size_t a = 0; a < n_axes; ++a) {
            const bool upper = (corner >> a) & 1u;
            weight *= upper ? frac[a] : 1.0 - frac[a];
            index += (static_cast<size_t>(lower[a]) + (upper ? 1u : 0u)) * stride[a];
        }
        if (weight != 0.0) value += weight * table.values[index];
    }
    return value;
}

double sample(const Table &table, const double *params, size_t channel) {
    return decode(table.channels[channel].encoding, sample_encoded(table, params, channel));
}

double sample(const Table &table, const SamplerCache &cache, const double *params, size_t channel) {
    return decode(table.channels[channel].encoding, sample_encoded(table, cache, params, channel));
}

} // namespace scatterlut
