// The GPU per-pixel bench's harness (scatterlut_gpu_bench: bench_gpu_pixel.cpp, the airlight
// scene bench_gpu_airlight.cpp, the near-light scene bench_gpu_nearlight.cpp): full-screen
// fragment passes through a surfaceless EGL / OpenGL 4.3 context (tests/egl_context.hpp;
// Mesa llvmpipe without a GPU), one per method, over per-pixel inputs read from a storage
// buffer, into an R32F target. Timing: rounds of every method with the order rotated each
// round, `frames` frames each (glDrawArrays + glFinish, wall clock); per round each method's
// median frame; every cost is printed as ratios to baselines measured in the same rounds.
// Errors: one frame of each read back and compared per pixel with the exact radiance (double
// quadrature) on the scene's sampled pixels.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include "egl_context.hpp"

namespace gpu_bench {

struct Options {
    int width = 1920, height = 1080, frames = 5, rounds = 7, stride = 4;
    std::string compare_snippet; // another scatterlut_airlight.glsl, run as method "compare"
    bool airlight = true, nearlight = true;
};

inline std::string read_text(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return in ? s.str() : std::string();
}

inline double median_of(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    const size_t n = v.size();
    return n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

// One method: a fragment program over the scene's inputs and the texture it samples (unit 0).
struct Method {
    std::string name, what;
    std::string fragment; // its fragment shader's source
    GLenum texture_target = GL_TEXTURE_2D;
    GLuint texture = 0;
    bool timed_only = false; // no error (the inputs-only pass)
    GLuint program = 0;
};

// A fragment shader: `code` (defines, snippets, uniforms), then main() reading the pixel's
// `vec4s` inputs into in0, in1, … and writing `call` (an expression of them).
inline std::string fragment_source(const std::string &code, int vec4s, const std::string &call) {
    std::string s = "#version 430\nlayout(std430, binding = 1) readonly buffer PixelInputs { vec4 px[]; };\n"
                    "uniform int width_px;\nlayout(location = 0) out float radiance_out;\n" +
                    code + "\nvoid main() {\n    ivec2 p = ivec2(gl_FragCoord.xy);\n    int i = p.y * width_px + p.x;\n";
    for (int k = 0; k < vec4s; ++k)
        s += "    vec4 in" + std::to_string(k) + " = px[" + std::to_string(vec4s) + " * i + " + std::to_string(k) + "];\n";
    return s + "    radiance_out = " + call + ";\n}\n";
}

// The full-screen passes over one scene's inputs (vec4s floats × 4 per pixel).
class Passes {
public:
    Passes(const gpu_harness::Gl &gl, int width, int height, const std::vector<float> &inputs) : gl_(gl), w_(width), h_(height) {
        gl.glGenBuffers(1, &inputs_);
        gl.glBindBuffer(GL_SHADER_STORAGE_BUFFER, inputs_);
        gl.glBufferData(GL_SHADER_STORAGE_BUFFER, static_cast<GLsizeiptr>(inputs.size() * sizeof(float)), inputs.data(),
                        GL_STATIC_DRAW);
        gl.glGenVertexArrays(1, &vao_);
        gl.glGenTextures(1, &target_);
        gl.glBindTexture(GL_TEXTURE_2D, target_);
        gl.glTexImage2D(GL_TEXTURE_2D, 0, GL_R32F, width, height, 0, GL_RED, GL_FLOAT, nullptr);
        gl.glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAX_LEVEL, 0);
        gl.glGenFramebuffers(1, &fbo_);
        gl.glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        gl.glFramebufferTexture2D(GL_FRAMEBUFFER, GL_COLOR_ATTACHMENT0, GL_TEXTURE_2D, target_, 0);
        complete_ = gl.glCheckFramebufferStatus(GL_FRAMEBUFFER) == GL_FRAMEBUFFER_COMPLETE;
    }
    ~Passes() {
        gl_.glDeleteFramebuffers(1, &fbo_);
        gl_.glDeleteTextures(1, &target_);
        gl_.glDeleteVertexArrays(1, &vao_);
        gl_.glDeleteBuffers(1, &inputs_);
    }
    Passes(const Passes &) = delete;
    Passes &operator=(const Passes &) = delete;
    bool complete() const { return complete_; }

    // Builds every method's program; "" or the first error.
    std::string build(std::vector<Method> &methods) const {
        static const char *vertex = "#version 430\nvoid main() { // one triangle over the whole viewport\n"
                                    "    vec2 p = vec2(float((gl_VertexID << 1) & 2), float(gl_VertexID & 2));\n"
                                    "    gl_Position = vec4(2.0 * p - 1.0, 0.0, 1.0);\n}\n";
        for (Method &m : methods) {
            const std::string error = gpu_harness::build_program_stages(
                gl_, {{GL_VERTEX_SHADER, vertex}, {GL_FRAGMENT_SHADER, m.fragment}}, &m.program);
            if (!error.empty()) return "method " + m.name + ": " + error;
            gl_.glUseProgram(m.program);
            const GLint loc = gl_.glGetUniformLocation(m.program, "width_px");
            if (loc >= 0) gl_.glUniform1i(loc, w_);
        }
        return "";
    }

    void draw(const Method &m) const {
        gl_.glBindFramebuffer(GL_FRAMEBUFFER, fbo_);
        gl_.glViewport(0, 0, w_, h_);
        gl_.glBindBufferBase(GL_SHADER_STORAGE_BUFFER, 1, inputs_);
        gl_.glBindVertexArray(vao_);
        gl_.glUseProgram(m.program);
        gl_.glActiveTexture(GL_TEXTURE0);
        gl_.glBindTexture(m.texture_target, m.texture);
        gl_.glDrawArrays(GL_TRIANGLES, 0, 3);
        gl_.glFinish();
    }

    std::vector<float> frame(const Method &m) const {
        draw(m);
        std::vector<float> image(static_cast<size_t>(w_) * h_);
        gl_.glReadPixels(0, 0, w_, h_, GL_RED, GL_FLOAT, image.data());
        return image;
    }

    // Per method, its median frame (ms) of each round; rounds rotate the order.
    std::vector<std::vector<double>> time_rounds(const std::vector<Method> &methods, const Options &opt) const {
        for (const Method &m : methods) draw(m); // untimed: llvmpipe compiles a shader at first use
        const size_t nm = methods.size();
        std::vector<std::vector<double>> round_ms(nm);
        for (int r = 0; r < opt.rounds; ++r)
            for (size_t k = 0; k < nm; ++k) {
                const size_t m = (k + static_cast<size_t>(r)) % nm;
                std::vector<double> frame_ms;
                for (int f = 0; f < opt.frames; ++f) {
                    const auto t0 = std::chrono::steady_clock::now();
                    draw(methods[m]);
                    frame_ms.push_back(
                        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
                }
                round_ms[m].push_back(median_of(frame_ms));
            }
        return round_ms;
    }

private:
    const gpu_harness::Gl &gl_;
    int w_, h_;
    GLuint inputs_ = 0, vao_ = 0, target_ = 0, fbo_ = 0;
    bool complete_ = false;
};

struct ErrorStats {
    double median = 0, p99 = 0, max = 0;
    size_t count = 0;
};

// Relative errors of `image` at `pixels` against `exact` (a non-finite result, or one that is
// nonzero where the exact value is 0, counts as +∞).
inline ErrorStats relative_errors(const std::vector<float> &image, const std::vector<size_t> &pixels,
                                  const std::vector<double> &exact) {
    std::vector<double> e;
    for (size_t k = 0; k < pixels.size(); ++k) {
        const double got = image[pixels[k]], want = exact[k];
        e.push_back(want == 0.0 ? (got == 0.0 ? 0.0 : HUGE_VAL)
                                : (std::isfinite(got) && got >= 0.0 ? std::fabs(got - want) / want : HUGE_VAL));
    }
    ErrorStats st;
    st.count = e.size();
    if (e.empty()) return st;
    std::sort(e.begin(), e.end());
    st.median = e[e.size() / 2];
    st.p99 = e[static_cast<size_t>(0.99 * static_cast<double>(e.size() - 1))];
    st.max = e.back();
    return st;
}

// Index of the method called `name` (methods.size() if none).
inline size_t index_of(const std::vector<Method> &methods, const std::string &name) {
    return static_cast<size_t>(std::find_if(methods.begin(), methods.end(),
                                            [&](const Method &m) { return m.name == name; }) -
                               methods.begin());
}

// The results table: per method its frame (median [min-max] of rounds), ns per pixel, net of
// the method `inputs`, the per-round ratios to each baseline (median [min-max]) and the
// errors (errors[m]; ignored for timed_only methods).
inline void print_table(const std::vector<Method> &methods, const std::vector<std::vector<double>> &round_ms,
                        const std::vector<std::string> &baselines, const std::vector<ErrorStats> &errors,
                        size_t pixels, int rounds) {
    std::printf("| method | ms per frame (median [min-max] of rounds) | ns per pixel | net of `inputs`, ns per pixel");
    for (const std::string &b : baselines) std::printf(" | / %s (median [min-max] of per-round ratios)", b.c_str());
    std::printf(" | median rel. error | p99 | max |\n|---|---|---|---");
    for (size_t b = 0; b < baselines.size(); ++b) std::printf("|---");
    std::printf("|---|---|---|\n");
    const size_t inputs = index_of(methods, "inputs");
    const double inputs_ms = inputs < methods.size() ? median_of(round_ms[inputs]) : 0.0;
    for (size_t m = 0; m < methods.size(); ++m) {
        const double ms = median_of(round_ms[m]);
        std::printf("| %s (%s) | %.2f [%.2f-%.2f] | %.2f | %.2f", methods[m].name.c_str(), methods[m].what.c_str(), ms,
                    *std::min_element(round_ms[m].begin(), round_ms[m].end()),
                    *std::max_element(round_ms[m].begin(), round_ms[m].end()), ms * 1e6 / static_cast<double>(pixels),
                    (ms - inputs_ms) * 1e6 / static_cast<double>(pixels));
        for (const std::string &b : baselines) {
            const size_t base = index_of(methods, b);
            std::vector<double> ratios;
            for (int r = 0; r < rounds; ++r) ratios.push_back(round_ms[m][r] / round_ms[base][r]);
            std::printf(" | %.2f [%.2f-%.2f]", median_of(ratios), *std::min_element(ratios.begin(), ratios.end()),
                        *std::max_element(ratios.begin(), ratios.end()));
        }
        if (methods[m].timed_only) std::printf(" | – | – | – |\n");
        else std::printf(" | %.2g | %.2g | %.2g |\n", errors[m].median, errors[m].p99, errors[m].max);
    }
}

// Both scenes (bench_gpu_airlight.cpp, bench_gpu_nearlight.cpp): 0, or 1 after printing why not.
int run_airlight_scene(const gpu_harness::Gl &gl, const Options &opt);
int run_nearlight_scene(const gpu_harness::Gl &gl, const Options &opt);

} // namespace gpu_bench
