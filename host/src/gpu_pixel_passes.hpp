// Full-screen fragment passes over per-pixel inputs, into an R32F target, through the OpenGL
// context of egl_context.hpp: what the GPU bench (bench/gpu_bench.hpp) and `scatterlut report`'s
// GPU section (report_gpu.cpp) draw. Each method is one fragment program that reads its
// pixel's inputs (`vec4s` vec4 per pixel, row by row, from a storage buffer) and writes one
// float; timing is wall clock around glDrawArrays + glFinish, in rounds that rotate the
// methods' order, so that the machine's drift affects them alike.
#pragma once

#include "egl_context.hpp"

#if SLUT_HAVE_EGL
#include <algorithm>
#include <chrono>
#include <string>
#include <utility>
#include <vector>

namespace gpu_harness {

inline double median_of(std::vector<double> v) {
    if (v.empty()) return 0.0;
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
    std::vector<std::pair<std::string, float>> uniforms = {}; // float uniforms, set once after linking
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
            for (const auto &[name, value] : m.uniforms) {
                const GLint at = gl_.glGetUniformLocation(m.program, name.c_str());
                if (at < 0) return "method " + m.name + ": no uniform " + name;
                gl_.glUniform1f(at, value);
            }
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

    // Per method, its median frame (ms) of each of `rounds` rounds of `frames` frames; rounds
    // rotate the order.
    std::vector<std::vector<double>> time_rounds(const std::vector<Method> &methods, int rounds, int frames) const {
        for (const Method &m : methods) draw(m); // untimed: llvmpipe compiles a shader at first use
        const size_t nm = methods.size();
        std::vector<std::vector<double>> round_ms(nm);
        for (int r = 0; r < rounds; ++r)
            for (size_t k = 0; k < nm; ++k) {
                const size_t m = (k + static_cast<size_t>(r)) % nm;
                std::vector<double> frame_ms;
                for (int f = 0; f < frames; ++f) {
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

} // namespace gpu_harness

#endif // SLUT_HAVE_EGL
