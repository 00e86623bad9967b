// GPU per-pixel cost of the airlight: full-screen fragment passes through a surfaceless EGL
// context (Mesa llvmpipe where there is no GPU; tests/egl_context.hpp) of
//   snippet    the generated scatterlut_airlight.glsl (slut_airlight_radiance, texelFetch
//              path) on the default airlight table (AirlightPlan: 512 x 256, f32),
//   snippet_hw the same with SLUT_AIRLIGHT_HARDWARE_FILTER (one filtered fetch per sample),
//   sun2005    Sun et al. 2005's two-fetch form A0·[F(A1, v_far) − F(A1, γ/2)] on a plain
//              64 x 64 F(u, v) table (u in [0, 10], v in [0, π/2], linear axes, GL_LINEAR,
//              clamped), as in NVIDIA's SDK 10 Rain sample; F from slut_F_quadrature
//              (bench/shaders/sun2005.glsl),
//   closed     the closed form engines use (Macklin 2010) times e^{−σ_t D}:
//              slut_airlight_no_extinction_attenuated (kernels/slut_airlight.h) in float GLSL
//              with the builtin atan (bench/shaders/closed_form.glsl),
//   inputs     a pass that only reads the per-pixel inputs (the floor every method pays),
// each rendering the same per-pixel geometries (read from a storage buffer) into an R32F
// target. Rounds A B C … A B C … with the order rotated each round; per frame glDrawArrays +
// glFinish timed by the wall clock; per round each method's median frame; ratios per round
// against `closed` in the same round. Then one frame of each is read back and compared with
// airlight_radiance_exact (double, the same float inputs) on every `stride`-th pixel whose
// e^{−σ_t D} ≥ 1e-6.
//
// The geometry, a street seen by a viewer 1.7 m above the ground (90° horizontal field of
// view, the street 16 m wide, rays end on the ground or the walls, at most at 200 m): every
// 32 x 32 pixel tile has its own lamp, at D log-uniform in [1, 100] m in a direction uniform
// on the sphere, fog σ_s log-uniform in [0.004, 0.4] per m, σ_a = σ_s/20, I0 = 100 W/sr.
//
// Usage: scatterlut_gpu_bench [--width N] [--height N] [--frames N] [--rounds N] [--stride N]
//                             [--compare-snippet FILE]
// --compare-snippet adds a method "compare": FILE (another version of scatterlut_airlight.glsl,
// e.g. one generated before a change) the way `snippet` runs, for an A/B in the same rounds.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <random>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "egl_context.hpp"
#include "generate_airlight.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/io.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_airlight_rational.h"
}

namespace {

constexpr double kPi = 3.14159265358979323846;

// Plain F table (Sun et al. 2005; the Rain sample's layout).
constexpr int kFCount = 64;
constexpr double kFUMax = 10.0;

struct Options {
    int width = 1920, height = 1080, frames = 5, rounds = 7, stride = 4;
    std::string compare_snippet; // another scatterlut_airlight.glsl, run as method "compare"
};

bool parse_int(const char *text, int lo, int hi, int *out) {
    char *end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi) return false;
    *out = static_cast<int>(v);
    return true;
}

int usage_error(const std::string &what) {
    std::fprintf(stderr, "scatterlut_gpu_bench: %s\nusage: scatterlut_gpu_bench [--width 16..8192] "
                         "[--height 16..8192] [--frames 1..1000] [--rounds 1..1000] [--stride 1..1000000] "
                         "[--compare-snippet FILE]\n",
                 what.c_str());
    return 2;
}

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

const char *kVertex = R"glsl(#version 430
void main() { // one triangle over the whole viewport
    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));
    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);
}
)glsl";

const char *kFragmentHead = R"glsl(
layout(std430, binding = 1) readonly buffer PixelGeometry { vec4 geo[]; };
uniform int width_px;
layout(location = 0) out float radiance_out;
)glsl";

// main() for a method: `call` is an expression of ss, sa, i0, dist, sg, cg, len.
std::string fragment_main(const std::string &call) {
    return R"glsl(
void main() {
    ivec2 p = ivec2(gl_FragCoord.xy);
    int i = p.y * width_px + p.x;
    vec4 a = geo[2 * i];
    vec4 b = geo[2 * i + 1];
    float ss = a.x, sa = a.y, i0 = a.z, dist = a.w, sg = b.x, cg = b.y, len = b.z;
    radiance_out = )glsl" + call + R"glsl(;
}
)glsl";
}

struct Method {
    std::string name, what;
    GLuint program = 0;
    GLuint texture = 0; // bound to unit 0
};

std::string read_text(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return in ? s.str() : std::string();
}

double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

GLuint make_texture(const gpu_harness::Gl &gl, const std::vector<float> &texels, int width, int height) {
    GLuint texture = 0;
    gl.glGenTextures(1, &texture);
    gl.glBindTexture(GL_TEXTURE_2D, texture);
    gl.glPixelStorei(GL_UNPACK_ALIGNMENT, 1);
    gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, texels.data());
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_LINEAR);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_LINEAR);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_S, GL_CLAMP_TO_EDGE);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_WRAP_T, GL_CLAMP_TO_EDGE);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    return texture;
}

struct ErrorStats {
    double median = 0, p99 = 0, max = 0;
    size_t count = 0;
};

ErrorStats error_stats(std::vector<double> e) {
    ErrorStats st;
    st.count = e.size();
    if (e.empty()) return st;
    std::sort(e.begin(), e.end());
    st.median = e[e.size() / 2];
    st.p99 = e[static_cast<size_t>(0.99 * static_cast<double>(e.size() - 1))];
    st.max = e.back();
    return st;
}

} // namespace

int main(int argc, char **argv) {
    Options opt;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if (a == "--compare-snippet") {
            if (k + 1 >= argc) return usage_error("option " + a + " needs a file");
            opt.compare_snippet = argv[++k];
            continue;
        }
        int *target = nullptr;
        int lo = 1, hi = 1000;
        if (a == "--width") target = &opt.width, lo = 16, hi = 8192;
        else if (a == "--height") target = &opt.height, lo = 16, hi = 8192;
        else if (a == "--frames") target = &opt.frames;
        else if (a == "--rounds") target = &opt.rounds;
        else if (a == "--stride") target = &opt.stride, hi = 1000000;
        else return usage_error("unknown option '" + a + "'");
        if (k + 1 >= argc) return usage_error("option " + a + " needs a value");
        if (!parse_int(argv[++k], lo, hi, target))
            return usage_error("option " + a + ": expected an integer in [" + std::to_string(lo) + ", " +
                               std::to_string(hi) + "], got '" + argv[k] + "'");
    }

    std::string compare_text;
    if (!opt.compare_snippet.empty()) {
        compare_text = read_text(opt.compare_snippet);
        if (compare_text.empty()) return usage_error("--compare-snippet: cannot read '" + opt.compare_snippet + "'");
    }

    gpu_harness::GpuContext &context = gpu_harness::gpu();
    if (!context.ok) {
        std::fprintf(stderr, "scatterlut_gpu_bench: no OpenGL context: %s\n", context.why_not.c_str());
        return 1;
    }
    const gpu_harness::Gl &gl = context.gl;
    const char *threads = std::getenv("LP_NUM_THREADS");
    std::printf("renderer: %s (LP_NUM_THREADS=%s)\n", context.renderer.c_str(), threads ? threads : "unset");

    // The default airlight table, as `scatterlut generate` makes it (f32 storage).
    const scatterlut::AirlightPlan plan;
    scatterlut::Table table = scatterlut::make_airlight_table_layout(plan);
    {
        scatterlut::Device device("");
        table.values = scatterlut::integrate_airlight_ln_gs(device, table);
    }
    for (double &v : table.values) v = scatterlut::round_to_storage(v, plan.storage);
    const int u_count = table.axes[0].map.count, w_count = table.axes[1].map.count;
    const std::vector<float> ln_gs(table.values.begin(), table.values.end());

    // The plain F table of Sun et al. 2005 from the exact F.
    std::vector<float> f_texels(static_cast<size_t>(kFCount) * kFCount);
    for (int j = 0; j < kFCount; ++j)
        for (int i = 0; i < kFCount; ++i)
            f_texels[static_cast<size_t>(j) * kFCount + i] = static_cast<float>(
                slut_F_quadrature(kFUMax * i / (kFCount - 1), 0.5 * kPi * j / (kFCount - 1)));

    const std::string snippet_path = std::string(SLUT_SHADER_DIR) + "/scatterlut_airlight.glsl";
    const std::string snippet = read_text(snippet_path);
    if (snippet.empty()) {
        std::fprintf(stderr, "scatterlut_gpu_bench: cannot read %s\n", snippet_path.c_str());
        return 1;
    }
    // The baselines' GLSL, shared with examples/web/bench_airlight.mjs (bench/shaders/).
    std::string closed_glsl, sun_glsl;
    for (auto [text, name] : {std::pair{&closed_glsl, "closed_form.glsl"}, std::pair{&sun_glsl, "sun2005.glsl"}}) {
        const std::string path = std::string(SLUT_BENCH_SHADER_DIR) + "/" + name;
        *text = read_text(path);
        if (text->empty()) {
            std::fprintf(stderr, "scatterlut_gpu_bench: cannot read %s\n", path.c_str());
            return 1;
        }
    }
    const std::string table_uniforms = "layout(binding = 0) uniform sampler2D ln_gs_table;\n"
                                       "uniform float u_max, u_scale, w_min;\nuniform int u_count, w_count;\n";
    const std::string snippet_call = "slut_airlight_radiance(ln_gs_table, slut_airlight_table(u_max, u_scale, "
                                     "u_count, w_min, w_count), ss, sa, i0, dist, sg, cg, len)";
    const GLuint ln_gs_texture = make_texture(gl, ln_gs, u_count, w_count);
    // The fast tier's table (kernels/slut_airlight_rational.h), f32.
    const int rational_count = 64;
    std::vector<float> hn(static_cast<size_t>(rational_count) * rational_count);
    for (int j = 0; j < rational_count; ++j)
        for (int i = 0; i < rational_count; ++i)
            hn[static_cast<size_t>(j) * rational_count + i] = static_cast<float>(slut_airlight_rational_node(
                static_cast<double>(i) / (rational_count - 1), static_cast<double>(j) / (rational_count - 1), 1.0));
    const GLuint hn_texture = make_texture(gl, hn, rational_count, rational_count);
    const GLuint f_texture = make_texture(gl, f_texels, kFCount, kFCount);

    std::vector<Method> methods = {
        {"fast", "scatterlut_airlight.glsl, SLUT_TIER_FAST", 0, hn_texture},
        {"accurate", "scatterlut_airlight.glsl, SLUT_TIER_ACCURATE", 0, hn_texture},
        {"airlight_F", "scatterlut_airlight.glsl without a tier: the airlight_F table, texelFetch", 0, ln_gs_texture},
        {"sun2005", "Sun et al. 2005, 64² F table, two fetches", 0, f_texture},
        {"closed", "closed form × e^{−σ_t D} (Macklin 2010)", 0, 0},
        {"inputs", "reads the inputs only", 0, 0},
    };
    if (!opt.compare_snippet.empty()) {
        methods.insert(methods.begin() + 2, Method{"compare", opt.compare_snippet + ", texelFetch", 0, ln_gs_texture});
    }
    for (Method &m : methods) {
        std::string fs = "#version 430\n";
        if (m.name == "fast") fs += "#define SLUT_TIER_FAST\n";
        if (m.name == "accurate") fs += "#define SLUT_TIER_ACCURATE\n";
        fs += kFragmentHead;
        if (m.name == "closed") fs += closed_glsl + fragment_main("closed_form_attenuated(ss, sa, i0, dist, sg, cg, len)");
        else if (m.name == "sun2005") fs += sun_glsl + fragment_main("sun2005(ss, sa, i0, dist, sg, cg, len)");
        else if (m.name == "inputs") fs += fragment_main("ss + sa + i0 + dist + sg + cg + len");
        else if (m.name == "fast" || m.name == "accurate")
            fs += "layout(binding = 0) uniform sampler2D hn_table;\nuniform int m_count, t_count;\n" + snippet +
                  fragment_main("slut_airlight_radiance(hn_table, slut_airlight_table(m_count, t_count), ss, sa, i0, "
                                "dist, sg, cg, len)");
        else fs += table_uniforms + (m.name == "compare" ? compare_text : snippet) + fragment_main(snippet_call);
        const std::string error = gpu_harness::build_program_stages(
            gl, {{GL_VERTEX_SHADER, kVertex}, {GL_FRAGMENT_SHADER, fs}}, &m.program);
        if (!error.empty()) {
            std::fprintf(stderr, "scatterlut_gpu_bench: method %s: %s\n", m.name.c_str(), error.c_str());
            return 1;
        }
        gl.glUseProgram(m.program);
        auto set_f = [&](const char *name, double v) {
            const GLint loc = gl.glGetUniformLocation(m.program, name);
            if (loc >= 0) gl.glUniform1f(loc, static_cast<float>(v));
        };
        auto set_i = [&](const char *name, int v) {
            const GLint loc = gl.glGetUniformLocation(m.program, name);
            if (loc >= 0) gl.glUniform1i(loc, v);
        };
        set_i("width_px", opt.width);
        set_f("u_max", plan.u_max);
        set_f("u_scale", plan.u_scale);
        set_f("w_min", plan.w_min);
        set_i("u_count", u_count);
        set_i("w_count", w_count);
        set_i("m_count", rational_count);
        set_i("t_count", rational_count);
        set_f("f_u_max", kFUMax);
    }

    // Scene, target, and the empty vertex array the full-screen triangle needs.
    const size_t pixels = static_cast<size_t>(opt.width) * opt.height;
    const std::vector<float> geo = make_scene(opt.width, opt.height);
    GLuint geo_buffer = 0, vao = 0, fbo = 0, target = 0;
    gl.glGenBuffers(1, &geo_buffer);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, geo_buffer);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(geo.size() * sizeof(float)), geo.data(),
                    GL_STATIC_DRAW);
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, geo_buffer);
    gl.glGenVertexArrays(1, &vao);
    gl.glBindVertexArray(vao);
    gl.glGenTextures(1, &target);
    gl.glBindTexture(GL_TEXTURE_2D, target);
    gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, opt.width, opt.height, 0, GL_RED, GL_FLOAT, nullptr);
    gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
    gl.glGenFramebuffers(1, &fbo);
    gl.glBindFramebuffer(GL_FRAMEBUFFER, fbo);
    gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target, 0);
    if (gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) != GL_FRAMEBUFFER_COMPLETE) {
        std::fprintf(stderr, "scatterlut_gpu_bench: the R32F render target is not complete\n");
        return 1;
    }
    gl.glViewport(0, 0, opt.width, opt.height);

    auto draw = [&](const Method &m) {
        gl.glUseProgram(m.program);
        gl.glActiveTexture(GL_TEXTURE0);
        gl.glBindTexture(GL_TEXTURE_2D, m.texture);
        gl.glDrawArrays(GL_TRIANGLES, 0, 3);
        gl.glFinish();
    };
    for (const Method &m : methods) draw(m); // untimed: llvmpipe compiles the shader at first use

    // Interleaved rounds: per round, each method's median frame (ms).
    const size_t nm = methods.size();
    std::vector<std::vector<double>> round_ms(nm);
    for (int r = 0; r < opt.rounds; ++r) {
        for (size_t k = 0; k < nm; ++k) {
            const size_t m = (k + static_cast<size_t>(r)) % nm;
            std::vector<double> frame_ms;
            for (int f = 0; f < opt.frames; ++f) {
                const auto t0 = std::chrono::steady_clock::now();
                draw(methods[m]);
                frame_ms.push_back(std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
            }
            round_ms[m].push_back(median_of(frame_ms));
        }
    }
    if (gl.glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "scatterlut_gpu_bench: OpenGL error during the timed frames\n");
        return 1;
    }

    // One frame of each, read back, against the exact radiance on the sampled pixels.
    std::vector<size_t> sampled;
    const scatterlut::AirlightTable airlight(table); // which path each sampled pixel takes
    size_t one_panel = 0, theta_fallback = 0, large_u = 0, small_w = 0, sun_clamped = 0;
    for (size_t i = 0; i < pixels; i += static_cast<size_t>(opt.stride)) {
        const float *g = &geo[i * 8];
        const double sigma_t = static_cast<double>(g[0]) + g[1];
        if (std::exp(-sigma_t * g[3]) >= 1e-6) sampled.push_back(i);
    }
    std::vector<double> exact(sampled.size());
    const auto e0 = std::chrono::steady_clock::now();
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
        const slut_airlight_geometry geometry = slut_airlight_setup(g[0], g[1], g[2], g[3], g[4], g[5], g[6]);
        if (geometry.kind == 0 && slut_airlight_theta_fits_one_panel(geometry)) {
            ++one_panel;
        } else if (geometry.kind == 0) { // two table samples; the θ-integral where they cancel
            const double gs2 = airlight.scaled_tail(geometry.u, geometry.w2, geometry.a2);
            const double gs1 = geometry.w1 > 0.0 ? airlight.scaled_tail(geometry.u, geometry.w1, geometry.a1) : 0.0;
            const double viewer_term = geometry.w2 / geometry.sin_gamma * gs2;
            const double far_term =
                geometry.w1 > 0.0 ? geometry.far_attenuation * geometry.w1 / geometry.sin_gamma * gs1 : 0.0;
            if (far_term > 0.5 * viewer_term) ++theta_fallback;
            if (geometry.u > airlight.u_max()) ++large_u;
            if (geometry.w1 < airlight.w_min()) ++small_w;
        }
        if ((static_cast<double>(g[0]) + g[1]) * g[3] * g[4] > kFUMax) ++sun_clamped;
    }
    const double exact_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - e0).count();

    const size_t closed = static_cast<size_t>(
        std::find_if(methods.begin(), methods.end(), [](const Method &m) { return m.name == "closed"; }) -
        methods.begin());
    std::printf("%d x %d pixels, %d rounds x %d frames per method; errors on %zu pixels (every %d-th with "
                "e^{-sigma_t D} >= 1e-6; exact radiance %.1f s); of those %.1f %% take the snippet's one-panel "
                "path (no fetch), %.1f %% the two-sample path and then the θ-integral (the ends cancel), %.1f %% sample "
                "beyond u_max, %.1f %% below w_min; %.1f %% have u > %g (the F table clamps)\n\n",
                opt.width, opt.height, opt.rounds, opt.frames, sampled.size(), opt.stride, exact_s,
                100.0 * one_panel / std::max<size_t>(sampled.size(), 1),
                100.0 * theta_fallback / std::max<size_t>(sampled.size(), 1),
                100.0 * large_u / std::max<size_t>(sampled.size(), 1),
                100.0 * small_w / std::max<size_t>(sampled.size(), 1),
                100.0 * sun_clamped / std::max<size_t>(sampled.size(), 1), kFUMax);
    std::printf("| method | ms per frame (median [min-max] of rounds) | ns per pixel | net of `inputs`, ns per pixel "
                "| / closed (median [min-max] of per-round ratios) | / sun2005 (the same) | median rel. error | p99 "
                "| max |\n|---|---|---|---|---|---|---|---|---|\n");
    const size_t sun = static_cast<size_t>(
        std::find_if(methods.begin(), methods.end(), [](const Method &m) { return m.name == "sun2005"; }) -
        methods.begin());
    // Per round, method m's median frame over `base`'s: "median [min-max]" of the rounds.
    auto ratio_text = [&](size_t m, size_t base) {
        std::vector<double> ratios;
        for (int r = 0; r < opt.rounds; ++r) ratios.push_back(round_ms[m][r] / round_ms[base][r]);
        char buf[64];
        std::snprintf(buf, sizeof buf, "%.2f [%.2f-%.2f]", median_of(ratios),
                      *std::min_element(ratios.begin(), ratios.end()), *std::max_element(ratios.begin(), ratios.end()));
        return std::string(buf);
    };
    const size_t inputs = nm - 1;
    const double inputs_ms = median_of(round_ms[inputs]);
    std::vector<float> image(pixels);
    for (size_t m = 0; m < nm; ++m) {
        const double ms = median_of(round_ms[m]);
        const double ns_per_pixel = ms * 1e6 / static_cast<double>(pixels);
        const double net = (ms - inputs_ms) * 1e6 / static_cast<double>(pixels);
        std::string errors = "– | – | –";
        if (m != inputs) {
            draw(methods[m]);
            gl.glReadPixels(0, 0, opt.width, opt.height, GL_RED, GL_FLOAT, image.data());
            std::vector<double> e;
            for (size_t k = 0; k < sampled.size(); ++k) {
                const double got = image[sampled[k]], want = exact[k];
                e.push_back(want == 0.0 ? (got == 0.0 ? 0.0 : HUGE_VAL)
                                        : (std::isfinite(got) ? std::fabs(got - want) / want : HUGE_VAL));
            }
            const ErrorStats st = error_stats(e);
            char buf[128];
            std::snprintf(buf, sizeof buf, "%.2g | %.2g | %.2g", st.median, st.p99, st.max);
            errors = buf;
        }
        std::printf("| %s (%s) | %.2f [%.2f-%.2f] | %.2f | %.2f | %s | %s | %s |\n", methods[m].name.c_str(),
                    methods[m].what.c_str(), ms, *std::min_element(round_ms[m].begin(), round_ms[m].end()),
                    *std::max_element(round_ms[m].begin(), round_ms[m].end()), ns_per_pixel, net,
                    ratio_text(m, closed).c_str(), ratio_text(m, sun).c_str(), errors.c_str());
    }
    if (gl.glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "scatterlut_gpu_bench: OpenGL error during the read-back\n");
        return 1;
    }
    return 0;
}
