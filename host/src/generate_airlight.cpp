#include "generate_airlight.hpp"

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>
#include <vector>

#include "measure_util.hpp"
#include "table_build.hpp"
#include "scatterlut/io.hpp"

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {

Table make_airlight_table_layout(const AirlightPlan &plan) {
    Table t;
    t.kind = kKindAirlightF;
    t.quantity_version = kAirlightFQuantityVersion;
    t.axes = {make_axis("u", "optical distance sigma_t*D*sin(gamma) (dimensionless), first argument of F(u,v)", 0.0,
                        plan.u_max, plan.u_scale, SLUT_WARP_LOG1P, plan.n_u),
              make_axis("w", "pi/2 - v (rad), v the second argument of F(u,v)", plan.w_min, SLUT_PIO2_HI, 0.0,
                        SLUT_WARP_ASINH_COT, plan.n_w)};
    Channel c;
    c.name = "ln_Gs";
    c.meaning = "ln of the scaled tail Gs(u,w) = exp(u cot w) * int_{pi/2-w}^{pi/2} exp(-u tan x) dx / w, in (0,1]";
    c.encoding = Encoding::Log;
    t.channels = {c};
    t.storage = plan.storage;
    return t;
}

Table generate_airlight_table(Device &device, const AirlightPlan &plan, const Provenance &provenance,
                              const std::function<void(double)> &progress) {
    Table t = make_airlight_table_layout(plan);
    t.provenance = provenance;
    const slut_axis &au = t.axes[0].map;
    const slut_axis &aw = t.axes[1].map;
    const size_t n = static_cast<size_t>(au.count) * static_cast<size_t>(aw.count);

    cl::Program &program = device.program("airlight_F.cl");
    cl::Kernel kernel(program, "airlight_ln_gs");
    cl::Buffer out(device.context(), CL_MEM_WRITE_ONLY, n * sizeof(double));
    int arg = 0;
    kernel.setArg(arg++, out);
    set_axis_args(kernel, &arg, au);
    set_axis_args(kernel, &arg, aw);
    kernel.setArg(arg++, 1.0); // refine: the production rule
    // Rows in slices so that a terminal can show progress on large tables.
    const int rows_per_slice = std::max(1, aw.count / 16);
    for (int j0 = 0; j0 < aw.count; j0 += rows_per_slice) {
        const int rows = std::min(rows_per_slice, aw.count - j0);
        device.queue().enqueueNDRangeKernel(kernel, cl::NDRange(0, static_cast<size_t>(j0)),
                                            cl::NDRange(static_cast<size_t>(au.count), static_cast<size_t>(rows)),
                                            cl::NullRange);
        device.queue().finish();
        if (progress) progress(static_cast<double>(j0 + rows) / aw.count);
    }
    std::vector<double> values(n);
    device.queue().enqueueReadBuffer(out, CL_TRUE, 0, n * sizeof(double), values.data());
    t.values = std::move(values);

    // Accuracy: of the integration, of the storage type, and of sampling with the stored values.
    t.accuracy.integration_max_rel = measure_airlight_integration(t, 400, 1);
    t.accuracy.storage_max_rel = storage_rounding_max_rel(t, t.storage);
    for (double &v : t.values) v = round_to_storage(v, t.storage);
    const SamplingStats s = measure_airlight_sampling(AirlightTable(t), 20000, 2);
    t.accuracy.sampling_max_rel = s.max_rel;
    t.accuracy.sampling_p99_rel = s.p99_rel;
    t.accuracy.sampling_median_rel = s.median_rel;
    t.accuracy.sampling_points = s.points;
    t.accuracy.sampling_domain = "Gs(u,w) at uniform random unit coordinates over the whole table";
    return t;
}

double measure_airlight_integration(const Table &table, int nodes, uint64_t seed) {
    const slut_axis &au = table.axes[0].map;
    const slut_axis &aw = table.axes[1].map;
    std::mt19937_64 rng(seed);
    std::vector<std::pair<int, int>> picks = {{0, 0}, {au.count - 1, 0}, {0, aw.count - 1}, {au.count - 1, aw.count - 1}};
    std::uniform_int_distribution<int> iu(0, au.count - 1), iw(0, aw.count - 1);
    while (static_cast<int>(picks.size()) < nodes) picks.emplace_back(iu(rng), iw(rng));
    std::vector<double> err(picks.size());
    parallel_for(static_cast<int>(picks.size()), [&](int k) {
        const auto [i, j] = picks[static_cast<size_t>(k)];
        const double u = slut_axis_node(&au, i), w = slut_axis_node(&aw, j);
        const double stored = std::exp(table.values[(static_cast<size_t>(j) * au.count + i) * table.channels.size()]);
        const double reference = slut_gs_quadrature(u, w, 3.0);
        err[static_cast<size_t>(k)] = std::fabs(stored - reference) / reference;
    });
    return *std::max_element(err.begin(), err.end());
}

SamplingStats measure_airlight_sampling(const AirlightTable &table, int points, uint64_t seed) {
    const slut_axis &au = table.table().axes[0].map;
    const slut_axis &aw = table.table().axes[1].map;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::pair<double, double>> at(static_cast<size_t>(points));
    for (auto &p : at) p = {slut_param_from_unit(&au, unit(rng)), slut_param_from_unit(&aw, unit(rng))};
    std::vector<double> err(at.size());
    parallel_for(points, [&](int k) {
        const auto [u, w] = at[static_cast<size_t>(k)];
        const double exact = slut_gs_quadrature(u, w, 1.0);
        err[static_cast<size_t>(k)] = std::fabs(table.scaled_tail(u, w) - exact) / exact;
    });
    SamplingStats s;
    const auto worst = std::max_element(err.begin(), err.end());
    s.max_rel = *worst;
    s.worst_u = at[static_cast<size_t>(worst - err.begin())].first;
    s.worst_w = at[static_cast<size_t>(worst - err.begin())].second;
    s.p99_rel = percentile(err, 0.99);
    s.median_rel = percentile(err, 0.5);
    s.points = err.size();
    return s;
}

} // namespace scatterlut
