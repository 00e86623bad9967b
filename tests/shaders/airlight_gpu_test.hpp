// What the airlight shader tests share (test_shaders.cpp: the isotropic snippet,
// test_shaders_airlight_hg.cpp: the Henyey-Greenstein one): the test table as the generator
// lays it out, the 16-float query record and its random geometries, the compute-shader
// wrapper around a snippet and the GPU run.
// The EGL/GL and tool plumbing is gpu_harness.hpp's.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "generate_airlight.hpp" // make_airlight_table_layout: the generator's own axes
#include "scatterlut/airlight.hpp"
#include "scatterlut/table.hpp"

extern "C" {
#include "slut_airlight_hg.h"
#include "slut_axes.h"
}

#include "gpu_harness.hpp"

namespace airlight_gpu_test {

using namespace gpu_harness;

constexpr double kPi = 3.14159265358979323846;

// ------------------------------------------------------------------------ the table

constexpr int kCountU = 128, kCountW = 64;
constexpr double kUMax = 64.0, kUScale = 1e-7, kWMin = 1e-3;

// The airlight table of asymmetry g (0: the isotropic kind airlight_F) as `scatterlut generate
// --u-max 64 --n-u 128 --n-w 64` lays it out (the generator's own make_airlight_table_layout:
// u LOG1P scale 1e-7 on [0, 64], w on [1e-3, pi/2] with slut_hg_airlight_w_warp(g) and
// slut_hg_airlight_w_peak_scale(g): ASINH_COT, or ASINH_COT_PEAK for g > 0), its nodes
// integrated here with the shared quadrature and rounded to f32 as a file round trip would.
inline scatterlut::Table airlight_test_table(double phase_g) {
    scatterlut::AirlightPlan plan;
    plan.phase_g = phase_g;
    plan.u_max = kUMax;
    plan.u_scale = kUScale;
    plan.w_min = kWMin;
    plan.n_u = kCountU;
    plan.n_w = kCountW;
    scatterlut::Table t = scatterlut::make_airlight_table_layout(plan);
    t.values.resize(static_cast<size_t>(kCountU) * kCountW);
    for (int j = 0; j < kCountW; ++j) {
        const double wj = slut_axis_node(&t.axes[1].map, j);
        for (int i = 0; i < kCountU; ++i) {
            const double ui = slut_axis_node(&t.axes[0].map, i);
            const double gs = phase_g == 0.0 ? slut_gs_quadrature(ui, wj, 1.0) : slut_hg_gs_quadrature(ui, wj, phase_g, 1.0);
            t.values[static_cast<size_t>(j) * kCountU + i] = static_cast<float>(std::log(gs));
        }
    }
    t.check_consistent();
    return t;
}

// ---------------------------------------------------------------------- the queries

constexpr int kQueryFloats = 16;

// One GPU query: 16 floats (gpu[0] the mode, the test's own), the double reference for it, and
// what its tolerance depends on.
struct Query {
    std::array<float, kQueryFloats> gpu{}; // what the shader gets
    double reference = 0;                  // the C++ code on the same (rounded) inputs
    double optical_distance = 0;           // sigma_t D (the float exp's error grows with it)
    double cell_jump = 0;                  // |d ln Gs| across the table cells sampled
    double own_tolerance = 0;              // what this query adds to its category's tolerance
    std::string label;                     // the category, for the statistics
};

inline double log_uniform(std::mt19937_64 &rng, double lo, double hi) {
    std::uniform_real_distribution<double> d(std::log(lo), std::log(hi));
    return std::exp(d(rng));
}

// "mode m [the first n - 1 arguments]" for messages.
inline std::string describe(const std::array<float, kQueryFloats> &q, int n = kQueryFloats) {
    std::ostringstream s;
    s.precision(9);
    s << "mode " << q[0] << " [";
    for (int k = 1; k < n; ++k) s << (k > 1 ? ", " : "") << q[k];
    s << "]";
    return s.str();
}

// (u, w) of a G~ query in every regime: the table (uniform in the warped coordinates of the
// axes au, aw), u = 0, u around and beyond u_max (the large-u form), tiny u, w below w_min (the
// small-w form), w near pi/2 (the forward peak of g > 0), w around w_min.
inline std::pair<double, double> random_scaled_tail_point(std::mt19937_64 &rng, const slut_axis &au,
                                                          const slut_axis &aw) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double r1 = unit(rng), r2 = unit(rng);
    double u = slut_param_from_unit(&au, unit(rng));
    double w = slut_param_from_unit(&aw, unit(rng));
    if (r1 < 0.08) u = 0.0;
    else if (r1 < 0.2) u = log_uniform(rng, au.max, 1e4);
    else if (r1 < 0.25) u = au.max * (1.0 + 2e-3 * (unit(rng) - 0.5));
    else if (r1 < 0.3) u = log_uniform(rng, 1e-12, 1e-6);
    if (r2 < 0.12) w = log_uniform(rng, 1e-7, aw.min);
    else if (r2 < 0.17) w = kPi / 2 - log_uniform(rng, 1e-7, 1e-2);
    else if (r2 < 0.2) w = aw.min * (1.0 + 2e-3 * (unit(rng) - 0.5));
    return {u, w};
}

// A random geometry of the acceptance domain of docs/AIRLIGHT.md and beyond it: sigma_t D in
// [1e-4, 13.8] (80 %) and up to 85 (where u passes u_max = 64 for 8 %, gamma then in
// [1.2, pi - 1.2]; e^{-87} is float's smallest normal), D in [0.01, 100] m, s/D in [1e-5, 100]
// or infinite (15 %), gamma uniform, near 0, near pi, exactly 0 and pi. gpu[4..7] = D,
// sin gamma, cos gamma, s; sigma_t (1/m) and I0 (W/sr; bright where e^{-sigma_t D} is small,
// so that the result stays in float's range) through the pointers.
inline void random_geometry(std::mt19937_64 &rng, Query *q, double *sigma_t, double *I0) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    const double r_tau = unit(rng), r_gamma = unit(rng), r_s = unit(rng);
    const bool large_u = r_tau >= 0.92;
    const double tau = r_tau < 0.8 ? log_uniform(rng, 1e-4, 13.8)
                       : large_u   ? log_uniform(rng, 70.0, 85.0)
                                   : log_uniform(rng, 13.8, 85.0);
    const double D = log_uniform(rng, 0.01, 100.0);
    *sigma_t = tau / D;
    *I0 = log_uniform(rng, 1.0, 1e4) * (tau > 13.8 ? 1e12 : 1.0);
    double gamma = kPi * unit(rng);
    if (r_gamma < 0.2) gamma = log_uniform(rng, 1e-7, 0.1);
    else if (r_gamma < 0.4) gamma = kPi - log_uniform(rng, 1e-7, 0.1);
    else if (r_gamma < 0.43) gamma = 0.0;
    else if (r_gamma < 0.46) gamma = kPi;
    if (large_u) gamma = 1.2 + (kPi - 2.4) * unit(rng);
    const double s = r_s < 0.15 ? std::numeric_limits<double>::infinity() : D * log_uniform(rng, 1e-5, 100.0);
    q->gpu[4] = static_cast<float>(D);
    q->gpu[5] = gamma == kPi ? 0.0f : static_cast<float>(std::sin(gamma));
    q->gpu[6] = gamma == kPi ? -1.0f : static_cast<float>(std::cos(gamma));
    q->gpu[7] = static_cast<float>(s);
}

// A radiance query (mode 1: gpu[1..7] = σ_s, σ_a, I0, D, sin γ, cos γ, s) of random_geometry's
// with albedo σ_s/σ_t uniform in [0.05, 1].
inline Query random_radiance_query(std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    Query q;
    double sigma_t = 0, I0 = 0;
    random_geometry(rng, &q, &sigma_t, &I0);
    const double albedo = 0.05 + 0.95 * unit(rng);
    q.gpu[0] = 1;
    q.gpu[1] = static_cast<float>(albedo * sigma_t);
    q.gpu[2] = static_cast<float>((1.0 - albedo) * sigma_t);
    q.gpu[3] = static_cast<float>(I0);
    return q;
}

// The C++ query of the seven radiance inputs a[0..6] = sigma_s, sigma_a (1/m), I0 (W/sr), D (m),
// sin gamma, cos gamma, s (m; +inf: an infinite ray), as the GPU gets them (float-rounded).
inline scatterlut::AirlightQuery cpp_query(const float *a) {
    scatterlut::AirlightQuery cq;
    cq.sigma_s_per_m = a[0];
    cq.sigma_a_per_m = a[1];
    cq.intensity_W_per_sr = a[2];
    cq.distance_m = a[3];
    cq.gamma_rad = std::atan2(static_cast<double>(a[4]), static_cast<double>(a[5]));
    cq.length_m = a[6];
    return cq;
}

// Degenerate radiance inputs (sigma_s, sigma_a, I0, D, sin gamma, cos gamma, s): zero radiance
// (sigma_s = 0, I0 = 0, s = 0), the ray through the light (gamma = 0, s >= D: +inf), gamma = 0
// short of the light (finite), gamma = pi.
inline std::vector<std::array<float, 7>> degenerate_radiance_inputs() {
    const float inf = std::numeric_limits<float>::infinity();
    return {{0.0f, 0.1f, 1.0f, 2.0f, 0.5f, 0.8f, 3.0f}, {0.1f, 0.1f, 0.0f, 2.0f, 0.5f, 0.8f, 3.0f},
            {0.1f, 0.1f, 1.0f, 2.0f, 0.5f, 0.8f, 0.0f}, {0.1f, 0.1f, 1.0f, 2.0f, 0.0f, 1.0f, 2.0f},
            {0.1f, 0.1f, 1.0f, 2.0f, 0.0f, 1.0f, inf},  {0.1f, 0.1f, 1.0f, 2.0f, 0.0f, 1.0f, 1.5f},
            {0.1f, 0.1f, 1.0f, 2.0f, 0.0f, -1.0f, inf}};
}

// Viewer, view direction and light of a radiance-from-points query (gpu[1..9]) with the light
// at distance D from the viewer and the view direction at angle gamma from it: the viewer
// within D of the origin (so that float positions keep D's precision). collinear (gamma 0 or
// pi exactly): positions on a 2^-10 grid, so that light - viewer is exact in float and in
// double, and the direction is +-(light - viewer).
inline void random_points(std::mt19937_64 &rng, double D, double gamma, bool collinear, Query *q) {
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::normal_distribution<double> normal;
    double viewer[3], l_dir[3], e1[3], n2 = 0;
    for (double &v : viewer) v = D * (2.0 * unit(rng) - 1.0);
    for (double &x : l_dir) x = normal(rng), n2 += x * x;
    for (double &x : l_dir) x /= std::sqrt(n2);
    // e1 perpendicular to l_dir, then the view direction at angle gamma from l_dir.
    const double any[3] = {std::fabs(l_dir[0]) < 0.9 ? 1.0 : 0.0, std::fabs(l_dir[0]) < 0.9 ? 0.0 : 1.0, 0.0};
    e1[0] = l_dir[1] * any[2] - l_dir[2] * any[1];
    e1[1] = l_dir[2] * any[0] - l_dir[0] * any[2];
    e1[2] = l_dir[0] * any[1] - l_dir[1] * any[0];
    const double ne1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    const double grid = 1024.0;
    for (int k = 0; k < 3; ++k) {
        const double v = viewer[k], l = viewer[k] + D * l_dir[k];
        const double dir = std::cos(gamma) * l_dir[k] + std::sin(gamma) * e1[k] / ne1;
        q->gpu[1 + k] = static_cast<float>(collinear ? std::round(v * grid) / grid : v);
        q->gpu[7 + k] = static_cast<float>(collinear ? std::round(l * grid) / grid : l);
        q->gpu[4 + k] = collinear ? (gamma == 0.0 ? 1.0f : -1.0f) * (q->gpu[7 + k] - q->gpu[1 + k])
                                  : static_cast<float>(dir);
    }
}

// ------------------------------------------------------------------ shader wrappers

// The compute shader around an airlight snippet (gpu_harness::glsl_compute_source with a 2-D table).
inline std::string glsl_compute_source(const std::string &snippet, const std::string &params, const std::string &body,
                                       const std::string &defines) {
    return gpu_harness::glsl_compute_source(snippet, params, body, defines, false);
}
inline std::string hlsl_compute_source(const std::string &snippet, const std::string &params, const std::string &body,
                                       const std::string &defines) {
    return gpu_harness::hlsl_compute_source(snippet, params, body, defines, false);
}

#if SLUT_HAVE_EGL
// Every query through a compute shader built by the functions above (or its spirv-cross
// translation) on `table` (one R32F texture, width = u count); params: the uniform block.
template <class Params>
std::vector<float> run_queries(const std::string &source, const scatterlut::Table &table,
                               const std::vector<Query> &qs, const Params &params, std::string *error) {
    const std::vector<float> texels(table.values.begin(), table.values.end());
    std::vector<float> packed;
    for (const Query &q : qs) packed.insert(packed.end(), q.gpu.begin(), q.gpu.end());
    return run_compute(source, texels, table.axes[0].map.count, table.axes[1].map.count, 0, packed, qs.size(),
                       &params, sizeof params, error);
}
#endif

} // namespace airlight_gpu_test
