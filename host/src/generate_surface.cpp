#include "generate_surface.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <stdexcept>
#include <vector>

#include "measure_util.hpp"
#include "reference_quadrature.hpp"
#include "table_build.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/surface.hpp"

extern "C" {
#include "slut_surface.h"
}

namespace scatterlut {
namespace {

// The runtime's G_n from a table.
double table_G(const SurfaceTable &table, double T, double theta) { return table.G(T, theta); }

// G_n at node (iT, iθ) of the table: the runtime's value at the node's parameters (bilinear
// weights 1 and 0 there, so the stored value decoded).
double node_G(const SurfaceTable &table, size_t iT, size_t itheta) {
    const Table &t = table.table();
    return table_G(table, slut_axis_node(&t.axes[0].map, static_cast<int>(iT)),
                   slut_axis_node(&t.axes[1].map, static_cast<int>(itheta)));
}

} // namespace

std::string surface_file_stem(int exponent) {
    return exponent == 1 ? "surface_G0" : "surface_G" + std::to_string(exponent);
}

int surface_table_exponent(const Table &table) { return table_surface_exponent(table); }

Table make_surface_table_layout(const SurfacePlan &plan) {
    Table t = surface_G_layout(plan.exponent, plan.T_max, plan.n_T, plan.n_theta);
    t.storage = plan.storage;
    return t;
}

std::vector<double> integrate_surface_G(Device &device, const Table &layout, double tolerance) {
    const slut_axis &aT = layout.axes[0].map, &atheta = layout.axes[1].map;
    const int exponent = surface_table_exponent(layout);
    std::vector<double> T_nodes(static_cast<size_t>(aT.count)), theta_nodes(static_cast<size_t>(atheta.count));
    for (int i = 0; i < aT.count; ++i) T_nodes[static_cast<size_t>(i)] = slut_axis_node(&aT, i);
    for (int j = 0; j < atheta.count; ++j) theta_nodes[static_cast<size_t>(j)] = slut_axis_node(&atheta, j);
    cl::Kernel kernel(device.program("surface_G.cl"), "surface_G");
    std::vector<double> G(layout.node_count());
    const cl::Buffer out = output_buffer(device, G);
    const cl::Buffer T_buffer = input_buffer(device, T_nodes), theta_buffer = input_buffer(device, theta_nodes);
    int arg = 0;
    kernel.setArg(arg++, out);
    kernel.setArg(arg++, T_buffer);
    kernel.setArg(arg++, aT.count);
    kernel.setArg(arg++, theta_buffer);
    kernel.setArg(arg++, atheta.count);
    kernel.setArg(arg++, exponent);
    kernel.setArg(arg++, slut_surface_subpanels_for_tolerance(tolerance));
    // One work-item per node, in work-groups of one: a work-item is a whole quadrature.
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange,
                                        cl::NDRange(static_cast<size_t>(aT.count), static_cast<size_t>(atheta.count)),
                                        cl::NDRange(1, 1));
    wait_for_output(device, out, G);
    device.kernels_ran("surface_G.cl");
    std::vector<double> stored(G.size());
    for (int j = 0; j < atheta.count; ++j)
        for (int i = 0; i < aT.count; ++i) {
            const size_t k = static_cast<size_t>(j) * static_cast<size_t>(aT.count) + static_cast<size_t>(i);
            stored[k] = surface_G_encode(exponent, T_nodes[static_cast<size_t>(i)], theta_nodes[static_cast<size_t>(j)], G[k]);
        }
    return stored;
}

Table generate_surface_table(Device &device, const SurfacePlan &plan, const Provenance &provenance) {
    Table t = make_surface_table_layout(plan);
    begin_generation(t, provenance, plan.integration_tolerance);
    t.values = integrate_surface_G(device, t, plan.integration_tolerance);
    t.accuracy.integration_max_rel = measure_surface_integration(
        SurfaceTable(t), random_table_nodes(t, 100, 1), IntegrationReference::FinerPanelRule);
    round_to_table_storage(t);
    const SamplingStats s = measure_surface_sampling(SurfaceTable(t), 4000, 2);
    record_sampling(t, s, std::string(plan.exponent == 1 ? "G0" : "G_n") +
                              "(T, theta) at uniform random unit coordinates of T and theta");
    return t;
}

double measure_surface_integration(const SurfaceTable &table, const std::vector<NodeIndex> &nodes,
                                   IntegrationReference reference) {
    const Table &t = table.table();
    const int n = surface_table_exponent(t);
    std::vector<double> err(nodes.size());
    parallel_for(static_cast<int>(nodes.size()), [&](int k) {
        const NodeIndex &p = nodes[static_cast<size_t>(k)];
        const double T = slut_axis_node(&t.axes[0].map, static_cast<int>(p[0]));
        const double theta = slut_axis_node(&t.axes[1].map, static_cast<int>(p[1]));
        const double ref = reference == IntegrationReference::FinerPanelRule ? surface_G_exact(n, T, theta)
                                                                             : reference_surface_G(n, T, theta);
        err[static_cast<size_t>(k)] = std::fabs(node_G(table, p[0], p[1]) - ref) / ref;
    });
    double worst = 0;
    for (double e : err) worst = std::isnan(e) ? HUGE_VAL : std::max(worst, e);
    return worst;
}

SamplingStats measure_surface_sampling(const SurfaceTable &table, int points, uint64_t seed) {
    const Table &t = table.table();
    const int n = surface_table_exponent(t);
    const int subpanels = slut_surface_subpanels_for_tolerance(1e-8);
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::array<double, 2>> at(static_cast<size_t>(points));
    for (auto &p : at)
        for (size_t a = 0; a < 2; ++a) p[a] = slut_param_from_unit(&t.axes[a].map, unit(rng));
    std::vector<double> err(at.size());
    parallel_for(static_cast<int>(at.size()), [&](int k) {
        const auto &p = at[static_cast<size_t>(k)];
        const double exact = slut_surface_G_fixed(n, p[0], p[1], subpanels);
        err[static_cast<size_t>(k)] = std::fabs(table_G(table, p[0], p[1]) - exact) / exact;
    });
    SamplingStats s;
    for (size_t k = 0; k < err.size(); ++k) {
        if (std::isnan(err[k])) err[k] = HUGE_VAL;
        if (err[k] > s.max_rel || k == 0) {
            s.max_rel = err[k];
            s.worst_u = at[k][0];
            s.worst_w = at[k][1];
            s.worst_at[0] = at[k][0];
            s.worst_at[1] = at[k][1];
        }
    }
    s.p99_rel = percentile(err, 0.99);
    s.median_rel = percentile(err, 0.5);
    s.points = err.size();
    return s;
}

} // namespace scatterlut
