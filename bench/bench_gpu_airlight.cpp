// scatterlut_gpu_bench's airlight scene (gpu_bench.hpp): the airlight of a point light in a
// homogeneous medium, per pixel, by
//   fast       the snippet's fast tier (scatterlut_airlight.glsl, SLUT_TIER_FAST: one filtered
//              fetch per sample of the airlight_rational table, kernels/slut_airlight_rational.h),
//   accurate   its accurate tier (SLUT_TIER_ACCURATE: the same arithmetic, four texel fetches
//              per sample),
//   airlight_F the snippet without a tier (the airlight_F table's ln Gs on warped axes, texel
//              fetches: the C++ runtime's AirlightTable algorithm),
//   sun2005    Sun et al. 2005's two-fetch form A0·[F(A1, v_far) − F(A1, γ/2)] on a plain 64 x 64
//              F(u, v) table (u in [0, 10], v in [0, π/2], linear axes, GL_LINEAR, clamped), as in
//              NVIDIA's SDK 10 Rain sample; F from slut_F_quadrature (bench/shaders/sun2005.glsl),
//   closed     the closed form engines use (Macklin 2010) times e^{−σ_t D}:
//              slut_airlight_no_extinction_attenuated (kernels/slut_airlight.h) in float GLSL
//              with the builtin atan (bench/shaders/closed_form.glsl),
//   inputs     a pass that only reads the per-pixel inputs (the floor every method pays),
//   compare    (--compare-snippet FILE) another scatterlut_airlight.glsl, as airlight_F runs,
// each rendering the same per-pixel geometries; errors against airlight_radiance_exact (double,
// the same float inputs) on every `stride`-th pixel whose e^{−σ_t D} ≥ 1e-6.
//
// The geometry, a street seen by a viewer 1.7 m above the ground (90° horizontal field of
// view, the street 16 m wide, rays end on the ground or the walls, at most at 200 m): every
// 32 x 32 pixel tile has its own lamp, at D log-uniform in [1, 100] m in a direction uniform
// on the sphere, fog σ_s log-uniform in [0.004, 0.4] per m, σ_a = σ_s/20, I0 = 100 W/sr.
//
// The tiers' tables: airlight_rational tables sized for the tiers' radiance targets (fast: 1e-3,
// accurate: 1.5e-4, issue #31) by their measured interpolation error, as the planner sizes them
// (kinds/airlight_rational_kind.cpp), generated on the OpenCL device as `scatterlut generate`
// does; airlight_F: the default plan.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "generate_airlight.hpp"
#include "generate_airlight_rational.hpp"
#include "gpu_bench.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/io.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_airlight_rational.h"
}

namespace gpu_bench {
namespace {

constexpr double kPi = 3.14159265358979323846;

// Plain F table (Sun et al. 2005; the Rain sample's layout).
constexpr int kFCount = 64;
constexpr double kFUMax = 10.0;

// Per-pixel inputs: sigma_s, sigma_a, I0, D | sin gamma, cos gamma, s, 0 (two vec4 per pixel).
std::vector<float> make_scene(int width, int height) {
    std::vector<float> geo(static_cast<size_t>(width) * height * 8);
    const double tan_half_fov = 1.0; // 90° horizontal
    const double eye_height_m = 1.7, half_street_m = 8.0, far_m = 200.0;
    const int tile = 32;
    const int tiles_x = (width + tile - 1) / tile;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int tile_index = (y / tile) * tiles_x + x / tile;
            std::mt19937_64 rng(0x5eedULL + static_cast<unsigned long long>(tile_index));
            std::uniform_real_distribution<double> uni(0.0, 1.0);
            const double z = 2.0 * uni(rng) - 1.0, phi = 2.0 * kPi * uni(rng);
            const double r = std::sqrt(std::max(0.0, 1.0 - z * z));
            const double light_dir[3] = {r * std::cos(phi), r * std::sin(phi), z};
            const double D = std::exp(std::log(1.0) + uni(rng) * (std::log(100.0) - std::log(1.0)));
            const double sigma_s = std::exp(std::log(0.004) + uni(rng) * (std::log(0.4) - std::log(0.004)));
            // The view ray through the pixel centre (row 0 at the bottom, as gl_FragCoord).
            double dir[3] = {(2.0 * (x + 0.5) / width - 1.0) * tan_half_fov,
                             (2.0 * (y + 0.5) / height - 1.0) * tan_half_fov * height / width, 1.0};
            const double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (double &c : dir) c /= n;
            double s = far_m;
            if (dir[1] < 0.0) s = std::min(s, eye_height_m / -dir[1]);
            if (dir[0] != 0.0) s = std::min(s, half_street_m / std::fabs(dir[0]));
            const double cos_g = dir[0] * light_dir[0] + dir[1] * light_dir[1] + dir[2] * light_dir[2];
            const double cx = dir[1] * light_dir[2] - dir[2] * light_dir[1];
            const double cy = dir[2] * light_dir[0] - dir[0] * light_dir[2];
            const double cz = dir[0] * light_dir[1] - dir[1] * light_dir[0];
            const double sin_g = std::sqrt(cx * cx + cy * cy + cz * cz);
            float *g = &geo[(static_cast<size_t>(y) * width + x) * 8];
            g[0] = static_cast<float>(sigma_s);
            g[1] = static_cast<float>(sigma_s / 20.0);
            g[2] = 100.0f;
            g[3] = static_cast<float>(D);
            g[4] = static_cast<float>(sin_g);
            g[5] = static_cast<float>(cos_g);
            g[6] = static_cast<float>(s);
            g[7] = 0.0f;
        }
    }
    return geo;
}

} // namespace

// The airlight_rational table for a radiance target: the smallest square of kSizes whose
// measured interpolation error (measure_airlight_rational_sampling, 20000 points) times the
// difference's gain 2G − 1 is within the target, generated on the OpenCL device as `scatterlut
// generate` does (f32).
scatterlut::Table rational_table(scatterlut::Device &device, double radiance_target) {
    static const int kSizes[] = {32, 48, 64, 96, 128, 192, 256, 384, 512};
    scatterlut::Table table;
    for (int n : kSizes) {
        scatterlut::AirlightRationalPlan plan;
        plan.n_m = plan.n_t = n;
        table = scatterlut::make_airlight_rational_layout(plan);
        table.values = scatterlut::integrate_airlight_rational(device, table, plan.integration_tolerance);
        for (double &v : table.values) v = scatterlut::round_to_storage(v, plan.storage);
        const double error = scatterlut::measure_airlight_rational_sampling(scatterlut::AirlightRationalTable(table),
                                                                            20000, 1).max_rel;
        if ((2.0 * SLUT_AIRLIGHT_RATIONAL_GAIN - 1.0) * error <= radiance_target) break;
    }
    return table;
}

// The default airlight_F table, as `scatterlut generate` makes it (f32 storage).
scatterlut::Table airlight_F_table(scatterlut::Device &device) {
    const scatterlut::AirlightPlan plan;
    scatterlut::Table table = scatterlut::make_airlight_table_layout(plan);
    table.values = scatterlut::integrate_airlight_ln_gs(device, table);
    for (double &v : table.values) v = scatterlut::round_to_storage(v, plan.storage);
    return table;
}

int run_airlight_scene(const gpu_harness::Gl &gl, const Options &opt) {
    std::string compare_text;
    if (!opt.compare_snippet.empty()) {
        compare_text = read_text(opt.compare_snippet);
        if (compare_text.empty()) {
            std::fprintf(stderr, "scatterlut_gpu_bench: --compare-snippet: cannot read '%s'\n", opt.compare_snippet.c_str());
            return 1;
        }
    }
    scatterlut::Device device("");
    const scatterlut::AirlightPlan plan;
    const scatterlut::Table table = airlight_F_table(device);
    const int u_count = table.axes[0].map.count, w_count = table.axes[1].map.count;

    // The plain F table of Sun et al. 2005 from the exact F.
    std::vector<float> f_texels(static_cast<size_t>(kFCount) * kFCount);
    for (int j = 0; j < kFCount; ++j)
        for (int i = 0; i < kFCount; ++i)
            f_texels[static_cast<size_t>(j) * kFCount + i] = static_cast<float>(
                slut_F_quadrature(kFUMax * i / (kFCount - 1), 0.5 * kPi * j / (kFCount - 1)));

    const std::string snippet = read_text(std::string(SLUT_SHADER_DIR) + "/scatterlut_airlight.glsl");
    const std::string closed_glsl = read_text(std::string(SLUT_BENCH_SHADER_DIR) + "/closed_form.glsl");
    const std::string sun_glsl = read_text(std::string(SLUT_BENCH_SHADER_DIR) + "/sun2005.glsl");
    if (snippet.empty() || closed_glsl.empty() || sun_glsl.empty()) {
        std::fprintf(stderr, "scatterlut_gpu_bench: cannot read the airlight snippet or bench/shaders/*.glsl\n");
        return 1;
    }
    const scatterlut::Table fast_table = rational_table(device, 1e-3), accurate_table = rational_table(device, 1.5e-4);
    const int fast_count = fast_table.axes[0].map.count, accurate_count = accurate_table.axes[0].map.count;
    const std::string inputs = "in0.x, in0.y, in0.z, in0.w, in1.x, in1.y, in1.z"; // ss, sa, I0, D, sin, cos, s
    auto tier = [&](const char *define, int n) {
        return std::string("#define ") + define + "\nlayout(binding = 0) uniform sampler2D hn_table;\n" + snippet +
               "\nSlutAirlightTable tier_table() { return slut_airlight_table(" + std::to_string(n) + ", " +
               std::to_string(n) + "); }\n";
    };
    const std::string table_F = "layout(binding = 0) uniform sampler2D ln_gs_table;\n";
    char F_table[160];
    std::snprintf(F_table, sizeof F_table, "slut_airlight_table(%.9g, %.9g, %d, %.9g, %d)", plan.u_max, plan.u_scale,
                  u_count, plan.w_min, w_count);
    const std::string F_call = "slut_airlight_radiance(ln_gs_table, " + std::string(F_table) + ", " + inputs + ")";
    const std::string tier_call = "slut_airlight_radiance(hn_table, tier_table(), " + inputs + ")";
    std::vector<Method> methods = {
        {"fast", "SLUT_TIER_FAST, airlight_rational " + std::to_string(fast_count) + "², one filtered fetch per sample",
         fragment_source(tier("SLUT_TIER_FAST", fast_count), 2, tier_call), GL_TEXTURE_2D,
         gpu_harness::make_r32f_texture(gl, std::vector<float>(fast_table.values.begin(), fast_table.values.end()), fast_count,
                                        fast_count, 0)},
        {"accurate", "SLUT_TIER_ACCURATE, airlight_rational " + std::to_string(accurate_count) + "², texel fetches",
         fragment_source(tier("SLUT_TIER_ACCURATE", accurate_count), 2, tier_call), GL_TEXTURE_2D,
         gpu_harness::make_r32f_texture(gl, std::vector<float>(accurate_table.values.begin(), accurate_table.values.end()),
                                        accurate_count, accurate_count, 0)},
        {"airlight_F", "no tier: the airlight_F table, texel fetches", fragment_source(table_F + snippet, 2, F_call),
         GL_TEXTURE_2D, gpu_harness::make_r32f_texture(gl, std::vector<float>(table.values.begin(), table.values.end()), u_count,
                                                       w_count, 0)},
        {"sun2005", "Sun et al. 2005, 64² F table, two fetches",
         fragment_source(sun_glsl, 2, "sun2005(" + inputs + ")"), GL_TEXTURE_2D,
         gpu_harness::make_r32f_texture(gl, f_texels, kFCount, kFCount, 0), false,
         {{"f_u_max", static_cast<float>(kFUMax)}}}, // the F table's u range
        {"closed", "closed form × e^{−σ_t D} (Macklin 2010)", fragment_source(closed_glsl, 2,
                                                                             "closed_form_attenuated(" + inputs + ")")},
        {"inputs", "reads the inputs only", fragment_source("", 2, "in0.x + in0.y + in0.z + in0.w + in1.x + in1.y + in1.z")},
    };
    methods.back().timed_only = true;
    if (!compare_text.empty())
        methods.insert(methods.begin() + 3, Method{"compare", opt.compare_snippet + ", as airlight_F",
                                                   fragment_source(table_F + compare_text, 2, F_call), GL_TEXTURE_2D,
                                                   methods[2].texture});

    const std::vector<float> geo = make_scene(opt.width, opt.height);
    Passes passes(gl, opt.width, opt.height, geo);
    std::vector<std::vector<double>> round_ms;
    if (!build_and_time(gl, passes, methods, opt, &round_ms)) return 1;

    // The sampled pixels and their exact radiance; which path each takes.
    const size_t pixels = static_cast<size_t>(opt.width) * opt.height;
    std::vector<size_t> sampled;
    for (size_t i = 0; i < pixels; i += static_cast<size_t>(opt.stride)) {
        const float *g = &geo[i * 8];
        if (std::exp(-(static_cast<double>(g[0]) + g[1]) * g[3]) >= 1e-6) sampled.push_back(i);
    }
    std::vector<double> exact(sampled.size());
    size_t segment_rule = 0, sun_clamped = 0;
    for (size_t k = 0; k < sampled.size(); ++k) {
        const float *g = &geo[sampled[k] * 8];
        scatterlut::AirlightQuery q;
        q.sigma_s_per_m = g[0];
        q.sigma_a_per_m = g[1];
        q.intensity_W_per_sr = g[2];
        q.distance_m = g[3];
        q.gamma_rad = std::atan2(static_cast<double>(g[4]), static_cast<double>(g[5]));
        q.length_m = g[6];
        exact[k] = scatterlut::airlight_radiance_exact(q);
        const slut_airlight_rational_setup r = slut_airlight_rational_setup_of(g[0], g[1], g[2], g[3], g[4], g[5], g[6]);
        const double h2 = slut_airlight_rational_node(r.x_m2, r.x_t2, 1.0), h1 = slut_airlight_rational_node(r.x_m1, r.x_t1, 1.0);
        if (r.kind == 0 && !(r.weight1 * h1 <= (1.0 - 1.0 / SLUT_AIRLIGHT_RATIONAL_GAIN) * r.weight2 * h2)) ++segment_rule;
        if ((static_cast<double>(g[0]) + g[1]) * g[3] * g[4] > kFUMax) ++sun_clamped;
    }
    std::vector<ErrorStats> errors(methods.size());
    for (size_t m = 0; m < methods.size(); ++m)
        if (!methods[m].timed_only) errors[m] = relative_errors(passes.frame(methods[m]), sampled, exact);
    if (gl.glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "scatterlut_gpu_bench: OpenGL error during the read-back\n");
        return 1;
    }
    const double share = 100.0 / static_cast<double>(std::max<size_t>(sampled.size(), 1));
    std::printf("\n## Airlight: %d x %d pixels, %d rounds x %d frames per method; errors on %zu pixels (every %d-th "
                "with e^{-sigma_t D} >= 1e-6); of those %.1f %% take the tiers' segment rule (their two samples would "
                "cancel), %.1f %% have u > %g (the F table clamps)\n\n",
                opt.width, opt.height, opt.rounds, opt.frames, sampled.size(), opt.stride, segment_rule * share,
                sun_clamped * share, kFUMax);
    print_table(methods, round_ms, {"closed", "sun2005"}, errors, pixels, opt.rounds);
    return 0;
}

} // namespace gpu_bench
