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
// sum (as a product of weights would guarantee). N is the number of axes: fixed at compile
// time for the tables the library knows (2-D airlight, 3-D and 4-D near light), so that
// the corner loops unroll and the cell's offsets stay in registers.
namespace {

double lerp_exact_ends(double lower, double upper, double f) {
    return f == 0.0 ? lower : f == 1.0 ? upper : lower + f * (upper - lower);
}

template <size_t N, typename Value>
double interpolate_cell(const Table &table, const Value *all_values, const double *unit, size_t channel) {
    constexpr size_t corners = size_t{1} << N;
    double frac[N];
    size_t offset[corners];
    size_t base = channel, stride = table.channels.size();
    offset[0] = 0;
    for (size_t a = 0; a < N; ++a) {
        const int count = table.axes[a].map.count;
        int lower;
        slut_cell_from_unit(unit[a], count, &lower, &frac[a]);
        base += static_cast<size_t>(lower) * stride;
        const size_t half = size_t{1} << a;
        for (size_t c = 0; c < half; ++c) offset[half + c] = offset[c] + stride;
        stride *= static_cast<size_t>(count);
    }
    const Value *values = all_values + base;
    double v[corners];
    for (size_t c = 0; c < corners; ++c) v[c] = values[offset[c]];
    for (size_t a = N; a-- > 0;) {
        const size_t half = size_t{1} << a;
        for (size_t c = 0; c < half; ++c) v[c] = lerp_exact_ends(v[c], v[c + half], frac[a]);
    }
    return v[0];
}

template <typename Value>
double interpolate(const Table &table, const Value *values, const double *unit, size_t channel) {
    switch (table.axes.size()) {
    case 1: return interpolate_cell<1>(table, values, unit, channel);
    case 2: return interpolate_cell<2>(table, values, unit, channel);
    case 3: return interpolate_cell<3>(table, values, unit, channel);
    case 4: return interpolate_cell<4>(table, values, unit, channel);
    case 5: return interpolate_cell<5>(table, values, unit, channel);
    case 6: return interpolate_cell<6>(table, values, unit, channel);
    case 7: return interpolate_cell<7>(table, values, unit, channel);
    default: return interpolate_cell<8>(table, values, unit, channel); // the file format's bound
    }
}

} // namespace

double sample_encoded_at_unit(const Table &table, const double *unit, size_t channel) {
    return interpolate(table, table.values.data(), unit, channel);
}

double sample_encoded_at_unit(const Table &table, const std::vector<float> &values, const double *unit,
                              size_t channel) {
    return values.empty() ? interpolate(table, table.values.data(), unit, channel)
                          : interpolate(table, values.data(), unit, channel);
}

std::vector<float> float_values_if_exact(const Table &table) {
    std::vector<float> out(table.values.size());
    for (size_t k = 0; k < out.size(); ++k) {
        out[k] = static_cast<float>(table.values[k]);
        if (static_cast<double>(out[k]) != table.values[k]) return {};
    }
    return out;
}

double sample(const Table &table, const double *params, size_t channel) {
    return decode(table.channels[channel].encoding, sample_encoded(table, params, channel));
}

double sample(const Table &table, const SamplerCache &cache, const double *params, size_t channel) {
    return decode(table.channels[channel].encoding, sample_encoded(table, cache, params, channel));
}

} // namespace scatterlut
