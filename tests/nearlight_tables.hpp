// Near-light tables and queries the kernel and runtime tests share: one OpenCL device, small
// 3-D / 4-D tables that span the lane groups, the default 4-D table, and a physical query from
// a reference case. Each table is generated once per test executable.
#pragma once

#include "generate_nearlight.hpp"
#include "nearlight_reference.hpp"
#include "opencl_device.hpp"
#include "reference_data.hpp"
#include "scatterlut/nearlight.hpp"

namespace slut_test {

inline scatterlut::Device &device() {
    static scatterlut::Device d("");
    return d;
}

inline const scatterlut::Table &small_table(bool finite) {
    static const auto make = [](bool fin) {
        scatterlut::NearLightPlan plan;
        plan.finite_thickness = fin;
        plan.n_T = 9;
        plan.n_g = 11;
        plan.n_r = 20; // two lane groups, the second partial
        plan.n_S = 5;
        plan.storage = scatterlut::Storage::F64;
        return scatterlut::generate_nearlight_table(device(), plan, scatterlut::Provenance{});
    };
    static const scatterlut::Table e3 = make(false), e4 = make(true);
    return finite ? e4 : e3;
}

// The default finite-thickness table (generated once; ~10–40 s on 2 busy cores).
inline const scatterlut::Table &default_e4() {
    static const scatterlut::Table t =
        scatterlut::generate_nearlight_table(device(), scatterlut::default_near_light_plan(true), {});
    return t;
}

inline scatterlut::NearLightQuery query_of(const NearLightRef &c) {
    scatterlut::NearLightQuery q;
    q.sigma_s_per_m = c.sigma_s;
    q.sigma_a_per_m = c.sigma_a;
    q.intensity_W_per_sr = c.intensity;
    for (int k = 0; k < 3; ++k) {
        q.normal[k] = c.normal[k];
        q.eye_dir[k] = c.eye_dir[k];
        q.light_rel_m[k] = c.light_pos[k];
    }
    q.length_m = c.length;
    return q;
}

} // namespace slut_test
