#include "scatterlut/sampler.hpp"

#include <cmath>

#include "sampler_cell.hpp"

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

// Multilinear interpolation: sampler_cell.hpp.
namespace {

template <size_t N, typename Value>
double interpolate_cell(const Table &table, const Value *all_values, const double *unit, size_t channel) {
    double v[size_t{1} << N], frac[N];
    detail::gather_cell<N>(table, all_values, unit, channel, v, frac);
    return detail::lerp_cell<N>(v, frac);
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
