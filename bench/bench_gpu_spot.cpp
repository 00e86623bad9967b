// scatterlut_gpu_bench's spot scene (gpu_bench.hpp): the airlight scene's street and lamps
// (bench_gpu_airlight.cpp), every lamp a spot light (glTF KHR_lights_punctual's cone) with its
// own axis and cone, drawn by
//   fast, accurate, airlight_F           the point light at the lamp, from positions
//                                        (slut_airlight_radiance_points) in the snippet's three
//                                        tiers (fast, accurate, no tier),
//   spot_fast, spot_accurate, spot_airlight_F
//                                        the spot in the same tiers
//                                        (slut_airlight_spot_radiance_points: kernels/slut_spot_rule.h),
//   inputs                               a pass that only reads the per-pixel inputs,
//   spot_compare                         (--compare-snippet FILE) another scatterlut_airlight.glsl's
//                                        spot, as spot_fast runs,
// all from the same per-pixel inputs (four vec4: the point light reads all but the cone's), so
// that the per-round ratio spot/point of a tier is the spot's cost against the point light's on
// the same pixels. Errors against the exact airlight (double, the same float inputs): the point
// rows against airlight_radiance_exact, the spot rows against spot_airlight_radiance_exact,
// on every `stride`-th pixel whose e^{−σ_t D} ≥ 1e-6 and whose exact radiance is > 0.
//
// The lamps: as the airlight scene's (every 32 x 32 tile its own: D log-uniform in [1, 100] m
// from the eye in a direction uniform on the sphere, σ_s log-uniform in [0.004, 0.4] per m,
// σ_a = σ_s/20, I0 = 100 W/sr), and per tile an axis uniform on the sphere, θ_o uniform in
// [0.3, 1.2] rad and θ_i = θ_o − U(0.05, 0.3) (soft cones of typical widths; every fourth a hard
// cone, θ_i = θ_o).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "generate_airlight.hpp"
#include "gpu_bench.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/spot.hpp"

namespace gpu_bench {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kEyeHeight = 1.7; // m; the eye at (0, 1.7, 0), looking along +z

// Per pixel (four vec4): σ_s, σ_a, I0, s | view direction, θ_o | light position, θ_i | axis, 0.
std::vector<float> make_scene(int width, int height) {
    std::vector<float> px(static_cast<size_t>(width) * height * 16);
    const double tan_half_fov = 1.0, half_street_m = 8.0, far_m = 200.0;
    const int tile = 32, tiles_x = (width + tile - 1) / tile;
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int tile_index = (y / tile) * tiles_x + x / tile;
            std::mt19937_64 rng(0x5eedULL + static_cast<unsigned long long>(tile_index));
            std::uniform_real_distribution<double> uni(0.0, 1.0);
            auto sphere = [&](double out[3]) {
                const double z = 2.0 * uni(rng) - 1.0, phi = 2.0 * kPi * uni(rng), r = std::sqrt(std::max(0.0, 1.0 - z * z));
                out[0] = r * std::cos(phi);
                out[1] = r * std::sin(phi);
                out[2] = z;
            };
            // The airlight scene's draws first (the same lamp and fog per tile), then the cone's.
            double light_dir[3];
            sphere(light_dir);
            const double D = std::exp(uni(rng) * std::log(100.0));
            const double sigma_s = std::exp(std::log(0.004) + uni(rng) * (std::log(0.4) - std::log(0.004)));
            double axis[3];
            sphere(axis);
            const double outer = 0.3 + 0.9 * uni(rng);
            const double inner = (tile_index % 4 == 0) ? outer : outer - (0.05 + 0.25 * uni(rng));
            double dir[3] = {(2.0 * (x + 0.5) / width - 1.0) * tan_half_fov,
                             (2.0 * (y + 0.5) / height - 1.0) * tan_half_fov * height / width, 1.0};
            const double n = std::sqrt(dir[0] * dir[0] + dir[1] * dir[1] + dir[2] * dir[2]);
            for (double &c : dir) c /= n;
            double s = far_m;
            if (dir[1] < 0.0) s = std::min(s, kEyeHeight / -dir[1]);
            if (dir[0] != 0.0) s = std::min(s, half_street_m / std::fabs(dir[0]));
            float *p = &px[(static_cast<size_t>(y) * width + x) * 16];
            const double row[16] = {sigma_s, sigma_s / 20.0, 100.0, s,
                                    dir[0], dir[1], dir[2], outer,
                                    D * light_dir[0], kEyeHeight + D * light_dir[1], D * light_dir[2], inner,
                                    axis[0], axis[1], axis[2], 0.0};
            for (int k = 0; k < 16; ++k) p[k] = static_cast<float>(row[k]);
        }
    }
    return px;
}

scatterlut::SpotQuery spot_query(const float *p) {
    scatterlut::SpotQuery q;
    q.sigma_s_per_m = p[0];
    q.sigma_a_per_m = p[1];
    q.light.intensity_W_per_sr = p[2];
    q.length_m = p[3];
    q.viewer_m = {0.0, static_cast<double>(static_cast<float>(kEyeHeight)), 0.0};
    q.view_dir = {p[4], p[5], p[6]};
    q.light.outer_angle_rad = p[7];
    q.light.position_m = {p[8], p[9], p[10]};
    q.light.inner_angle_rad = p[11];
    q.light.direction = {p[12], p[13], p[14]};
    return q;
}

} // namespace

int run_spot_scene(const gpu_harness::Gl &gl, const Options &opt) {
    const std::string snippet = read_text(std::string(SLUT_SHADER_DIR) + "/scatterlut_airlight.glsl");
    if (snippet.empty()) {
        std::fprintf(stderr, "scatterlut_gpu_bench: cannot read the airlight snippet\n");
        return 1;
    }
    scatterlut::Device device("");
    const scatterlut::AirlightPlan plan;
    const scatterlut::Table table_F = airlight_F_table(device);
    const scatterlut::Table fast_table = rational_table(device, 1e-3), accurate_table = rational_table(device, 1.5e-4);
    const int fast_count = fast_table.axes[0].map.count, accurate_count = accurate_table.axes[0].map.count;
    char F_table[160];
    std::snprintf(F_table, sizeof F_table, "slut_airlight_table(%.9g, %.9g, %d, %.9g, %d)", plan.u_max, plan.u_scale,
                  table_F.axes[0].map.count, plan.w_min, table_F.axes[1].map.count);
    auto code = [&](const char *define, const std::string &table_expr) {
        return std::string(define ? std::string("#define ") + define + "\n" : "") +
               "layout(binding = 0) uniform sampler2D table_tex;\n" + snippet +
               "\nSlutAirlightTable bench_table() { return " + table_expr + "; }\nconst vec3 eye_m = vec3(0.0, " +
               std::to_string(static_cast<float>(kEyeHeight)) + ", 0.0);\n";
    };
    const std::string point_call =
        "slut_airlight_radiance_points(table_tex, bench_table(), eye_m, in1.xyz, in2.xyz, in0.w, in0.x, in0.y, in0.z)";
    const std::string spot_call = "slut_airlight_spot_radiance_points(table_tex, bench_table(), eye_m, in1.xyz, in2.xyz, "
                                  "in3.xyz, in1.w, in2.w, in0.w, in0.x, in0.y, in0.z)";
    const std::string fast_expr = "slut_airlight_table(" + std::to_string(fast_count) + ", " + std::to_string(fast_count) + ")";
    const std::string accurate_expr =
        "slut_airlight_table(" + std::to_string(accurate_count) + ", " + std::to_string(accurate_count) + ")";
    auto texture = [&](const scatterlut::Table &t) {
        return gpu_harness::make_r32f_texture(gl, std::vector<float>(t.values.begin(), t.values.end()),
                                              t.axes[0].map.count, t.axes[1].map.count, 0);
    };
    const GLuint fast_tex = texture(fast_table), accurate_tex = texture(accurate_table), F_tex = texture(table_F);
    const std::string fast_what = "SLUT_TIER_FAST, airlight_rational " + std::to_string(fast_count) + "²";
    const std::string accurate_what = "SLUT_TIER_ACCURATE, airlight_rational " + std::to_string(accurate_count) + "²";
    std::vector<Method> methods = {
        {"fast", "point light, " + fast_what, fragment_source(code("SLUT_TIER_FAST", fast_expr), 4, point_call),
         GL_TEXTURE_2D, fast_tex},
        {"spot_fast", "spot, " + fast_what, fragment_source(code("SLUT_TIER_FAST", fast_expr), 4, spot_call),
         GL_TEXTURE_2D, fast_tex},
        {"accurate", "point light, " + accurate_what,
         fragment_source(code("SLUT_TIER_ACCURATE", accurate_expr), 4, point_call), GL_TEXTURE_2D, accurate_tex},
        {"spot_accurate", "spot, " + accurate_what,
         fragment_source(code("SLUT_TIER_ACCURATE", accurate_expr), 4, spot_call), GL_TEXTURE_2D, accurate_tex},
        {"airlight_F", "point light, no tier (airlight_F)", fragment_source(code(nullptr, F_table), 4, point_call),
         GL_TEXTURE_2D, F_tex},
        {"spot_airlight_F", "spot, no tier (airlight_F)", fragment_source(code(nullptr, F_table), 4, spot_call),
         GL_TEXTURE_2D, F_tex},
        {"inputs", "reads the inputs only",
         fragment_source("", 4, "dot(in0, vec4(1.0)) + dot(in1, vec4(1.0)) + dot(in2, vec4(1.0)) + dot(in3, vec4(1.0))")},
    };
    methods.back().timed_only = true;
    if (!opt.compare_snippet.empty()) { // --compare-snippet: another scatterlut_airlight.glsl's spot, as spot_fast runs
        const std::string other = read_text(opt.compare_snippet);
        if (other.empty()) {
            std::fprintf(stderr, "scatterlut_gpu_bench: --compare-snippet: cannot read '%s'\n", opt.compare_snippet.c_str());
            return 1;
        }
        const std::string other_code = "#define SLUT_TIER_FAST\nlayout(binding = 0) uniform sampler2D table_tex;\n" + other +
                                       "\nSlutAirlightTable bench_table() { return " + fast_expr +
                                       "; }\nconst vec3 eye_m = vec3(0.0, " + std::to_string(static_cast<float>(kEyeHeight)) +
                                       ", 0.0);\n";
        methods.insert(methods.begin() + 2, Method{"spot_compare", opt.compare_snippet + ", as spot_fast",
                                                   fragment_source(other_code, 4, spot_call), GL_TEXTURE_2D, fast_tex});
    }

    const std::vector<float> px = make_scene(opt.width, opt.height);
    Passes passes(gl, opt.width, opt.height, px);
    std::vector<std::vector<double>> round_ms;
    if (!build_and_time(gl, passes, methods, opt, &round_ms)) return 1;

    // The sampled pixels and their exact radiances (point light and spot).
    const size_t pixels = static_cast<size_t>(opt.width) * opt.height;
    std::vector<size_t> sampled_point, sampled_spot;
    std::vector<double> exact_point, exact_spot;
    size_t core = 0;
    for (size_t i = 0; i < pixels; i += static_cast<size_t>(opt.stride)) {
        const float *p = &px[i * 16];
        const scatterlut::SpotQuery q = spot_query(p);
        const scatterlut::AirlightQuery a = scatterlut::airlight_query_from_points(
            q.viewer_m.data(), q.view_dir.data(), q.light.position_m.data(), q.length_m, q.sigma_s_per_m,
            q.sigma_a_per_m, q.light.intensity_W_per_sr);
        if (std::exp(-(a.sigma_s_per_m + a.sigma_a_per_m) * a.distance_m) < 1e-6) continue;
        sampled_point.push_back(i);
        exact_point.push_back(scatterlut::airlight_radiance_exact(a));
        const double spot = scatterlut::spot_airlight_radiance_exact(q);
        if (!(spot > 0.0)) continue;
        sampled_spot.push_back(i);
        exact_spot.push_back(spot);
        core += q.light.inner_angle_rad == q.light.outer_angle_rad;
    }
    std::vector<ErrorStats> errors(methods.size());
    for (size_t m = 0; m < methods.size(); ++m) {
        if (methods[m].timed_only) continue;
        const bool spot = methods[m].name.rfind("spot_", 0) == 0;
        errors[m] = relative_errors(passes.frame(methods[m]), spot ? sampled_spot : sampled_point,
                                    spot ? exact_spot : exact_point);
    }
    if (gl.glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "scatterlut_gpu_bench: OpenGL error during the read-back\n");
        return 1;
    }
    std::printf("\n## Spot lights: %d x %d pixels, %d rounds x %d frames per method; errors on %zu pixels (point "
                "light: every %d-th with e^{-sigma_t D} >= 1e-6) and the %zu of them the spot lights (%zu behind a "
                "hard cone)\n\n",
                opt.width, opt.height, opt.rounds, opt.frames, sampled_point.size(), opt.stride, sampled_spot.size(),
                core);
    print_table(methods, round_ms, {"fast", "accurate", "airlight_F"}, errors, pixels, opt.rounds);
    return 0;
}

} // namespace gpu_bench
