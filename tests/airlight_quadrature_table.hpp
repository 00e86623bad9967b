// An airlight table (AirlightPlan's layout, phase g, n_u x n_w nodes) filled on the CPU by the
// shared quadrature of kernels/slut_airlight.h and slut_airlight_hg.h, stored as ln G̃ in
// float: the tables the spot tests sample without an OpenCL device (test_spot_table,
// test_spot_rule, test_spot_eval).
#pragma once

#include <cmath>
#include <cstddef>

#include "generate_airlight.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_airlight_hg.h"
#include "slut_axes.h"
}

namespace slut_test {

inline scatterlut::Table airlight_quadrature_table(double phase_g, int n_u, int n_w) {
    scatterlut::AirlightPlan plan;
    plan.phase_g = phase_g;
    plan.n_u = n_u;
    plan.n_w = n_w;
    scatterlut::Table t = scatterlut::make_airlight_table_layout(plan);
    const slut_axis &au = t.axes[0].map, &aw = t.axes[1].map;
    t.values.resize(static_cast<size_t>(au.count) * aw.count);
    for (int j = 0; j < aw.count; ++j)
        for (int i = 0; i < au.count; ++i) {
            const double u = slut_axis_node(&au, i), w = slut_axis_node(&aw, j);
            const double gs = phase_g == 0.0 ? slut_gs_quadrature(u, w, 1.0) : slut_hg_gs_quadrature(u, w, phase_g, 1.0);
            t.values[static_cast<size_t>(j) * au.count + i] = static_cast<float>(std::log(gs));
        }
    return t;
}

} // namespace slut_test
