// The snippets' spot-light entry points (slut_airlight_spot_radiance_points in
// scatterlut_airlight.{glsl,hlsl,essl}, slut_airlight_hg_spot_radiance_points in
// scatterlut_airlight_hg.*; kernels/slut_spot_rule.h; docs/SHADERS.md "Spot lights") in every
// tier, per query against
//   - the C++ reference of the same rule in double on the same float inputs and float table
//     (scatterlut::detail::spot_airlight_radiance_gpu_rule with the tier's own C++ radiance:
//     AirlightRationalTable for the fast and accurate airlight tiers, AirlightTable without a
//     tier, AirlightHgTable for the anisotropic snippet), at the float tolerance: the point
//     light's (1e-5 + 4e-7 σ_t D) plus 4× the query's own conditioning (how much the reference
//     moves when its float inputs move by one rounding: a ray that grazes a cone's edge is
//     ill-conditioned in any precision), plus in the fast tier the filter weights' term;
//   - the exact spot airlight (spot_airlight_radiance_exact) at the stated tolerance: that, plus
//     the table's (2G − 1 times the airlight_rational table's measured interpolation error; for
//     the airlight_F and airlight_Fg tables the largest effect of the table on the rule over the
//     queries, measured in double), plus the rule's own (docs/SPOT.md: by the band's optical
//     length; relative to the whole ray's point-light radiance for outer angles beyond π/2);
// on hard and soft cones, the viewer inside, beside and along the beam and with the apex behind
// it, finite and infinite rays (tests/spot_geometry.hpp), and degenerate inputs: θ_o = 0,
// θ_o = θ_i = π (the point light: also against the snippet's own point light), rays through
// the apex (lit: +∞; unlit: finite), γ = 0 and π. Never NaN, never negative. GLSL on llvmpipe,
// HLSL through spirv-cross, GLSL ES and HLSL compiled by glslang; WGSL cases for WebGPUSnippets.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "generate_airlight_rational.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/airlight_rational.hpp"
#include "scatterlut/spot.hpp"
#include "spot_gpu_cases.hpp"
#include "spot_geometry.hpp"

extern "C" {
#include "slut_airlight_rational.h"
#include "slut_spot_rule.h"
}

#include "airlight_gpu_test.hpp"
#include "wgsl_cases.hpp"

namespace {

using namespace airlight_gpu_test;
using namespace spot_gpu_cases;
using scatterlut::SpotQuery;

// --------------------------------------------------------------------------- shaders
const char *kParams = "    int m_count; int t_count; float u_max; float u_scale; int u_count; float w_min; int w_count;\n"
                      "    int n_queries; float phase_g; float w_scale; int w_warp;";
struct Params { // std140 of kParams
    int32_t m_count, t_count;
    float u_max, u_scale;
    int32_t u_count;
    float w_min;
    int32_t w_count, n_queries;
    float phase_g, w_scale;
    int32_t w_warp, pad;
};
Params test_params(int k) {
    const scatterlut::Table &t = table_of(k);
    Params p{kRationalCount, kRationalCount, static_cast<float>(kUMax), static_cast<float>(kUScale), kCountU,
             static_cast<float>(kWMin), kCountW, static_cast<int32_t>(cases().size()), static_cast<float>(phase_of(k)),
             1.0f, 0, 0};
    if (k != kRational) {
        p.w_scale = static_cast<float>(t.axes[1].map.scale);
        p.w_warp = t.axes[1].map.warp;
    }
    return p;
}

// The per-query bodies: mode 1 the spot, mode 2 the point light on the same ray, modes 3–5 the
// anisotropic snippet's RGB spot entry with the query's medium in channel mode − 3 (the GLSL and
// HLSL runs; the isotropic body answers them with the spot). The WebGPU cases take the spot alone (spot_only): on Chromium's SwiftShader a module
// whose test_eval calls both the spot and the point light returned wrong values for every query,
// spot and point alike (not chased down: each alone agrees; the point light is the WGSL tests'
// own subject elsewhere).
std::string body_airlight(bool spot_only) {
    std::string s = R"slsl(
float test_eval(int i) {
#if defined(SLUT_TIER_FAST) || defined(SLUT_TIER_ACCURATE)
    SlutAirlightTable t = slut_airlight_table(m_count, t_count);
#else
    SlutAirlightTable t = slut_airlight_table(u_max, u_scale, u_count, w_min, w_count);
#endif
    int b = 20 * i;
    SLUT_FLOAT3 viewer = SLUT_FLOAT3(q[b + 1], q[b + 2], q[b + 3]);
    SLUT_FLOAT3 dir = SLUT_FLOAT3(q[b + 4], q[b + 5], q[b + 6]);
    SLUT_FLOAT3 light = SLUT_FLOAT3(q[b + 7], q[b + 8], q[b + 9]);
)slsl";
    if (!spot_only)
        s += R"slsl(    if (int(q[b]) == 2)
        return slut_airlight_radiance_points(SLUT_TEX_ARG(slut_test_table), t, viewer, dir, light, q[b + 15], q[b + 16],
                                             q[b + 17], q[b + 18]);
)slsl";
    return s + R"slsl(    return slut_airlight_spot_radiance_points(SLUT_TEX_ARG(slut_test_table), t, viewer, dir, light,
                                              SLUT_FLOAT3(q[b + 10], q[b + 11], q[b + 12]), q[b + 13], q[b + 14],
                                              q[b + 15], q[b + 16], q[b + 17], q[b + 18]);
}
)slsl";
}

std::string body_hg(bool spot_only) {
    std::string s = R"slsl(
float test_eval(int i) {
    SlutAirlightHgTable t = slut_airlight_hg_table(slut_axis_make(0.0, u_max, u_scale, SLUT_WARP_LOG1P, u_count),
                                                   slut_axis_make(w_min, SLUT_PIO2_HI, w_scale, w_warp, w_count), phase_g);
    int b = 20 * i;
    SLUT_FLOAT3 viewer = SLUT_FLOAT3(q[b + 1], q[b + 2], q[b + 3]);
    SLUT_FLOAT3 dir = SLUT_FLOAT3(q[b + 4], q[b + 5], q[b + 6]);
    SLUT_FLOAT3 light = SLUT_FLOAT3(q[b + 7], q[b + 8], q[b + 9]);
)slsl";
    if (!spot_only)
        s += R"slsl(    if (int(q[b]) == 2)
        return slut_airlight_hg_radiance_points(SLUT_TEX_ARG(slut_test_table), t, viewer, dir, light, q[b + 15],
                                                q[b + 16], q[b + 17], q[b + 18]);
    if (int(q[b]) >= 3) { // the RGB entry: the query's medium in channel c, other media in the others
        int c = int(q[b]) - 3;
        float s = q[b + 16], a = q[b + 17];
        SLUT_FLOAT3 sigma_s = SLUT_FLOAT3((c == 0) ? s : 0.5 * s, (c == 1) ? s : 2.0 * s, (c == 2) ? s : 0.0);
        SLUT_FLOAT3 sigma_a = SLUT_FLOAT3((c == 0) ? a : 3.0 * a, (c == 1) ? a : 0.1, (c == 2) ? a : 0.0);
        SLUT_FLOAT3 L = slut_airlight_hg_spot_radiance_points_rgb(SLUT_TEX_ARG(slut_test_table), t, viewer, dir, light,
                                                                  SLUT_FLOAT3(q[b + 10], q[b + 11], q[b + 12]), q[b + 13],
                                                                  q[b + 14], q[b + 15], sigma_s, sigma_a, q[b + 18]);
        return (c == 0) ? L.x : ((c == 1) ? L.y : L.z);
    }
)slsl";
    return s + R"slsl(    return slut_airlight_hg_spot_radiance_points(SLUT_TEX_ARG(slut_test_table), t, viewer, dir, light,
                                                 SLUT_FLOAT3(q[b + 10], q[b + 11], q[b + 12]), q[b + 13], q[b + 14],
                                                 q[b + 15], q[b + 16], q[b + 17], q[b + 18]);
}
)slsl";
}
const std::string kBodyAirlight = body_airlight(false), kBodyHg = body_hg(false);

const std::string &snippet(bool hg, const char *extension) {
    static std::string text[2][3];
    const int e = std::string(extension) == "glsl" ? 0 : std::string(extension) == "hlsl" ? 1 : 2;
    std::string &s = text[hg ? 1 : 0][e];
    if (s.empty()) s = read_text(kShaderDir + (hg ? "scatterlut_airlight_hg." : "scatterlut_airlight.") + extension);
    return s;
}
const std::string &body_of(int k) { return k == kHg ? kBodyHg : kBodyAirlight; }
std::string define(const std::string &tier) { return tier.empty() ? "" : "#define " + tier + "\n"; }

// ------------------------------------------------------------------------ tolerances
constexpr double kTolFloat = 2e-5, kTolPerOpticalDistance = 4e-7, kConditioningFactor = 8.0;
const double kDifferenceGain = 2.0 * SLUT_AIRLIGHT_RATIONAL_GAIN - 1.0;

// The table's part of the error against the exact airlight: airlight_rational, (2G − 1) times its
// measured interpolation error (the tiers' stated bound); airlight_F and airlight_Fg, the largest
// effect of the table on the rule over these cases (the rule with the table against the rule
// with the exact point light, in double), times 2.
double table_term(int k) {
    static double term[3] = {-1, -1, -1};
    if (term[k] >= 0) return term[k];
    if (k == kRational) {
        term[k] = kDifferenceGain * scatterlut::measure_airlight_rational_sampling(rational_table(), 20000, 7).max_rel;
    } else {
        const scatterlut::detail::PointLightRadiance exact = [k](const scatterlut::AirlightQuery &a) {
            return scatterlut::airlight_radiance_exact(a, phase_of(k));
        };
        double worst = 0;
        for (const SpotCase &c : cases()) {
            if (c.wide || !(c.reference[k] > 0.0) || std::isinf(c.reference[k]) || c.gpu[0] != 1) continue;
            const double with_exact = scatterlut::detail::spot_airlight_radiance_gpu_rule(exact, c.q, phase_of(k));
            if (with_exact > 1e-30) worst = std::fmax(worst, std::fabs(c.reference[k] - with_exact) / with_exact);
        }
        term[k] = 2.0 * worst;
    }
    std::printf("[ table ] %s: %.3g\n", kind_name(k), term[k]);
    return term[k];
}

// The largest relative jump of a table's texels across a cell (Ĥ for airlight_rational; for the
// others the stored ln G̃, whose jump is the filtered value's relative change).
double max_cell_jump(int k) {
    const scatterlut::Table &t = table_of(k);
    const int w = t.axes[0].map.count, h = t.axes[1].map.count;
    double worst = 0;
    for (int j = 0; j + 1 < h; ++j)
        for (int i = 0; i + 1 < w; ++i) {
            const size_t n = static_cast<size_t>(j) * w + i;
            const double a = t.values[n], dx = std::fabs(t.values[n + 1] - a), dy = std::fabs(t.values[n + w] - a);
            worst = std::fmax(worst, k == kRational ? (dx + dy) / a : dx + dy);
        }
    return worst;
}

std::string describe_case(const SpotCase &c) {
    std::string s = "[";
    for (int i = 0; i < kFloats - 1; ++i) s += (i ? ", " : "") + std::to_string(c.gpu[i]);
    return s + "]";
}

double tolerance_cpp(const SpotCase &c, int k, double filter_extra) {
    return kTolFloat + kTolPerOpticalDistance * c.optical + kConditioningFactor * c.conditioning[k] + filter_extra;
}

#if SLUT_HAVE_EGL
std::vector<float> run_on_gpu(const std::string &source, int k, std::string *error) {
    const scatterlut::Table &t = table_of(k);
    std::vector<float> packed;
    for (const SpotCase &c : cases()) packed.insert(packed.end(), c.gpu.begin(), c.gpu.end());
    const Params p = test_params(k);
    return run_compute(source, std::vector<float>(t.values.begin(), t.values.end()), t.axes[0].map.count,
                       t.axes[1].map.count, 0, packed, cases().size(), &p, sizeof p, error);
}
#endif

// Relative error of a GPU result against a reference: relative to the reference, or for θ_o > π/2
// to the whole ray's point light (where the rule subtracts the dark cone's light from it, and
// float's rounding of the two does not shrink with their difference); infinities must match,
// NaN never does.
double spot_error(const SpotCase &c, int k, double got, double want, bool relative_to_whole) {
    if (std::isinf(want) || std::isinf(got)) return got == want ? 0.0 : HUGE_VAL;
    if (std::isnan(got)) return HUGE_VAL;
    const double scale = relative_to_whole ? c.whole[k] : want;
    return scale > 0.0 ? std::fabs(got - want) / scale : (got == 0.0 ? 0.0 : HUGE_VAL);
}

struct Summary {
    std::vector<double> e;
    double worst_ratio = 0;
    size_t worst = 0;
    void add(size_t i, double err, double tol) {
        e.push_back(err);
        if (err / tol >= worst_ratio) worst_ratio = err / tol, worst = i;
    }
    std::string text() {
        std::sort(e.begin(), e.end());
        char s[160];
        std::snprintf(s, sizeof s, "n=%zu max %.3g p99 %.3g median %.3g max error/tolerance %.2f", e.size(), e.back(),
                      e[static_cast<size_t>(0.99 * static_cast<double>(e.size() - 1))], e[e.size() / 2], worst_ratio);
        return s;
    }
};

void expect_agreement(const std::vector<float> &got, int k, const std::string &run, double filter_extra,
                      ::testing::Test *test) {
    ASSERT_EQ(got.size(), cases().size());
    Summary vs_cpp, vs_exact;
    for (size_t i = 0; i < cases().size(); ++i) {
        const SpotCase &c = cases()[i];
        const double g = got[i];
        EXPECT_FALSE(std::isnan(g) || g < 0.0) << run << ": " << g << " at " << c.label;
        EXPECT_EQ(std::isinf(g), std::isinf(c.exact[k])) << run << ": " << g << " against " << c.exact[k] << " at "
                                                          << c.label;
        const double tol_cpp = tolerance_cpp(c, k, filter_extra);
        const double e_cpp = spot_error(c, k, g, c.reference[k], c.wide);
        vs_cpp.add(i, e_cpp, tol_cpp);
        EXPECT_LE(e_cpp, tol_cpp) << run << " vs the C++ rule at " << c.label << " " << describe_case(c) << ": got " << g
                                  << ", want " << c.reference[k];
        const double tol_exact = tol_cpp + table_term(k) + c.rule_tol[k];
        const double e_exact = spot_error(c, k, g, c.exact[k], c.wide || c.rule_whole[k]);
        vs_exact.add(i, e_exact, tol_exact);
        EXPECT_LE(e_exact, tol_exact) << run << " vs the exact airlight at " << c.label << " " << describe_case(c)
                                      << ": got " << g << ", exact " << c.exact[k] << ", C++ rule " << c.reference[k];
    }
    const double cpp_max = *std::max_element(vs_cpp.e.begin(), vs_cpp.e.end());
    const double exact_max = *std::max_element(vs_exact.e.begin(), vs_exact.e.end());
    const SpotCase &we = cases()[vs_exact.worst];
    std::printf("[ %s ] vs C++ rule %s (%s) | vs exact %s (%s: got %.6g, exact %.6g, rule's tolerance %.3g)\n",
                run.c_str(), vs_cpp.text().c_str(), cases()[vs_cpp.worst].label.c_str(), vs_exact.text().c_str(),
                we.label.c_str(), got[vs_exact.worst], we.exact[k], we.rule_tol[k]);
    test->RecordProperty(run + "_cpp_max_rel_err", std::to_string(cpp_max));
    test->RecordProperty(run + "_exact_max_rel_err", std::to_string(exact_max));
}

} // namespace

// The cases cover what the rule distinguishes: rays that reach the inner cone and rays that only
// cross the band, hard cones, outer angles beyond π/2, infinite rays, and the limits.
TEST(SpotShaderCases, CoverTheRuleAndTheLimits) {
    int core = 0, band_only = 0, hard = 0, wide = 0, infinite = 0, divergent = 0, zero = 0;
    auto v = [](const scatterlut::Vec3 &a) { return slut_vec3_make(a[0], a[1], a[2]); };
    for (const SpotCase &c : cases()) {
        const SpotQuery &q = c.q;
        const slut_spot_ray ray = slut_spot_ray_of(v(q.viewer_m), v(q.view_dir), v(q.light.position_m),
                                                   v(q.light.direction), q.light.outer_angle_rad,
                                                   q.light.inner_angle_rad, q.length_m);
        const slut_spot_interval iv = slut_spot_interval_of(ray);
        if (iv.hi > iv.lo) (iv.has_core ? core : band_only) += 1;
        hard += q.light.inner_angle_rad == q.light.outer_angle_rad;
        wide += c.wide;
        infinite += std::isinf(q.length_m);
        divergent += std::isinf(c.exact[0]);
        zero += c.exact[0] == 0.0;
    }
    std::printf("%zu cases: reach the inner cone %d, band only %d, hard cones %d, theta_o > pi/2 %d, infinite rays %d, "
                "+inf %d, 0 %d\n",
                cases().size(), core, band_only, hard, wide, infinite, divergent, zero);
    EXPECT_GE(core, 250);
    EXPECT_GE(band_only, 40);
    EXPECT_GE(hard, 100);
    EXPECT_GE(wide, 30);
    EXPECT_GE(infinite, 150);
    EXPECT_GE(divergent, 2);
    EXPECT_GE(zero, 50);
}

TEST(SpotShaderGlslang, EveryTierCompilesInEveryLanguage) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    for (bool hg : {false, true})
        for (const std::string tier : {"", "SLUT_TIER_FAST", "SLUT_TIER_ACCURATE"}) {
            const std::string tag = std::string(hg ? "spot_hg_" : "spot_") + (tier.empty() ? "none" : tier);
            const std::string &body = hg ? kBodyHg : kBodyAirlight;
            EXPECT_EQ(glslang(tag + ".comp", glsl_compute_source(snippet(hg, "glsl"), kParams, body, define(tier)), ""), "");
            EXPECT_EQ(glslang(tag + ".hlsl", hlsl_compute_source(snippet(hg, "hlsl"), kParams, body, define(tier)),
                              "-D -V -e main -S comp -o " + gpu_harness::quoted(scratch_dir() + "/" + tag + ".spv")),
                      "");
            // GLSL ES 3.00 (WebGL2): a fragment shader as an engine writes it.
            const std::string table = hg ? "SlutAirlightHgTable t = slut_airlight_hg_table_default(64.0, 1e-7, 128, 1e-3, 64, 0.85);\n"
                                         : (tier.empty() ? "SlutAirlightTable t = slut_airlight_table(64.0, 1e-7, 512, 1e-3, 256);\n"
                                                         : "SlutAirlightTable t = slut_airlight_table(96, 96);\n");
            const std::string essl = "#version 300 es\n" + define(tier) + snippet(hg, "essl") +
                                     "uniform sampler2D table_tex;\nuniform vec3 eye, light, axis;\nuniform vec2 cone;\n"
                                     "in vec3 p;\nout vec4 colour;\nvoid main() {\n    " + table +
                                     "    float L = " + (hg ? "slut_airlight_hg_spot_radiance_points" : "slut_airlight_spot_radiance_points") +
                                     "(table_tex, t, eye, p - eye, light, axis, cone.x, cone.y, length(p - eye), 0.04, 0.01, 100.0);\n"
                                     "    colour = vec4(vec3(L), 1.0);\n}\n";
            EXPECT_EQ(glslang(tag + "_es.frag", essl, ""), "");
        }
}

class GpuSpot : public gpu_harness::GpuTest {};

TEST_F(GpuSpot, AirlightTiersMatchTheCppRuleAndTheExactAirlight) {
#if SLUT_HAVE_EGL
    const double weight_error = hardware_filter_weight_error();
    ASSERT_GE(weight_error, 0.0) << "the ramp shader failed";
    for (const std::string tier : {"SLUT_TIER_ACCURATE", "SLUT_TIER_FAST", ""}) {
        const int k = tier.empty() ? kF : kRational;
        const double extra = tier == "SLUT_TIER_FAST" ? kDifferenceGain * weight_error * max_cell_jump(k) : 0.0;
        std::string error;
        const std::vector<float> got =
            run_on_gpu(glsl_compute_source(snippet(false, "glsl"), kParams, kBodyAirlight, define(tier)), k, &error);
        ASSERT_EQ(error, "") << tier;
        expect_agreement(got, k, tier.empty() ? "airlight none" : tier == "SLUT_TIER_FAST" ? "airlight fast" : "airlight accurate",
                         extra, this);
    }
#endif
}

TEST_F(GpuSpot, AirlightHgTiersMatchTheCppRuleAndTheExactAirlight) {
#if SLUT_HAVE_EGL
    const double weight_error = hardware_filter_weight_error();
    ASSERT_GE(weight_error, 0.0) << "the ramp shader failed";
    for (const std::string tier : {"", "SLUT_TIER_FAST"}) { // the accurate tier's code is the no-tier one
        const double extra = tier.empty() ? 0.0 : 4.0 * weight_error * max_cell_jump(kHg);
        std::string error;
        const std::vector<float> got =
            run_on_gpu(glsl_compute_source(snippet(true, "glsl"), kParams, kBodyHg, define(tier)), kHg, &error);
        ASSERT_EQ(error, "") << tier;
        expect_agreement(got, kHg, tier.empty() ? "airlight_hg none/accurate" : "airlight_hg fast", extra, this);
    }
#endif
}

TEST_F(GpuSpot, HlslMatchesTheCppRule) {
#if SLUT_HAVE_EGL
    if (kGlslang.empty() || kSpirvCross.empty())
        SLUT_SKIP_OR_FAIL("running the HLSL needs glslangValidator and spirv-cross (Debian: glslang-tools, spirv-cross)");
    for (bool hg : {false, true}) {
        const int k = hg ? kHg : kRational;
        std::string error;
        const std::string glsl = hlsl_compute_to_glsl(
            hg ? "spot_hg" : "spot",
            hlsl_compute_source(snippet(hg, "hlsl"), kParams, body_of(k), define(hg ? "" : "SLUT_TIER_ACCURATE")), &error);
        ASSERT_EQ(error, "");
        const std::vector<float> got = run_on_gpu(glsl, k, &error);
        ASSERT_EQ(error, "");
        expect_agreement(got, k, hg ? "hlsl airlight_hg" : "hlsl airlight accurate", 0.0, this);
    }
#endif
}

// ------------------------------------------------------------------ the WebGPU test's cases
namespace {

std::vector<wgsl_cases::CaseSet> write_wgsl_cases() {
    std::vector<wgsl_cases::CaseSet> sets;
    for (int k : {kRational, kF, kHg}) {
        for (bool vs_exact : {false, true}) {
            wgsl_cases::CaseSet c;
            c.name = std::string("spot on ") + kind_name(k) + (vs_exact ? " vs the exact airlight" : " vs the C++ rule");
            c.snippet = k == kHg ? "airlight_hg" : "airlight";
            const scatterlut::Table &t = table_of(k);
            c.width = t.axes[0].map.count;
            c.height = t.axes[1].map.count;
            c.texels.assign(t.values.begin(), t.values.end());
            c.params_decl = kParams;
            Params params = test_params(k);
            params.n_queries = static_cast<int32_t>(
                std::count_if(cases().begin(), cases().end(), [](const SpotCase &s) { return s.gpu[0] == 1; }));
            c.params = wgsl_cases::bytes_of(params);
            c.body = k == kHg ? body_hg(true) : body_airlight(true);
            c.query_floats = kFloats;
            const double per_weight_error = (k == kRational ? kDifferenceGain : 4.0) * max_cell_jump(k);
            wgsl_cases::Tier none, accurate, fast;
            accurate.name = "accurate";
            fast.name = "fast";
            for (const SpotCase &s : cases()) {
                if (s.gpu[0] != 1) continue; // the spot alone (body_airlight)
                // Where the comparison is relative to the whole ray's point light (θ_o > π/2; the rule
                // against the exact airlight for Λ > 8), the tolerance is scaled to the reference.
                const double ref = vs_exact ? s.exact[k] : s.reference[k];
                c.queries.insert(c.queries.end(), s.gpu.begin(), s.gpu.end());
                c.labels.push_back(s.label.substr(0, s.label.find(' ')));
                c.reference.push_back(ref);
                double tol = tolerance_cpp(s, k, 0.0) + (vs_exact ? table_term(k) + s.rule_tol[k] : 0.0);
                const bool whole = s.wide || (vs_exact && s.rule_whole[k]);
                if (whole && ref > 0.0 && std::isfinite(ref)) tol *= s.whole[k] / ref;
                if (whole && ref == 0.0) tol = HUGE_VAL; // checked on the GLSL run, against the whole ray's light
                for (wgsl_cases::Tier *tier : {&none, &accurate, &fast}) tier->tol.push_back(tol);
                fast.tol_per_weight_error.push_back(per_weight_error);
            }
            // On SwiftShader (the test's headless Chromium) every one of these sets agrees when it
            // runs first in a browser session (node tests/shaders/webgpu_snippets.mjs ... --only
            // "spot on airlight_F vs the C++" --slow build/tests/test_shaders_spot, and likewise for each),
            // but from the third spot pipeline of a session on, whatever ran before, the results
            // are garbage (negative values, which the shader cannot return; a new GPUDevice does
            // not help). The sets "vs the C++ rule" and "vs the exact airlight" of one table run the
            // same module on the same texels and queries (only the reference differs), and in one
            // session (2026-12-05, --slow --only spot) the first agreed where the second returned
            // garbage, with the same sets failing on a rerun: SwiftShader's, not the snippet's
            // (the web demo's three spot pipelines, fast, accurate and airlight_F, draw right).
            // Skipped there, run with --slow or elsewhere.
            c.slow_on_swiftshader = "from the third spot pipeline of a SwiftShader session on, its results are garbage "
                                    "(each set agrees run alone: --slow --only NAME)";
            if (k == kRational) c.tiers = {accurate, fast};
            else if (k == kF) c.tiers = {none};
            else c.tiers = {none, fast};
            sets.push_back(c);
        }
    }
    return sets;
}

} // namespace

SLUT_WGSL_CASES(write_wgsl_cases);
