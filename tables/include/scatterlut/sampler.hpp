// scatterlut runtime — multilinear sampling of a table with the generator's own axis
// maps (kernels/slut_axes.h). Allocation-free and thread-safe (const; a SamplerCache is
// plain data computed once per table).
#pragma once

#include <cstddef>
#include <vector>

#include "scatterlut/table.hpp"

namespace scatterlut {

// Interpolates channel `channel` at the given parameters (one per axis, in axis order),
// linearly in each axis's unit coordinate, on the stored (encoded) values, then decodes
// (Log channels: exp). Parameters outside an axis clamp to its end nodes; callers that
// must not clamp (the radiance front-ends) check the domain first.
double sample(const Table &table, const double *params, size_t channel = 0);

// As sample(), but returns the interpolated encoded value (ln q for Log channels).
double sample_encoded(const Table &table, const double *params, size_t channel = 0);

// The per-axis constants of the unit maps (the warped domain ends), computed once per
// table so that a lookup evaluates one warp per axis instead of three.
struct SamplerCache {
    double g0[8] = {}, g1[8] = {};
};
SamplerCache make_sampler_cache(const Table &table);

// As above with the table's cache (bit-identical results).
double sample(const Table &table, const SamplerCache &cache, const double *params, size_t channel = 0);
double sample_encoded(const Table &table, const SamplerCache &cache, const double *params, size_t channel = 0);

// The interpolated encoded value at given unit coordinates (one per axis, each clamped to
// [0, 1]): for axes whose unit coordinate is not a one-parameter warp (the near-light slab
// axis, SLUT_WARP_NL_QODDS), computed by the caller (NearLightTable).
double sample_encoded_at_unit(const Table &table, const double *unit, size_t channel = 0);

// The same from a float copy of table.values (float_values_if_exact; empty: table.values):
// identical results, half the memory a lookup touches (the cells of a random query miss
// the caches: the default near-light tables are 3.9 MB and 63 MB as doubles).
double sample_encoded_at_unit(const Table &table, const std::vector<float> &values, const double *unit,
                              size_t channel = 0);
// table.values as floats if every value is one (f16 and f32 storage: always), else empty.
std::vector<float> float_values_if_exact(const Table &table);

// Decodes one stored value of a channel.
double decode(Encoding encoding, double stored);

} // namespace scatterlut
