// scatterlut generator — pieces every table generator uses: an axis from its fields, and
// an axis passed to a kernel as (min, max, scale, warp, count).
#pragma once

#include <cstdio>

#include <CL/opencl.hpp>

#include "scatterlut/table.hpp"

namespace scatterlut {

inline Axis make_axis(const char *name, const char *meaning, double min, double max, double scale, int warp,
                      int count) {
    Axis a;
    a.name = name;
    a.meaning = meaning;
    a.map.min = min;
    a.map.max = max;
    a.map.scale = scale;
    a.map.warp = warp;
    a.map.count = count;
    return a;
}

// Starts a table for generation: provenance, and the integration tolerance it is generated
// with (extra "integration.tolerance": requested; accuracy.integration_max_rel is what it
// reached).
inline void begin_generation(Table &t, const Provenance &provenance, double integration_tolerance) {
    t.provenance = provenance;
    char text[32];
    std::snprintf(text, sizeof text, "%.3g", integration_tolerance);
    t.extra["integration.tolerance"] = text;
}

// Sets the five kernel arguments of one axis starting at *arg, advancing it.
inline void set_axis_args(cl::Kernel &kernel, int *arg, const slut_axis &a) {
    kernel.setArg((*arg)++, a.min);
    kernel.setArg((*arg)++, a.max);
    kernel.setArg((*arg)++, a.scale);
    kernel.setArg((*arg)++, a.warp);
    kernel.setArg((*arg)++, a.count);
}

} // namespace scatterlut
