// The spot shader test's tables and cases (tests/shaders/test_shaders_spot.cpp): the three tables
// the spot entry points run on, and the queries with their references in double (the C++ rule of
// the same algorithm with each table, the exact spot airlight, the conditioning, the rule's stated
// tolerance).
#include "spot_gpu_cases.hpp"

#include <algorithm>
#include <cmath>
#include <random>

#include "generate_airlight_rational.hpp"
#include "spot_geometry.hpp"

extern "C" {
#include "slut_airlight_rational.h"
#include "slut_spot_rule.h"
}

#include "airlight_gpu_test.hpp"

namespace spot_gpu_cases {

using namespace airlight_gpu_test;
using scatterlut::SpotQuery;

// ------------------------------------------------------------------------ the tables
const scatterlut::AirlightRationalTable &rational_table() {
    static const scatterlut::AirlightRationalTable table = [] {
        scatterlut::AirlightRationalPlan plan;
        plan.n_m = plan.n_t = kRationalCount;
        scatterlut::Table t = scatterlut::make_airlight_rational_layout(plan);
        t.values.resize(static_cast<size_t>(kRationalCount) * kRationalCount);
        for (int j = 0; j < kRationalCount; ++j)
            for (int i = 0; i < kRationalCount; ++i)
                t.values[static_cast<size_t>(j) * kRationalCount + i] = static_cast<float>(slut_airlight_rational_node(
                    static_cast<double>(i) / (kRationalCount - 1), static_cast<double>(j) / (kRationalCount - 1), 1.0));
        return scatterlut::AirlightRationalTable(t);
    }();
    return table;
}
const scatterlut::AirlightTable &f_table() {
    static const scatterlut::AirlightTable table(airlight_test_table(0.0));
    return table;
}
const scatterlut::AirlightHgTable &hg_table() {
    static const scatterlut::AirlightHgTable table(airlight_test_table(kPhaseG));
    return table;
}

const char *kind_name(int k) { return k == kRational ? "airlight_rational" : k == kF ? "airlight_F" : "airlight_Fg"; }
const scatterlut::Table &table_of(int k) {
    return k == kRational ? rational_table().table() : k == kF ? f_table().table() : hg_table().table();
}
double phase_of(int k) { return k == kHg ? kPhaseG : 0.0; }
namespace {

scatterlut::detail::PointLightRadiance point_of(int k) {
    if (k == kRational) return [](const scatterlut::AirlightQuery &a) { return rational_table().radiance(a); };
    if (k == kF) return [](const scatterlut::AirlightQuery &a) { return f_table().radiance(a); };
    return [](const scatterlut::AirlightQuery &a) { return hg_table().radiance(a); };
}

// ----------------------------------------------------------------------- the queries
// The C++ query of a record: the float inputs as doubles, the angles at most π (float(π) rounds
// above it; the C++ query refuses that, the snippet takes it as π).
SpotQuery query_of(const std::array<float, kFloats> &g) {
    SpotQuery q;
    q.viewer_m = {g[1], g[2], g[3]};
    q.view_dir = {g[4], g[5], g[6]};
    q.light.position_m = {g[7], g[8], g[9]};
    q.light.direction = {g[10], g[11], g[12]};
    q.light.outer_angle_rad = std::fmin(static_cast<double>(g[13]), kPi);
    q.light.inner_angle_rad = std::fmin(static_cast<double>(g[14]), kPi);
    q.length_m = g[15];
    q.sigma_s_per_m = g[16];
    q.sigma_a_per_m = g[17];
    q.light.intensity_W_per_sr = g[18];
    return q;
}

double rule_of(int k, const SpotQuery &q) {
    if (q.light.inner_angle_rad > q.light.outer_angle_rad) return 0.0;
    return scatterlut::detail::spot_airlight_radiance_gpu_rule(point_of(k), q, phase_of(k));
}

void fill(SpotCase &c, const std::string &label) {
    c.label = label;
    c.q = query_of(c.gpu);
    c.wide = c.q.light.outer_angle_rad > 0.5 * kPi;
    std::mt19937_64 rng(static_cast<unsigned long long>(c.gpu[1] * 1e6f) ^ 0x5107ULL);
    std::uniform_int_distribution<int> sign(0, 1);
    for (int k = 0; k < 3; ++k) {
        c.reference[k] = rule_of(k, c.q);
        c.exact[k] = scatterlut::spot_airlight_radiance_exact(c.q, phase_of(k));
        const spot_geometry::RuleTolerance rt = spot_geometry::rule_tolerance(c.q, phase_of(k));
        c.rule_tol[k] = rt.tol;
        c.rule_whole[k] = rt.relative_to_whole;
        {
            const scatterlut::AirlightQuery p = scatterlut::airlight_query_from_points(
                c.q.viewer_m.data(), c.q.view_dir.data(), c.q.light.position_m.data(), c.q.length_m, c.q.sigma_s_per_m,
                c.q.sigma_a_per_m, c.q.light.intensity_W_per_sr);
            c.whole[k] = scatterlut::airlight_radiance_exact(p, phase_of(k));
        }
        // Conditioning: the reference with every input moved by about one float rounding (a relative
        // 2^-24 either way; both angles by the same factor, so that θ_i ≤ θ_o stays), 4 draws.
        double worst = 0;
        if (std::isfinite(c.reference[k]) && c.reference[k] > 0.0)
            for (int trial = 0; trial < 4; ++trial) {
                std::array<float, kFloats> moved = c.gpu;
                const float ulp = 5.9604645e-8f;
                for (int f = 1; f < 19; ++f) moved[f] *= 1.0f + (sign(rng) ? ulp : -ulp);
                moved[14] = moved[13] * (c.gpu[14] / std::fmax(c.gpu[13], 1e-30f));
                moved[14] = std::fmin(moved[14], moved[13]);
                const double r = rule_of(k, query_of(moved));
                worst = std::fmax(worst, std::isfinite(r) ? std::fabs(r - c.reference[k]) / c.reference[k] : 1.0);
            }
        c.conditioning[k] = worst;
    }
    const double D = std::hypot(c.q.light.position_m[0] - c.q.viewer_m[0],
                                std::hypot(c.q.light.position_m[1] - c.q.viewer_m[1], c.q.light.position_m[2] - c.q.viewer_m[2]));
    c.optical = (c.q.sigma_s_per_m + c.q.sigma_a_per_m) * D;
}

std::array<float, kFloats> record(const SpotQuery &q, int mode = 1) {
    std::array<float, kFloats> g{};
    g[0] = static_cast<float>(mode);
    for (int i = 0; i < 3; ++i) {
        g[1 + i] = static_cast<float>(q.viewer_m[i]);
        g[4 + i] = static_cast<float>(q.view_dir[i]);
        g[7 + i] = static_cast<float>(q.light.position_m[i]);
        g[10 + i] = static_cast<float>(q.light.direction[i]);
    }
    g[13] = static_cast<float>(q.light.outer_angle_rad);
    g[14] = std::fmin(static_cast<float>(q.light.inner_angle_rad), g[13]);
    g[15] = static_cast<float>(q.length_m);
    g[16] = static_cast<float>(q.sigma_s_per_m);
    g[17] = static_cast<float>(q.sigma_a_per_m);
    g[18] = static_cast<float>(q.light.intensity_W_per_sr);
    return g;
}

// Degenerate inputs on exact float geometry: the tests' base soft cone (the beam down the z
// axis from (5, 0, 4)) with its angles float's.
std::vector<std::pair<SpotQuery, std::string>> degenerate_queries() {
    SpotQuery b = spot_geometry::base_query();
    b.light.outer_angle_rad = 0.6f;
    b.light.inner_angle_rad = 0.3f;
    std::vector<std::pair<SpotQuery, std::string>> out;
    auto add = [&](SpotQuery q, const char *what) { out.push_back({q, what}); };
    add(b, "soft cone crossed");
    SpotQuery q = b;
    q.light.outer_angle_rad = q.light.inner_angle_rad = 0.0;
    add(q, "theta_o = 0");
    q = b;
    q.light.outer_angle_rad = q.light.inner_angle_rad = static_cast<float>(kPi);
    add(q, "theta_o = pi (point light)");
    q.length_m = HUGE_VAL;
    add(q, "theta_o = pi, infinite ray");
    q = b;
    q.viewer_m = {5, 0, 0};
    q.view_dir = {0, 0, 1};
    add(q, "up the axis through the apex (lit: +inf)");
    q.length_m = 3;
    add(q, "up the axis, short of the apex");
    q = b;
    q.viewer_m = {5, 0, 6};
    q.view_dir = {0, 0, -1};
    add(q, "down through the apex (dark, then lit: +inf)");
    q = b;
    q.viewer_m = {0, 0, 4};
    add(q, "sideways through the apex (unlit: 0)");
    q = b;
    q.light.outer_angle_rad = q.light.inner_angle_rad = 0.6f;
    add(q, "hard cone crossed");
    q.length_m = HUGE_VAL;
    add(q, "hard cone, infinite ray");
    for (double sign : {1.0, -1.0}) { // γ = 0 and π from inside and beside the beam
        for (const scatterlut::Vec3 &viewer : {scatterlut::Vec3{5, 0, -4}, scatterlut::Vec3{5, 4, 0}}) {
            q = b;
            q.viewer_m = viewer;
            q.view_dir = {sign * (5 - viewer[0]), sign * (0 - viewer[1]), sign * (4 - viewer[2])};
            q.length_m = 3;
            add(q, sign > 0 ? "gamma = 0, short of the light" : "gamma = pi");
        }
    }
    q = b;
    q.light.direction = {0, 0, 1};
    add(q, "beam pointing away");
    q = b;
    q.light.outer_angle_rad = 2.0f;
    q.light.inner_angle_rad = 1.2f;
    add(q, "theta_o > pi/2");
    return out;
}

std::vector<SpotCase> make_cases() {
    std::vector<SpotCase> out;
    std::mt19937_64 rng(20261205);
    const spot_geometry::Ranges typical = spot_geometry::typical_ranges();
    for (int k = 0; k < 500; ++k) {
        SpotCase c;
        c.gpu = record(spot_geometry::random_geometry(rng, k, typical).q);
        fill(c, std::string("typical ") + spot_geometry::kind_name(k % 4));
        out.push_back(c);
    }
    // The anisotropic snippet's RGB entry (slut_airlight_hg_spot_radiance_points_rgb): the first 60
    // typical rays again, the query's medium in channel mode − 3 and other media in the other two
    // (test_shaders_spot's body); every other body answers them with the spot alone.
    for (int k = 0; k < 60; ++k) {
        SpotCase c = out[static_cast<size_t>(k)]; // the same inputs, references and tolerances
        c.gpu[0] = static_cast<float>(3 + k % 3);
        c.label = "rgb channel " + std::to_string(k % 3) + ": " + c.label;
        out.push_back(c);
    }
    for (int k = 0; k < 200; ++k) { // test_spot's population: any cone, hard cones, wide ones
        SpotCase c;
        c.gpu = record(spot_geometry::random_geometry(rng, k).q);
        fill(c, std::string("any cone ") + spot_geometry::kind_name(k % 4));
        out.push_back(c);
    }
    for (const auto &d : degenerate_queries()) {
        SpotCase c;
        c.gpu = record(d.first);
        fill(c, "degenerate: " + d.second);
        out.push_back(c);
        if (d.second.rfind("theta_o = pi", 0) == 0) { // the snippet's own point light on the same ray
            SpotCase p;
            p.gpu = record(d.first, 2);
            fill(p, "point light: " + d.second);
            out.push_back(p);
        }
    }
    return out;
}

} // namespace

const std::vector<SpotCase> &cases() {
    static const std::vector<SpotCase> c = make_cases();
    return c;
}


} // namespace spot_gpu_cases
