// The anisotropic airlight snippets' test queries (airlight_hg_gpu_queries.hpp): the tables each g
// is sampled on and the queries of every regime, entry point and branch, with their C++
// references (tests/shaders/test_shaders_airlight_hg.cpp compares the GPU's results with them).
#include "airlight_hg_gpu_queries.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <map>
#include <random>
#include <string>
#include <vector>

#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"
#include "scatterlut/table.hpp"

extern "C" {
#include "slut_airlight_hg.h"
#include "slut_axes.h"
}

namespace airlight_hg_gpu_test {

using namespace airlight_gpu_test;

// Every regime and entry point at these g; at g = 0.99 only G~_g just beyond u_max at the
// forward peak (kPeakOnlyG). There the peak (width (1 - g)/(1 + g) = 0.005 in tan v) makes
// G~_g steep in w near pi/2: the float pi/2 - w of the snippet's sin/cos, (SLUT_PIO2_HI - w) +
// SLUT_PIO2_LO, loses its 4.4e-8 of SLUT_PIO2_LO where the GPU compiler reassociates the two
// constants (Mesa does: the GPU results equal the double ones at that w to 7 digits), which moves
// G~_g by up to 1.2e-5 at g = 0.99 (below 5e-6 at g <= 0.95, inside the 1e-5). Those queries add
// exactly that shift to their tolerance (w_fold_shift); elsewhere the same rounding of the ends
// w2, w1 of a radiance at g = 0.99 measured 1.8e-5 (docs/SHADERS.md).
const std::vector<double> kPhaseGs = {-0.5, 0.85, 0.95};
std::vector<double> all_phase_gs() {
    std::vector<double> all = kPhaseGs;
    all.push_back(kPeakOnlyG);
    return all;
}

// ------------------------------------------------------------------------ the tables

// The table of each g as `scatterlut generate --u-max 64 --n-u 128 --n-w 64` lays it out
// (airlight_gpu_test::airlight_test_table: the generator's own axes, ASINH_COT_PEAK on w for
// g > 0). u_max = 64 lies below the large-u series' onset for g >= 0.85 (the planner would
// raise it): beyond it the samplers' large-u form falls back to the quadrature near the
// forward peak (slut_hg_gs_beyond_u_max), which the queries below probe.
const scatterlut::AirlightHgTable &table_for(double g) {
    static std::map<double, scatterlut::AirlightHgTable> tables;
    auto it = tables.find(g);
    if (it == tables.end()) it = tables.emplace(g, scatterlut::AirlightHgTable(airlight_test_table(g))).first;
    return it->second;
}

namespace {

// ---------------------------------------------------------------------- the queries

// One GPU query (airlight_gpu_test::Query, 16 floats). mode 0: Gs_g(u, w); 1: table radiance
// (sigma_s, sigma_a, I0, D, sin gamma, cos gamma, s); 2: exact radiance (the same inputs, no
// table); 3: the RGB entry point (sigma_s rgb, sigma_a rgb, I0, D, sin gamma, cos gamma, s,
// channel returned); 4: radiance from points (viewer, dir, light, s, sigma_s, sigma_a, I0);
// 5, 6: the thin-medium and distant-light closed forms with the phase (mode 1's inputs, no table).
enum Mode { kScaledTail = 0, kRadiance = 1, kExact = 2, kRgb = 3, kPoints = 4, kThin = 5, kDistant = 6 };

// A query of the seven radiance inputs d (sigma_s, sigma_a, I0, D, sin gamma, cos gamma, s) in
// one of the modes that take them (1, 2, 5, 6), with its optical distance sigma_t D.
Query inputs_query(Mode mode, const std::array<float, 7> &d) {
    Query q;
    q.gpu[0] = mode;
    std::copy(d.begin(), d.end(), q.gpu.begin() + 1);
    q.optical_distance = (static_cast<double>(d[0]) + d[1]) * d[3];
    return q;
}

// The largest change of the stored ln Gs_g across the cell that holds (u, w), the u and the w
// step added; 0 outside the table (the asymptotic forms serve there).
double cell_jump(const scatterlut::AirlightHgTable &table, double u, double w) {
    if (w < table.w_min() || u > table.u_max()) return 0.0;
    const scatterlut::Table &t = table.table();
    const int nu = t.axes[0].map.count, nw = t.axes[1].map.count;
    const double pu = slut_node_position_from_unit(slut_unit_from_param(&t.axes[0].map, u), nu);
    const double pw = slut_node_position_from_unit(slut_unit_from_param(&t.axes[1].map, w), nw);
    const int i = slut_cell_index(pu, nu), j = slut_cell_index(pw, nw);
    const auto v = [&](int a, int b) { return static_cast<double>(t.values[static_cast<size_t>(b) * nu + a]); };
    const double du = std::max(std::fabs(v(i + 1, j) - v(i, j)), std::fabs(v(i + 1, j + 1) - v(i, j + 1)));
    const double dw = std::max(std::fabs(v(i, j + 1) - v(i, j)), std::fabs(v(i + 1, j + 1) - v(i + 1, j)));
    return du + dw;
}

// The cell jumps of the samples the table radiance takes (both ends), from the double set-up.
double radiance_cell_jump(const scatterlut::AirlightHgTable &table, const scatterlut::AirlightQuery &cq) {
    const double sigma_t = cq.sigma_s_per_m + cq.sigma_a_per_m;
    const double s_over_D = cq.length_m > 1e300 ? HUGE_VAL : cq.length_m / cq.distance_m;
    const slut_hg_airlight_ends e = slut_hg_airlight_setup_ends(sigma_t * cq.distance_m, std::sin(cq.gamma_rad),
                                                                std::cos(cq.gamma_rad), s_over_D);
    if (e.samples == 0) return 0.0;
    return std::max(cell_jump(table, e.u, e.w2), e.w1 > 0.0 ? cell_jump(table, e.u, e.w1) : 0.0);
}

// |relative change of G~_g(u, w)| when pi/2 - w loses SLUT_PIO2_LO (the float pi/2 - w a GPU
// compiler that folds (SLUT_PIO2_HI - w) + SLUT_PIO2_LO into (SLUT_PIO2_HI + SLUT_PIO2_LO) - w
// computes); 0 below pi/4, where sin and cos take w itself.
double w_fold_shift(const scatterlut::AirlightHgTable &table, double u, double w) {
    if (w <= kPi / 4) return 0.0;
    const double pio2_float = static_cast<float>(kPi / 2); // SLUT_PIO2_HI, exactly
    const double folded = kPi / 2 - (pio2_float - w);     // the w whose pi/2 - w that is
    return std::fabs(table.scaled_tail(u, folded) / table.scaled_tail(u, w) - 1.0);
}

std::vector<Query> make_queries(double g) {
    const scatterlut::AirlightHgTable &table = table_for(g);
    std::mt19937_64 rng(20261202 + static_cast<uint64_t>(std::lround(100 * (g + 1))));
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<Query> out;

    // Gs_g(u, w) in every regime: the table, u = 0, u around and beyond u_max, w below w_min,
    // w near pi/2 (where the forward peak of g > 0 lies).
    const slut_axis &au = table.table().axes[0].map;
    const slut_axis &aw = table.table().axes[1].map;
    for (int i = 0; i < 800; ++i) {
        const auto [u, w] = random_scaled_tail_point(rng, au, aw);
        Query q;
        q.gpu[0] = kScaledTail;
        q.gpu[1] = static_cast<float>(u);
        q.gpu[2] = static_cast<float>(w);
        q.reference = table.scaled_tail(q.gpu[1], q.gpu[2]);
        q.cell_jump = cell_jump(table, q.gpu[1], q.gpu[2]);
        q.label = "Gs";
        out.push_back(q);
    }

    // Just beyond u_max at the forward peak (w within 0.03 of pi/2): Watson's series does not
    // converge there for g >= 0.85 (u rho ~ 2 at g = 0.95), the large-u form must fall back to
    // the quadrature (it gave -1.38 at g = 0.95, u = 64.03, w = 1.5649 before). At kPeakOnlyG
    // these are the only queries.
    const bool peak_only = g == kPeakOnlyG;
    if (peak_only) out.clear();
    for (int i = 0; i < 200; ++i) {
        Query q;
        q.gpu[0] = kScaledTail;
        q.gpu[1] = static_cast<float>(kUMax * (1.0 + (i % 4 == 0 ? 1e-3 * unit(rng) : 0.5 * unit(rng))));
        q.gpu[2] = static_cast<float>(kPi / 2 - (i % 10 == 0 ? 0.0 : log_uniform(rng, 1e-6, 0.03)));
        q.reference = table.scaled_tail(q.gpu[1], q.gpu[2]);
        if (peak_only) q.own_tolerance = w_fold_shift(table, q.gpu[1], q.gpu[2]);
        q.label = "Gs";
        out.push_back(q);
    }
    // The closed forms with the phase (no table: every g, the peak-only one included) against
    // airlight_hg_radiance_thin / _distant on the same float inputs: the radiance's random
    // geometries (gamma -> 0 and -> pi, infinite rays) and the degenerate inputs.
    // Their own random stream, so that the other queries stay what they were.
    {
        std::mt19937_64 closed_rng(7771 + static_cast<uint64_t>(std::lround(100 * (g + 1))));
        std::vector<std::array<float, 7>> inputs = degenerate_radiance_inputs();
        for (int i = 0; i < 600; ++i) {
            Query geometry; // random_geometry's D, sin gamma, cos gamma, s in gpu[4..7]
            double sigma_t = 0, I0 = 0;
            random_geometry(closed_rng, &geometry, &sigma_t, &I0);
            const float sigma_s = static_cast<float>(sigma_t * (0.05 + 0.95 * unit(closed_rng)));
            inputs.push_back({sigma_s, static_cast<float>(sigma_t - sigma_s), static_cast<float>(I0), geometry.gpu[4],
                              geometry.gpu[5], geometry.gpu[6], geometry.gpu[7]});
        }
        for (const auto &d : inputs)
            for (Mode mode : {kThin, kDistant}) {
                Query q = inputs_query(mode, d);
                const scatterlut::AirlightQuery cq = cpp_query(d.data());
                q.reference = mode == kThin ? scatterlut::airlight_hg_radiance_thin(cq, g)
                                            : scatterlut::airlight_hg_radiance_distant(cq, g);
                if (mode == kThin) q.optical_distance = 0.0; // no e^{-sigma_t D} in the thin form
                q.label = mode == kThin ? "thin" : "distant";
                out.push_back(q);
            }
    }
    if (peak_only) return out;

    // Radiance from the table and exactly, on the same geometries.
    for (int i = 0; i < 1500; ++i) {
        Query q;
        double sigma_t = 0, I0 = 0;
        random_geometry(rng, &q, &sigma_t, &I0);
        const double albedo = 0.05 + 0.95 * unit(rng);
        q.gpu[1] = static_cast<float>(albedo * sigma_t);
        q.gpu[2] = static_cast<float>((1.0 - albedo) * sigma_t);
        q.gpu[3] = static_cast<float>(I0);
        const scatterlut::AirlightQuery cq = cpp_query(&q.gpu[1]);
        q.optical_distance = (static_cast<double>(q.gpu[1]) + q.gpu[2]) * q.gpu[4];
        q.gpu[0] = kRadiance;
        q.reference = table.radiance(cq);
        q.cell_jump = radiance_cell_jump(table, cq);
        q.label = "radiance";
        out.push_back(q);
        if (i % 3 == 0) { // the exact path costs tens of panels: a third of the geometries
            q.gpu[0] = kExact;
            q.reference = scatterlut::airlight_radiance_exact(cq, g);
            q.cell_jump = 0.0; // no table
            q.label = "exact";
            out.push_back(q);
        }
    }

    // Degenerate inputs (airlight_gpu_test::degenerate_radiance_inputs), and more rays through
    // the light.
    const float inf = std::numeric_limits<float>::infinity();
    std::vector<std::array<float, 7>> limits = degenerate_radiance_inputs();
    for (int i = 0; i < 20; ++i) { // rays through the light (gamma = 0, s >= D or infinite): +inf
        const float D = static_cast<float>(log_uniform(rng, 0.01, 100.0));
        limits.push_back({0.05f, 0.01f, 10.0f, D, 0.0f, 1.0f, i % 2 == 0 ? inf : D * static_cast<float>(1.0 + unit(rng))});
    }
    for (const auto &d : limits)
        for (Mode mode : {kRadiance, kExact}) {
            Query q = inputs_query(mode, d);
            const scatterlut::AirlightQuery cq = cpp_query(d.data());
            q.reference = mode == kRadiance ? table.radiance(cq) : scatterlut::airlight_radiance_exact(cq, g);
            q.label = mode == kRadiance ? "radiance" : "exact";
            out.push_back(q);
        }

    // The RGB entry point: per-channel coefficients (one channel clear now and then, sigma_t = 0,
    // while another is dense), one GPU item per channel.
    for (int i = 0; i < 300; ++i) {
        Query q;
        double sigma_t = 0, I0 = 0;
        random_geometry(rng, &q, &sigma_t, &I0);
        scatterlut::Rgb ss{}, sa{};
        for (int c = 0; c < 3; ++c) {
            const double factor = log_uniform(rng, 0.2, 5.0), albedo = 0.05 + 0.95 * unit(rng);
            ss[c] = static_cast<float>(albedo * sigma_t * factor);
            sa[c] = static_cast<float>((1.0 - albedo) * sigma_t * factor);
        }
        if (unit(rng) < 0.15) ss[i % 3] = sa[i % 3] = 0.0;
        const float D = q.gpu[4], sg = q.gpu[5], cg = q.gpu[6], s = q.gpu[7];
        const float geometry[7] = {0.0f, 0.0f, static_cast<float>(I0), D, sg, cg, s};
        const scatterlut::AirlightQuery cq = cpp_query(geometry);
        const scatterlut::Rgb want = table.radiance_rgb(cq, ss, sa);
        const double jump = radiance_cell_jump(table, cq); // u differs per channel: the largest
        double jump_rgb = jump;
        for (int c = 0; c < 3; ++c) {
            scatterlut::AirlightQuery cc = cq;
            cc.sigma_s_per_m = ss[c];
            cc.sigma_a_per_m = sa[c];
            jump_rgb = std::max(jump_rgb, radiance_cell_jump(table, cc));
        }
        for (int c = 0; c < 3; ++c) {
            Query qc;
            qc.gpu[0] = kRgb;
            for (int k = 0; k < 3; ++k) {
                qc.gpu[1 + k] = static_cast<float>(ss[k]);
                qc.gpu[4 + k] = static_cast<float>(sa[k]);
            }
            qc.gpu[7] = static_cast<float>(I0);
            qc.gpu[8] = D;
            qc.gpu[9] = sg;
            qc.gpu[10] = cg;
            qc.gpu[11] = s;
            qc.gpu[12] = static_cast<float>(c);
            qc.reference = want[c];
            qc.optical_distance = (ss[c] + sa[c]) * D;
            qc.cell_jump = jump_rgb;
            qc.label = "rgb";
            out.push_back(qc);
        }
    }

    // Radiance from points (gamma in [0.1, pi - 0.1]: a float cross product of nearly parallel
    // vectors loses sin gamma's relative precision, the caller's input, not the snippet's error).
    for (int i = 0; i < 300; ++i) {
        const double D = log_uniform(rng, 0.01, 100.0), tau = log_uniform(rng, 1e-4, 13.8);
        const double sigma_t = tau / D, albedo = 0.05 + 0.95 * unit(rng);
        const double gamma = 0.1 + (kPi - 0.2) * unit(rng);
        const double s = unit(rng) < 0.15 ? std::numeric_limits<double>::infinity() : D * log_uniform(rng, 1e-5, 100.0);
        Query q;
        q.gpu[0] = kPoints;
        random_points(rng, D, gamma, false, &q);
        q.gpu[10] = static_cast<float>(s);
        q.gpu[11] = static_cast<float>(albedo * sigma_t);
        q.gpu[12] = static_cast<float>((1.0 - albedo) * sigma_t);
        q.gpu[13] = static_cast<float>(log_uniform(rng, 1.0, 1e4));
        const double v[3] = {q.gpu[1], q.gpu[2], q.gpu[3]}, d[3] = {q.gpu[4], q.gpu[5], q.gpu[6]},
                     l[3] = {q.gpu[7], q.gpu[8], q.gpu[9]};
        const scatterlut::AirlightQuery cq =
            scatterlut::airlight_query_from_points(v, d, l, q.gpu[10], q.gpu[11], q.gpu[12], q.gpu[13]);
        q.reference = table.radiance(cq);
        q.cell_jump = radiance_cell_jump(table, cq);
        q.optical_distance = (static_cast<double>(q.gpu[11]) + q.gpu[12]) * cq.distance_m;
        q.label = "points";
        out.push_back(q);
    }
    return out;
}

} // namespace

const std::vector<Query> &queries(double g) {
    static std::map<double, std::vector<Query>> all;
    auto it = all.find(g);
    if (it == all.end()) it = all.emplace(g, make_queries(g)).first;
    return it->second;
}

} // namespace airlight_hg_gpu_test
