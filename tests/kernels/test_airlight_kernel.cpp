// The OpenCL kernel against an independent CPU reference (Boost.Math quadrature in
// tests/airlight_reference.hpp), never against itself: every node of a table that
// spans the hard corners (u = 0, u ≪ 1 with w → w_min, large u at v = 0).
#include <cmath>
#include <cstdio>
#include <vector>

#include <gtest/gtest.h>

#include "airlight_reference.hpp"
#include "generate_airlight.hpp"
#include "opencl_device.hpp"
#include "reference_data.hpp"

extern "C" {
#include "slut_airlight.h"
}

// Every node to ≤ 1e-9 relative (the airlight kernel's contract); we expect ~1e-13.
TEST(AirlightKernel, EveryNodeMatchesBoostReference) {
    scatterlut::Device device("");
    scatterlut::AirlightPlan plan;
    plan.n_u = 97;
    plan.n_w = 61;
    plan.u_max = 500.0;
    plan.w_min = 1e-6;
    plan.storage = scatterlut::Storage::F64;
    scatterlut::Provenance provenance;
    const scatterlut::Table t = scatterlut::generate_airlight_table(device, plan, provenance);
    const slut_axis &au = t.axes[0].map, &aw = t.axes[1].map;
    double worst = 0;
    for (int j = 0; j < aw.count; ++j)
        for (int i = 0; i < au.count; ++i) {
            const double u = slut_axis_node(&au, i), w = slut_axis_node(&aw, j);
            const double got = std::exp(t.values[static_cast<size_t>(j) * au.count + i]);
            const double err = slut_test::rel_err(got, slut_ref::ref_scaled_tail(u, w));
            ASSERT_LE(err, 1e-9) << "node (" << i << ", " << j << ") u=" << u << " w=" << w;
            worst = std::max(worst, err);
        }
    RecordProperty("worst_rel_err", std::to_string(worst));
    std::printf("kernel vs Boost, %d nodes: max rel err %.2e\n", au.count * aw.count, worst);
    // The table records what generation measured, and it is honest.
    EXPECT_GE(t.accuracy.integration_max_rel, 0.0);
    EXPECT_LE(t.accuracy.integration_max_rel, 1e-12);
    EXPECT_GT(t.accuracy.sampling_max_rel, 0.0);
}

// A device selector that matches nothing is a clear error, not a crash.
TEST(AirlightKernel, UnknownDeviceIsAClearError) {
    try {
        scatterlut::Device device("no-such-device-xyz");
        FAIL() << "expected DeviceError";
    } catch (const scatterlut::DeviceError &e) {
        EXPECT_NE(std::string(e.what()).find("no OpenCL device matches"), std::string::npos) << e.what();
    }
}

// The anisotropic tables (Henyey–Greenstein g, the same sweep with k_g in the weights and,
// where lane 0's u reaches slut_hg_sweep_series_u_min, k_g's large-u series): every node of a
// corner table (u up to 500, w down to 1e-6, so that the series replaces the rule at small w
// and large u) against the independent long-double Gauss–Kronrod reference
// (reference_scaled_tail_hg). The table's declared integration error holds as well.
TEST(AirlightKernel, AnisotropicEveryNodeMatchesTheIndependentReference) {
    scatterlut::Device device("");
    for (double g : {0.85, 0.99, -0.5, -0.99}) {
        scatterlut::AirlightPlan plan;
        plan.phase_g = g;
        plan.n_u = 97;
        plan.n_w = 61;
        plan.u_max = 500.0;
        plan.w_min = 1e-6;
        plan.storage = scatterlut::Storage::F64;
        const scatterlut::Table t = scatterlut::generate_airlight_table(device, plan, scatterlut::Provenance{});
        std::vector<scatterlut::NodeIndex> every;
        for (size_t j = 0; j < static_cast<size_t>(plan.n_w); ++j)
            for (size_t i = 0; i < static_cast<size_t>(plan.n_u); ++i) {
                scatterlut::NodeIndex p{};
                p[0] = i;
                p[1] = j;
                every.push_back(p);
            }
        const double worst =
            scatterlut::measure_airlight_integration(t, every, scatterlut::IntegrationReference::IndependentGaussKronrod);
        std::printf("g %5.2f: kernel vs the independent reference, %zu nodes: max rel err %.2e (declared %.2e)\n", g,
                    every.size(), worst, t.accuracy.integration_max_rel);
        EXPECT_LE(worst, 1e-12) << "g " << g;
        EXPECT_LE(t.accuracy.integration_max_rel, 1e-12) << "g " << g;
    }
}
