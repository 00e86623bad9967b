// The spot shader test's tables and cases (tests/shaders/test_shaders_spot.cpp): the three tables
// the spot entry points run on, and the queries with their references in double (the C++ rule of
// the same algorithm with each table, the exact spot airlight, the conditioning, the rule's stated
// tolerance).
#pragma once

#include <array>
#include <string>
#include <vector>

#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/airlight_rational.hpp"
#include "scatterlut/spot.hpp"

namespace spot_gpu_cases {

constexpr int kRationalCount = 96; // the airlight_rational table's side
constexpr double kPhaseG = 0.85;   // the airlight_Fg table's g

const scatterlut::AirlightRationalTable &rational_table();
const scatterlut::AirlightTable &f_table();
const scatterlut::AirlightHgTable &hg_table();

// The three cases: the airlight snippet on airlight_rational (fast, accurate), on airlight_F (no
// tier), and the anisotropic snippet on airlight_Fg of g = 0.85 (every tier: the table is the same).
enum Kind { kRational = 0, kF = 1, kHg = 2 };
const char *kind_name(int k);
const scatterlut::Table &table_of(int k);
double phase_of(int k);

// 20 floats: mode (1 spot, 2 the point light), viewer, view direction, light, axis, θ_o, θ_i,
// length, σ_s, σ_a, I0, 0.
constexpr int kFloats = 20;
struct SpotCase {
    std::array<float, kFloats> gpu{};
    scatterlut::SpotQuery q; // the same in double
    double reference[3]{};   // the rule with each kind's table
    double exact[3]{};       // spot_airlight_radiance_exact (kHg: g = 0.85)
    double conditioning[3]{};
    double rule_tol[3]{};    // the rule's stated error (docs/SPOT.md)
    bool rule_whole[3]{};    // ... relative to the whole ray's point light
    double optical = 0;      // σ_t D
    bool wide = false;       // θ_o > π/2: errors against the C++ rule relative to the whole ray's point light
    double whole[3]{};       // that radiance (exact)
    std::string label;
};

const std::vector<SpotCase> &cases();

} // namespace spot_gpu_cases
