// scatterlut generator — pieces every table generator uses: an axis from its fields, an
// axis passed to a kernel as (min, max, scale, warp, count), and the kernels' buffers.
#pragma once

#include <cstdio>
#include <string>
#include <utility>
#include <vector>

#include <CL/opencl.hpp>

#include "measurement.hpp"
#include "opencl_device.hpp"
#include "scatterlut/io.hpp"
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

// Rounds the integrated values to the table's storage type, recording the largest relative
// error the rounding makes (accuracy.storage_max_rel).
inline void round_to_table_storage(Table &t) {
    t.accuracy.storage_max_rel = storage_rounding_max_rel(t, t.storage);
    for (double &v : t.values) v = round_to_storage(v, t.storage);
}

// Records a sampling-error measurement of the stored values; `domain` says where its points lie.
inline void record_sampling(Table &t, const SamplingStats &s, std::string domain) {
    t.accuracy.sampling_max_rel = s.max_rel;
    t.accuracy.sampling_p99_rel = s.p99_rel;
    t.accuracy.sampling_median_rel = s.median_rel;
    t.accuracy.sampling_points = s.points;
    t.accuracy.sampling_domain = std::move(domain);
}

// Sets the five kernel arguments of one axis starting at *arg, advancing it.
inline void set_axis_args(cl::Kernel &kernel, int *arg, const slut_axis &a) {
    kernel.setArg((*arg)++, a.min);
    kernel.setArg((*arg)++, a.max);
    kernel.setArg((*arg)++, a.scale);
    kernel.setArg((*arg)++, a.warp);
    kernel.setArg((*arg)++, a.count);
}

// A read-only device copy of v (a kernel's input).
template <class T> cl::Buffer input_buffer(Device &device, const std::vector<T> &v) {
    return cl::Buffer(device.context(), CL_MEM_READ_ONLY | CL_MEM_COPY_HOST_PTR, v.size() * sizeof(T),
                      const_cast<T *>(v.data()));
}

// A device buffer over `values` itself (CL_MEM_USE_HOST_PTR): the kernels write the table's
// values in place, with no copy; they are there once wait_for_output returns.
inline cl::Buffer output_buffer(Device &device, std::vector<double> &values) {
    return cl::Buffer(device.context(), CL_MEM_WRITE_ONLY | CL_MEM_USE_HOST_PTR, values.size() * sizeof(double),
                      values.data());
}

// Queues a map and an unmap of `out` (an output_buffer over `values`) behind the kernels
// and waits once for all: each blocking call would be a round trip to PoCL's worker threads.
inline void wait_for_output(Device &device, const cl::Buffer &out, const std::vector<double> &values) {
    void *mapped = device.queue().enqueueMapBuffer(out, CL_FALSE, CL_MAP_READ, 0, values.size() * sizeof(double));
    device.queue().enqueueUnmapMemObject(out, mapped);
    device.queue().finish();
}

} // namespace scatterlut
