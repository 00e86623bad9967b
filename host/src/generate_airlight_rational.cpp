#include "generate_airlight_rational.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include <boost/math/special_functions/expint.hpp>

#include "generate_airlight.hpp" // airlight_measurement_nodes: the corners, then random nodes
#include "measure_util.hpp"
#include "reference_quadrature.hpp"
#include "table_build.hpp"
#include "text_format.hpp"
#include "scatterlut/io.hpp"

extern "C" {
#include "slut_airlight_rational.h"
}

namespace scatterlut {

Table make_airlight_rational_layout(const AirlightRationalPlan &plan) {
    Table t;
    t.kind = kKindAirlightRational;
    t.quantity_version = kAirlightRationalQuantityVersion;
    // The x_m map's text names its K (SLUT_AIRLIGHT_RATIONAL_M_SCALE) as the file's reader needs it.
    const std::string m_meaning = "(m/(m+K))^(1/4), K = " + fmt("%g", SLUT_AIRLIGHT_RATIONAL_M_SCALE) +
                                  ", m = u(1+t), u = sigma_t D sin gamma";
    t.axes = {make_axis("x_m", m_meaning.c_str(), 0.0, 1.0, 0.0, SLUT_WARP_LINEAR, plan.n_m),
              make_axis("x_t", "t/(1+t), t = tan v = cot w", 0.0, 1.0, 0.0, SLUT_WARP_LINEAR, plan.n_t)};
    Channel c;
    c.name = "Hn";
    c.meaning = "the airlight tail H(u,t) = int_0^inf exp(-u y)/(1+(t+y)^2) dy times N = t + 2/pi + u(1+t^2), in "
                "[0.80, 1.29]";
    c.encoding = Encoding::Linear;
    t.channels = {c};
    t.storage = plan.storage;
    return t;
}

std::vector<double> integrate_airlight_rational(Device &device, const Table &layout, double) {
    const slut_axis &am = layout.axes[0].map, &at = layout.axes[1].map;
    std::vector<double> m_nodes(static_cast<size_t>(am.count)), t_nodes(static_cast<size_t>(at.count));
    for (int i = 0; i < am.count; ++i) m_nodes[static_cast<size_t>(i)] = slut_axis_node(&am, i);
    for (int j = 0; j < at.count; ++j) t_nodes[static_cast<size_t>(j)] = slut_axis_node(&at, j);
    const char *file = "airlight_rational.cl";
    cl::Kernel kernel(device.program(file), "airlight_rational_hn");
    std::vector<double> values(layout.node_count());
    const cl::Buffer out = output_buffer(device, values);
    const cl::Buffer m_buffer = input_buffer(device, m_nodes), t_buffer = input_buffer(device, t_nodes);
    int arg = 0;
    kernel.setArg(arg++, out);
    kernel.setArg(arg++, m_buffer);
    kernel.setArg(arg++, am.count);
    kernel.setArg(arg++, t_buffer);
    kernel.setArg(arg++, at.count);
    // One work-item per node, in work-groups of one: a work-item is a whole quadrature.
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange,
                                        cl::NDRange(static_cast<size_t>(am.count), static_cast<size_t>(at.count)),
                                        cl::NDRange(1, 1));
    wait_for_output(device, out, values);
    device.kernels_ran(file);
    return values;
}

Table generate_airlight_rational_table(Device &device, const AirlightRationalPlan &plan,
                                       const Provenance &provenance, const std::function<void(double)> &progress) {
    Table t = make_airlight_rational_layout(plan);
    begin_generation(t, provenance, plan.integration_tolerance);
    t.values = integrate_airlight_rational(device, t, plan.integration_tolerance);
    if (progress) progress(1.0);
    t.accuracy.integration_max_rel = measure_airlight_rational_integration(
        AirlightRationalTable(t), airlight_measurement_nodes(t, 400, 1), IntegrationReference::FinerPanelRule);
    round_to_table_storage(t);
    const SamplingStats s = measure_airlight_rational_sampling(AirlightRationalTable(t), 20000, 2);
    record_sampling(t, s, "Hn(x_m, x_t) at uniform random unit coordinates over the whole table");
    return t;
}

namespace {

// m of the unit coordinate x_m ∈ [0, 1): the axis's map slut_airlight_rational_x_m (the
// definition, increasing) inverted by bisection, not by the node function's closed inverse.
double m_of_unit(double x_m) {
    if (!(x_m > 0.0)) return 0.0;
    double lo = 0.0, hi = 1.0;
    while (slut_airlight_rational_x_m(hi) < x_m && hi < SLUT_INFINITE_ABOVE) hi *= 2.0;
    for (int k = 0; k < 2200; ++k) { // to adjacent doubles (from ~1e-300 to 1e300: ≤ ~2100 halvings)
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;
        (slut_airlight_rational_x_m(mid) < x_m ? lo : hi) = mid;
    }
    return 0.5 * (lo + hi);
}

} // namespace

double reference_airlight_rational(double x_m, double x_t) {
    using real = long double;
    if (x_m >= 1.0) return 1.0; // u = ∞: H·N → 1
    const real m = m_of_unit(x_m);
    if (x_t >= 1.0) { // t = ∞ at fixed m: e^m E_2(m)·(1 + m), E_2(0) = 1
        if (m == 0) return 1.0;
        if (m <= 1000) return static_cast<double>((1 + m) * std::exp(m) * boost::math::expint(2, m));
        // Beyond, e^m leaves long double's range: the asymptotic series Σ_k (−1)^k (k + 1)!/m^{k+1}
        // (20 terms: the remainder ≤ 22!/m^22 ≤ 1e-45).
        real sum = 0, term = 1 / m;
        for (int k = 0; k < 20; ++k, term *= -(k + 1) / m) sum += term;
        return static_cast<double>((1 + m) * sum);
    }
    const double t = x_t / (1.0 - x_t);
    const double u = static_cast<double>(m / (1 + static_cast<real>(t)));
    const double w = std::atan2(1.0, t); // arccot t
    const real H = static_cast<real>(w) * reference_scaled_tail(u, w);
    const real two_over_pi = 2 / std::acos(real(-1));
    return static_cast<double>(H * (t + two_over_pi + static_cast<real>(u) * (1 + static_cast<real>(t) * t)));
}

double measure_airlight_rational_integration(const AirlightRationalTable &table, const std::vector<NodeIndex> &nodes,
                                             IntegrationReference reference) {
    const Table &t = table.table();
    const slut_axis &am = t.axes[0].map, &at = t.axes[1].map;
    std::vector<double> err(nodes.size());
    parallel_for(static_cast<int>(nodes.size()), [&](int k) {
        const NodeIndex &p = nodes[static_cast<size_t>(k)];
        const double x_m = slut_axis_node(&am, static_cast<int>(p[0])), x_t = slut_axis_node(&at, static_cast<int>(p[1]));
        const double stored = t.values[t.index(p.data())]; // Linear: the quantity itself
        const double exact = reference == IntegrationReference::FinerPanelRule
                                 ? slut_airlight_rational_node(x_m, x_t, 3.0)
                                 : reference_airlight_rational(x_m, x_t);
        err[static_cast<size_t>(k)] = std::fabs(stored - exact) / exact;
    });
    double worst = 0;
    for (double e : err) worst = std::isnan(e) ? HUGE_VAL : std::max(worst, e);
    return worst;
}

SamplingStats measure_airlight_rational_sampling(const AirlightRationalTable &table, int points, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::array<double, 2>> at(static_cast<size_t>(points));
    for (auto &p : at) p = {unit(rng), unit(rng)};
    std::vector<double> err(at.size());
    parallel_for(points, [&](int k) {
        const auto &p = at[static_cast<size_t>(k)];
        const double exact = slut_airlight_rational_node(p[0], p[1], 1.0);
        err[static_cast<size_t>(k)] = std::fabs(table.sample(p[0], p[1]) - exact) / exact;
    });
    SamplingStats s;
    for (size_t k = 0; k < err.size(); ++k) {
        if (std::isnan(err[k])) err[k] = HUGE_VAL;
        if (err[k] > s.max_rel || k == 0) {
            s.max_rel = err[k];
            s.worst_u = s.worst_at[0] = at[k][0];
            s.worst_w = s.worst_at[1] = at[k][1];
        }
    }
    s.p99_rel = percentile(err, 0.99);
    s.median_rel = percentile(err, 0.5);
    s.points = err.size();
    return s;
}

} // namespace scatterlut
