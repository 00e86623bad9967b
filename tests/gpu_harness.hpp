// The GPU test harness shared by the shader tests (tests/shaders/: the airlight and near-light
// snippets, isotropic and Henyey-Greenstein; what the airlight tests share beyond this is
// shaders/airlight_gpu_test.hpp, the near-light ones shaders/nearlight_gpu_test.hpp): tool runs (glslang, spirv-cross) in a scratch
// directory, and one surfaceless EGL / OpenGL 4.3 core context (Mesa llvmpipe where there
// is no GPU) that runs a compute shader over a buffer of queries with one R32F texture.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "egl_context.hpp"

#ifndef SLUT_GLSLANG_VALIDATOR
#define SLUT_GLSLANG_VALIDATOR ""
#endif
#ifndef SLUT_SPIRV_CROSS
#define SLUT_SPIRV_CROSS ""
#endif
#ifndef SLUT_REQUIRE_SHADER_TESTS
#define SLUT_REQUIRE_SHADER_TESTS 0
#endif

namespace gpu_harness {

const std::string kShaderDir = std::string(SLUT_SHADER_DIR) + "/"; // generated at build time
const std::string kGlslang = SLUT_GLSLANG_VALIDATOR;
const std::string kSpirvCross = SLUT_SPIRV_CROSS;

// A missing tool or display: skip, or fail where the build asked for the shader tests.
#define SLUT_SKIP_OR_FAIL(message)                                                         \
    do {                                                                                   \
        if (SLUT_REQUIRE_SHADER_TESTS) FAIL() << (message);                                \
        GTEST_SKIP() << "skipped: " << (message);                                          \
    } while (0)

inline std::string read_text(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    if (!in) throw std::runtime_error("cannot read " + path);
    std::ostringstream s;
    s << in.rdbuf();
    return s.str();
}

inline void write_text(const std::string &path, const std::string &text) {
    std::ofstream out(path, std::ios::binary);
    out << text;
    if (!out) throw std::runtime_error("cannot write " + path);
}

// The part of a generated snippet outside its language prelude (cmake/assemble_shaders.cmake
// writes the markers): identical in the GLSL and the HLSL file.
inline const char *kBodyBegin = "// ==== BEGIN SHARED BODY";
inline const char *kBodyEnd = "// ==== END SHARED BODY ====";

inline std::string shared_body(const std::string &text) {
    const size_t b = text.find(kBodyBegin), e = text.find(kBodyEnd);
    if (b == std::string::npos || e == std::string::npos || e < b) return "";
    return text.substr(b, e - b);
}

// A scratch directory for this process (tool inputs and outputs), removed at exit unless
// SLUT_KEEP_SHADER_SCRATCH is set (to inspect what glslang / spirv-cross were given).
struct ScratchDir {
    std::string path;
    ScratchDir() {
        std::string templ = (std::getenv("TMPDIR") ? std::getenv("TMPDIR") : "/tmp");
        templ += "/slut_shaders_XXXXXX";
        std::vector<char> buf(templ.begin(), templ.end());
        buf.push_back('\0');
        if (!mkdtemp(buf.data())) throw std::runtime_error("mkdtemp failed in " + templ);
        path = buf.data();
    }
    ~ScratchDir() {
        std::error_code ec;
        if (!std::getenv("SLUT_KEEP_SHADER_SCRATCH")) std::filesystem::remove_all(path, ec);
    }
};

inline const std::string &scratch_dir() {
    static const ScratchDir dir;
    return dir.path;
}

// Runs a command, returns its exit status; its output (stdout + stderr) in *output.
inline int run_command(const std::string &command, std::string *output) {
    FILE *pipe = popen((command + " 2>&1").c_str(), "r");
    if (!pipe) return -1;
    std::string text;
    char buf[4096];
    size_t n;
    while ((n = fread(buf, 1, sizeof buf, pipe)) > 0) text.append(buf, n);
    const int status = pclose(pipe);
    if (output) *output = text;
    return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string quoted(const std::string &s) { return "'" + s + "'"; }


// glslangValidator on a source written to the scratch directory; "" on success, else the
// command and its output.
inline std::string glslang(const std::string &file_name, const std::string &source, const std::string &options) {
    const std::string path = scratch_dir() + "/" + file_name;
    write_text(path, source);
    const std::string command = quoted(kGlslang) + " " + options + " " + quoted(path);
    std::string output;
    const int rc = run_command(command, &output);
    return rc == 0 ? "" : command + "\n" + output;
}

// An HLSL compute shader -> SPIR-V (glslang) -> GLSL 4.30 (spirv-cross), files named by
// `tag` in the scratch directory: what lets the HLSL run on the OpenGL context. Empty
// string and *error on failure.
inline std::string hlsl_compute_to_glsl(const std::string &tag, const std::string &hlsl, std::string *error) {
    const std::string spv = scratch_dir() + "/run_" + tag + ".spv";
    const std::string glsl = scratch_dir() + "/run_" + tag + ".comp";
    *error = glslang("run_" + tag + ".hlsl", hlsl, "-D -V -e main -S comp -o " + quoted(spv));
    if (!error->empty()) return "";
    std::string output;
    const std::string command = quoted(kSpirvCross) + " --version 430 --no-es " + quoted(spv) + " --output " + quoted(glsl);
    if (run_command(command, &output) != 0) {
        *error = command + "\n" + output;
        return "";
    }
    return read_text(glsl);
}

// A compute shader around `snippet` that evaluates one query per invocation, in GLSL 4.30 or
// HLSL: `body` defines float test_eval(int i) (written once for both languages with the
// snippets' own prelude macros: SLUT_FLOAT3, SLUT_TEX_ARG(slut_test_table)); `params` the
// fields of the uniform block (n_queries among them); `defines` goes first. Bindings: 0 the
// table (a 2-D texture, or 3-D with three_d), 1 the queries q[], 2 the results r[], 3 the
// parameters (std140).
inline std::string glsl_compute_source(const std::string &snippet, const std::string &params,
                                       const std::string &body, const std::string &defines, bool three_d) {
    return "#version 430\n" + defines + "\nlayout(local_size_x = 64) in;\nlayout(binding = 0) uniform " +
           (three_d ? "sampler3D" : "sampler2D") + R"glsl( slut_test_table;
layout(std430, binding = 1) readonly buffer SlutTestQueries { float q[]; };
layout(std430, binding = 2) writeonly buffer SlutTestResults { float r[]; };
layout(std140, binding = 3) uniform SlutTestParams {
)glsl" + params + "\n};\n" + snippet + body + R"glsl(
void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i < n_queries) r[i] = test_eval(i);
}
)glsl";
}

inline std::string hlsl_compute_source(const std::string &snippet, const std::string &params,
                                       const std::string &body, const std::string &defines, bool three_d) {
    return defines + "\n[[vk::binding(0)]] " + (three_d ? "Texture3D" : "Texture2D") + R"hlsl(<float> slut_test_table;
[[vk::binding(4)]] SamplerState slut_test_table_sampler;
[[vk::binding(1)]] StructuredBuffer<float> q;
[[vk::binding(2)]] RWStructuredBuffer<float> r;
[[vk::binding(3)]] cbuffer SlutTestParams {
)hlsl" + params + "\n};\n" + snippet + body + R"hlsl(
[numthreads(64, 1, 1)]
void main(uint3 id : SV_DispatchThreadID) {
    int i = int(id.x);
    if (i < n_queries) r[i] = test_eval(i);
}
)hlsl";
}

// glslang on a snippet's compute shaders (glsl_source / hlsl_source of the hardware-filter flag),
// with and without the hardware filter: GLSL for OpenGL and for Vulkan (SPIR-V), HLSL to SPIR-V.
// Files named by `tag` in the scratch directory.
template <class GlslSource, class HlslSource>
void expect_compute_shaders_compile(const std::string &tag, const GlslSource &glsl_source,
                                    const HlslSource &hlsl_source) {
    for (bool hw : {false, true}) {
        SCOPED_TRACE(hw ? "hardware filter" : "texel-fetch path");
        const std::string name = tag + (hw ? "_compute_hw" : "_compute");
        EXPECT_EQ(glslang(name + ".comp", glsl_source(hw), ""), "");
        EXPECT_EQ(glslang(name + "_vk.comp", glsl_source(hw), "-V -o " + quoted(scratch_dir() + "/" + name + "_vk.spv")), "");
        EXPECT_EQ(glslang(name + ".hlsl", hlsl_source(hw),
                          "-D -V -e main -S comp -o " + quoted(scratch_dir() + "/" + name + "_hlsl.spv")),
                  "");
    }
}

// glslang on an engine's shaders around a snippet (compile checks): a GLSL fragment shader, a
// GLSL ES 3.00 one and an HLSL pixel shader (to SPIR-V). Files named by `tag`.
inline void expect_engine_shaders_compile(const std::string &tag, const std::string &glsl_fragment,
                                          const std::string &essl_fragment, const std::string &hlsl_pixel) {
    EXPECT_EQ(glslang(tag + "_fragment.frag", glsl_fragment, ""), "");
    EXPECT_EQ(glslang(tag + "_fragment_es.frag", essl_fragment, ""), "");
    EXPECT_EQ(glslang(tag + "_pixel.hlsl", hlsl_pixel, "-D -V -e main -S frag -o " + quoted(scratch_dir() + "/" + tag + "_pixel.spv")),
              "");
}

// relative error; infinities must match, NaN never does, 0 only by 0.
inline double rel_err(double got, double want) {
    if (std::isinf(want) || std::isinf(got)) return (got == want) ? 0.0 : std::numeric_limits<double>::infinity();
    if (std::isnan(got)) return std::numeric_limits<double>::infinity();
    if (want == 0.0) return got == 0.0 ? 0.0 : std::numeric_limits<double>::infinity();
    return std::fabs(got - want) / std::fabs(want);
}

struct Stats {
    double max = 0, p99 = 0, median = 0;
    double max_ratio = 0; // worst error / tolerance
    size_t count = 0, worst = 0, worst_ratio = 0;
};

// Relative errors of got[i] against reference[i] for i in `indices`, and their ratio to a
// per-query tolerance(i). References below kFloor (values float cannot hold to its full
// precision) are compared absolutely against kFloor.
constexpr double kFloor = 1e-30;

template <class Tolerance>
Stats error_stats(const std::vector<float> &got, const std::vector<double> &reference,
                  const std::vector<size_t> &indices, const Tolerance &tolerance) {
    std::vector<double> errs;
    Stats st;
    for (size_t i : indices) {
        double e = rel_err(got[i], reference[i]);
        if (std::isfinite(reference[i]) && std::fabs(reference[i]) < kFloor && std::isfinite(got[i]))
            e = std::fabs(got[i] - reference[i]) / kFloor;
        errs.push_back(e);
        if (e >= st.max) {
            st.max = e;
            st.worst = i;
        }
        const double ratio = e / tolerance(i);
        if (ratio >= st.max_ratio) {
            st.max_ratio = ratio;
            st.worst_ratio = i;
        }
    }
    st.count = errs.size();
    if (errs.empty()) return st;
    std::sort(errs.begin(), errs.end());
    st.p99 = errs[static_cast<size_t>(0.99 * static_cast<double>(errs.size() - 1))];
    st.median = errs[errs.size() / 2];
    return st;
}

#if SLUT_HAVE_EGL

// Runs a compute shader over n_items (64 per group): binding 0 a width x height R32F
// texture (width x height x depth for depth > 0) with GL_LINEAR filtering and CLAMP_TO_EDGE (what the hardware-filter path needs;
// the texelFetch path ignores both), 1 `inputs`, 2 the n_items results, 3 `params` (a
// uniform block). The results, or an error in *error.
inline std::vector<float> run_compute(const std::string &source, const std::vector<float> &texels, int width, int height,
                               int depth, const std::vector<float> &inputs, size_t n_items, const void *params,
                               size_t params_bytes, std::string *error) {
    const Gl &gl = gpu().gl;
    GLuint program = 0;
    *error = build_program(gl, source, &program);
    if (!error->empty()) return {};
    gl.glUseProgram(program);
    // Every sampler uniform (spirv-cross names its combined samplers itself) on unit 0.
    GLint n_uniforms = 0;
    gl.glGetProgramiv(program, GL_ACTIVE_UNIFORMS, &n_uniforms);
    for (GLint i = 0; i < n_uniforms; ++i) {
        char name[256];
        GLint size = 0;
        GLenum type = 0;
        gl.glGetActiveUniform(program, static_cast<GLuint>(i), sizeof name, nullptr, &size, &type, name);
        if (type == GL_SAMPLER_2D || type == GL_SAMPLER_3D) gl.glUniform1i(gl.glGetUniformLocation(program, name), 0);
    }
    gl.glActiveTexture(GL_TEXTURE0);
    const GLuint texture = make_r32f_texture(gl, texels, width, height, depth);

    GLuint buffers[3];
    gl.glGenBuffers(3, buffers);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[0]);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(inputs.size() * sizeof(float)), inputs.data(),
                    GL_STATIC_DRAW);
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, buffers[0]);
    std::vector<float> results(n_items, std::numeric_limits<float>::quiet_NaN());
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
    gl.glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(results.size() * sizeof(float)),
                    results.data(), GL_DYNAMIC_READ);
    gl.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 2, buffers[1]);
    gl.glBindBuffer(GL_UNIFORM_BUFFER, buffers[2]);
    gl.glBufferData(GL_UNIFORM_BUFFER, static_cast<GLsizeiptr>(params_bytes), params, GL_STATIC_DRAW);
    gl.glBindBufferBase(GL_UNIFORM_BUFFER, 3, buffers[2]);

    gl.glDispatchCompute(static_cast<GLuint>((n_items + 63) / 64), 1, 1);
    gl.glMemoryBarrier(GL_BUFFER_UPDATE_BARRIER_BIT);
    gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, buffers[1]);
    gl.glGetBufferSubData(GL_SHADER_STORAGE_BUFFER, 0, static_cast<GLsizeiptr>(results.size() * sizeof(float)),
                          results.data());
    gl.glFinish();
    const GLenum err = gl.glGetError();
    if (err != GL_NO_ERROR) *error = "OpenGL error 0x" + GpuContext::hex(static_cast<EGLint>(err));
    gl.glDeleteBuffers(3, buffers);
    gl.glDeleteTextures(1, &texture);
    gl.glUseProgram(0);
    gl.glDeleteProgram(program);
    return results;
}

// The hardware filter's weight error: GL_LINEAR on a 2x1 ramp texture [0, 1] at texel
// coordinate f between the two centres must return f; returns max |result - f| over 4096
// fractions of a golden-ratio sequence (every mantissa bit in use): ~6e-8 with float
// weights, up to 1/512 with 8-bit fixed-point weights; negative on error.
inline double hardware_filter_weight_error() {
    static const double measured = [] {
        const std::string source = R"glsl(#version 430
layout(local_size_x = 64) in;
layout(binding = 0) uniform sampler2D ramp;
layout(std430, binding = 1) readonly buffer Fractions { float f[]; };
layout(std430, binding = 2) writeonly buffer Results { float r[]; };
layout(std140, binding = 3) uniform Params { int n; };
void main() {
    int i = int(gl_GlobalInvocationID.x);
    if (i < n) r[i] = textureLod(ramp, vec2((f[i] + 0.5) / 2.0, 0.5), 0.0).r;
}
)glsl";
        const int n = 4096;
        std::vector<float> f(n);
        for (int i = 0; i < n; ++i) f[i] = static_cast<float>(std::fmod(0.5 + i * 0.6180339887498949, 1.0)); // all 24 bits used
        const int32_t params[4] = {n, 0, 0, 0};
        std::string error;
        const std::vector<float> r = run_compute(source, {0.0f, 1.0f}, 2, 1, 0, f, n, params, sizeof params, &error);
        if (!error.empty()) return -1.0;
        double worst = 0;
        for (int i = 0; i < n; ++i) worst = std::max(worst, std::fabs(static_cast<double>(r[i]) - f[i]));
        return worst;
    }();
    return measured;
}

#endif // SLUT_HAVE_EGL

// The fixture of the tests that run shaders: skips (or fails, SCATTERLUT_REQUIRE_SHADER_TESTS)
// without a GPU context; records and prints the renderer.
class GpuTest : public ::testing::Test {
protected:
    void SetUp() override {
#if SLUT_HAVE_EGL
        if (!gpu().ok) SLUT_SKIP_OR_FAIL("no GPU context: " + gpu().why_not);
        RecordProperty("renderer", gpu().renderer);
        std::printf("[ renderer ] %s\n", gpu().renderer.c_str());
#else
        SLUT_SKIP_OR_FAIL("built without EGL/OpenGL headers and libraries (Debian: libegl-dev, libgl-dev)");
#endif
    }
};

} // namespace gpu_harness
