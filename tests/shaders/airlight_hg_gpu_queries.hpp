// The anisotropic airlight snippets' test queries (tests/shaders/test_shaders_airlight_hg.cpp):
// the tables each g is sampled on and the queries of every regime, entry point and branch, with
// their C++ references and tolerances' inputs (airlight_hg_gpu_queries.cpp).
#pragma once

#include <vector>

#include "scatterlut/airlight_hg.hpp"

#include "airlight_gpu_test.hpp"

namespace airlight_hg_gpu_test {

// Every regime and entry point at these g; at g = 0.99 (kPeakOnlyG) only G~_g just beyond u_max
// at the forward peak (airlight_hg_gpu_queries.cpp says why).
extern const std::vector<double> kPhaseGs;
constexpr double kPeakOnlyG = 0.99;
std::vector<double> all_phase_gs();

// The table of each g as `scatterlut generate --u-max 64 --n-u 128 --n-w 64` lays it out (built once).
const scatterlut::AirlightHgTable &table_for(double g);

// The queries at g (made once): GPU inputs, the C++ reference, label and tolerance terms.
const std::vector<airlight_gpu_test::Query> &queries(double g);

} // namespace airlight_hg_gpu_test
