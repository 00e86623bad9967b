// scatterlut_gpu_bench's near-light scene (gpu_bench.hpp): the single-scattered radiance of a
// point light outside a thick translucent medium (Gath 2008), per pixel, by
//   nearlight_fast      the near-light snippet's fast tier (scatterlut_nearlight.glsl,
//                       SLUT_TIER_FAST: one trilinear filtered fetch of the E3 table),
//   nearlight_accurate  its accurate tier (SLUT_TIER_ACCURATE: eight texel fetches, the
//                       trilinear done in the shader, as the C++ runtime's NearLightTable),
//   thin                the thin-medium closed form (Gath 2008 §4.2: E ≈ (1 − e^{−x})/x,
//                       x = S(1 + r)/r; slut_near_light_radiance_thin),
//   inputs              a pass that only reads the per-pixel inputs,
// each on the same per-pixel geometries. The table: the default E3 plan (default_near_light_plan),
// generated on the OpenCL device as `scatterlut generate` does, f32. Errors against
// near_light_radiance_exact (double) on every `stride`-th pixel, reported over the pixels the
// E3 table covers (NearLightTable::covers; elsewhere the shader clamps to the table's edge).
//
// The geometry: a viewer 1.7 m above a floor of the medium (the plane y = 0, normal +y), looking
// 35° down (90° horizontal field of view: every ray meets the floor); every 32 x 32 pixel tile
// has its own lamp, 1 cm to 1 m above the floor (log-uniform), up to 1 m to the side of the
// floor point seen at the tile's centre, I0 = 10 W/sr, and its own medium: σ_t log-uniform in
// [1, 100] per m (wax, marble, skin), albedo in [0.5, 0.99]; no refraction (η = 1).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <string>
#include <vector>

#include "generate_nearlight.hpp"
#include "gpu_bench.hpp"
#include "opencl_device.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/nearlight.hpp"

namespace gpu_bench {
namespace {

constexpr int kInputVec4s = 4; // (σ_s, σ_a, I0, s), (normal, η), (eye_dir, 0), (light_rel, 0)

// The per-pixel queries (as floats, kInputVec4s vec4s per pixel).
std::vector<float> make_scene(int width, int height) {
    std::vector<float> px(static_cast<size_t>(width) * height * 4 * kInputVec4s);
    const double eye[3] = {0.0, 1.7, 0.0}, pitch = 35.0 * 3.14159265358979323846 / 180.0;
    const int tile = 32;
    const int tiles_x = (width + tile - 1) / tile;
    // The floor point seen through pixel (x, y) (row 0 at the bottom, as gl_FragCoord).
    auto floor_point = [&](double x, double y, double out[3]) {
        const double cx = (2.0 * x / width - 1.0), cy = (2.0 * y / height - 1.0) * height / width;
        // Camera looking along +z pitched down: forward (0, -sin, cos), up (0, cos, sin).
        const double d[3] = {cx, cy * std::cos(pitch) - std::sin(pitch), cy * std::sin(pitch) + std::cos(pitch)};
        const double t = eye[1] / -d[1];
        for (int k = 0; k < 3; ++k) out[k] = eye[k] + t * d[k];
    };
    for (int y = 0; y < height; ++y) {
        for (int x = 0; x < width; ++x) {
            const int tx = x / tile, ty = y / tile;
            std::mt19937_64 rng(0x1a4bULL + static_cast<unsigned long long>(ty * tiles_x + tx));
            std::uniform_real_distribution<double> uni(0.0, 1.0);
            auto log_uniform = [&](double lo, double hi) { return std::exp(std::log(lo) + uni(rng) * std::log(hi / lo)); };
            double centre[3], o[3];
            floor_point((tx + 0.5) * tile, (ty + 0.5) * tile, centre);
            const double height_m = log_uniform(0.01, 1.0), radius = std::sqrt(uni(rng)), phi = 6.283185307 * uni(rng);
            const double lamp[3] = {centre[0] + radius * std::cos(phi), height_m, centre[2] + radius * std::sin(phi)};
            const double sigma_t = log_uniform(1.0, 100.0), albedo = 0.5 + 0.49 * uni(rng);
            floor_point(x + 0.5, y + 0.5, o);
            double eye_dir[3], n = 0;
            for (int k = 0; k < 3; ++k) eye_dir[k] = eye[k] - o[k], n += eye_dir[k] * eye_dir[k];
            float *p = &px[(static_cast<size_t>(y) * width + x) * 4 * kInputVec4s];
            const float v[16] = {static_cast<float>(albedo * sigma_t), static_cast<float>((1.0 - albedo) * sigma_t),
                                 10.0f, std::numeric_limits<float>::infinity(),
                                 0.0f, 1.0f, 0.0f, 1.0f,
                                 static_cast<float>(eye_dir[0] / std::sqrt(n)), static_cast<float>(eye_dir[1] / std::sqrt(n)),
                                 static_cast<float>(eye_dir[2] / std::sqrt(n)), 0.0f,
                                 static_cast<float>(lamp[0] - o[0]), static_cast<float>(lamp[1] - o[1]),
                                 static_cast<float>(lamp[2] - o[2]), 0.0f};
            std::copy(v, v + 16, p);
        }
    }
    return px;
}

// The query of pixel inputs p (float-rounded as the GPU reads them).
scatterlut::NearLightQuery query_of(const float *p) {
    scatterlut::NearLightQuery q;
    q.sigma_s_per_m = p[0];
    q.sigma_a_per_m = p[1];
    q.intensity_W_per_sr = p[2];
    q.length_m = p[3];
    for (int k = 0; k < 3; ++k) {
        q.normal[k] = p[4 + k];
        q.eye_dir[k] = p[8 + k];
        q.light_rel_m[k] = p[12 + k];
    }
    // The float eye direction, renormalised in double (the check wants a unit vector).
    const double n = std::sqrt(q.eye_dir[0] * q.eye_dir[0] + q.eye_dir[1] * q.eye_dir[1] + q.eye_dir[2] * q.eye_dir[2]);
    for (double &c : q.eye_dir) c /= n;
    return q;
}

} // namespace

int run_nearlight_scene(const gpu_harness::Gl &gl, const Options &opt) {
    const scatterlut::NearLightPlan plan = scatterlut::default_near_light_plan(false);
    scatterlut::Table table = scatterlut::make_nearlight_table_layout(plan);
    {
        scatterlut::Device device("");
        table.values = scatterlut::integrate_nearlight_ln_E(device, table);
    }
    for (double &v : table.values) v = scatterlut::round_to_storage(v, plan.storage);
    const scatterlut::NearLightTable runtime(table);
    const std::string snippet = read_text(std::string(SLUT_SHADER_DIR) + "/scatterlut_nearlight.glsl");
    if (snippet.empty()) {
        std::fprintf(stderr, "scatterlut_gpu_bench: cannot read scatterlut_nearlight.glsl\n");
        return 1;
    }
    std::string axes;
    for (int k = 0; k < 3; ++k) {
        const slut_axis &a = table.axes[static_cast<size_t>(k)].map;
        char buf[160];
        std::snprintf(buf, sizeof buf, "%sslut_axis_make(%.9g, %.9g, %.9g, %d, %d)", k ? ", " : "", a.min, a.max,
                      a.scale, a.warp, a.count);
        axes += buf;
    }
    const std::string args = "in0.x, in0.y, in0.z, in1.xyz, in2.xyz, in3.xyz, in0.w, in1.w, false";
    auto tier = [&](const char *define) {
        return std::string("#define ") + define + "\nlayout(binding = 0) uniform sampler3D ln_e_table;\n" + snippet;
    };
    const std::string table_call =
        "slut_near_light_radiance(ln_e_table, slut_near_light_table_e3(" + axes + "), " + args + ")";
    const GLuint texture = gpu_harness::make_r32f_texture(gl, std::vector<float>(table.values.begin(), table.values.end()),
                                        table.axes[0].map.count, table.axes[1].map.count, table.axes[2].map.count);
    std::vector<Method> methods = {
        {"nearlight_fast", "SLUT_TIER_FAST, default E3, one filtered fetch",
         fragment_source(tier("SLUT_TIER_FAST"), kInputVec4s, table_call), GL_TEXTURE_3D, texture},
        {"nearlight_accurate", "SLUT_TIER_ACCURATE, default E3, eight texel fetches",
         fragment_source(tier("SLUT_TIER_ACCURATE"), kInputVec4s, table_call), GL_TEXTURE_3D, texture},
        {"thin", "thin-medium closed form, Gath 2008 §4.2",
         fragment_source(snippet, kInputVec4s, "slut_near_light_radiance_thin(" + args + ")")},
        {"inputs", "reads the inputs only",
         fragment_source("", kInputVec4s, "in0.x + in0.y + in0.z + in1.x + in2.x + in2.y + in2.z + in3.x + in3.y + in3.z")},
    };
    methods.back().timed_only = true;

    const std::vector<float> px = make_scene(opt.width, opt.height);
    Passes passes(gl, opt.width, opt.height, px);
    std::vector<std::vector<double>> round_ms;
    if (!build_and_time(gl, passes, methods, opt, &round_ms)) return 1;

    // The sampled pixels the table covers, with their exact radiance.
    const size_t pixels = static_cast<size_t>(opt.width) * opt.height;
    std::vector<size_t> sampled;
    std::vector<double> exact;
    size_t all = 0;
    for (size_t i = 0; i < pixels; i += static_cast<size_t>(opt.stride)) {
        const scatterlut::NearLightQuery q = query_of(&px[i * 4 * kInputVec4s]);
        const scatterlut::NearLightParams p = scatterlut::near_light_params(q);
        ++all;
        if (p.light_below || !runtime.covers(p.T, p.g, p.r, p.S)) continue;
        sampled.push_back(i);
        exact.push_back(scatterlut::near_light_radiance_exact(q));
    }
    std::vector<ErrorStats> errors(methods.size());
    for (size_t m = 0; m < methods.size(); ++m)
        if (!methods[m].timed_only) errors[m] = relative_errors(passes.frame(methods[m]), sampled, exact);
    if (gl.glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "scatterlut_gpu_bench: OpenGL error in the near-light scene\n");
        return 1;
    }
    std::printf("\n## Near light: %d x %d pixels, %d rounds x %d frames per method; errors on the %zu of %zu sampled "
                "pixels (every %d-th) that the E3 table (%d x %d x %d) covers\n\n",
                opt.width, opt.height, opt.rounds, opt.frames, sampled.size(), all, opt.stride, table.axes[0].map.count,
                table.axes[1].map.count, table.axes[2].map.count);
    print_table(methods, round_ms, {"thin"}, errors, pixels, opt.rounds);
    return 0;
}

} // namespace gpu_bench
