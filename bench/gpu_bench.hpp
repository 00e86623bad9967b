// The GPU per-pixel bench's harness (scatterlut_gpu_bench: bench_gpu_pixel.cpp, the airlight
// scene bench_gpu_airlight.cpp, the near-light scene bench_gpu_nearlight.cpp): full-screen
// fragment passes through a surfaceless EGL / OpenGL 4.3 context (host/src/egl_context.hpp, gpu_pixel_passes.hpp;
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

#include "gpu_pixel_passes.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {
class Device;
}

namespace gpu_bench {

struct Options {
    int width = 1920, height = 1080, frames = 5, rounds = 7, stride = 4;
    std::string compare_snippet; // another scatterlut_airlight.glsl, run as method "compare"
    bool airlight = true, spot = true, nearlight = true;
};

inline std::string read_text(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    std::ostringstream s;
    s << in.rdbuf();
    return in ? s.str() : std::string();
}

using gpu_harness::fragment_source;
using gpu_harness::median_of;
using gpu_harness::Method;
using gpu_harness::Passes;

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
// Builds every method's program on `passes` and times them (Passes::time_rounds): the rounds'
// frame times in ms per method in *round_ms; false after printing why not (the render target, a
// shader, an OpenGL error during the frames).
inline bool build_and_time(const gpu_harness::Gl &gl, const Passes &passes, std::vector<Method> &methods, const Options &opt,
                           std::vector<std::vector<double>> *round_ms) {
    const std::string error = passes.complete() ? passes.build(methods) : "the R32F render target is not complete";
    if (!error.empty()) {
        std::fprintf(stderr, "scatterlut_gpu_bench: %s\n", error.c_str());
        return false;
    }
    *round_ms = passes.time_rounds(methods, opt.rounds, opt.frames);
    if (gl.glGetError() != GL_NO_ERROR) {
        std::fprintf(stderr, "scatterlut_gpu_bench: OpenGL error during the timed frames\n");
        return false;
    }
    return true;
}

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

// The airlight tables the airlight scenes share (bench_gpu_airlight.cpp): the airlight_rational
// table for a radiance target (the smallest square whose measured interpolation error times the
// difference's gain 2G − 1 is within it) and the default airlight_F table, generated on the
// OpenCL device as `scatterlut generate` does, f32.
scatterlut::Table rational_table(scatterlut::Device &device, double radiance_target);
scatterlut::Table airlight_F_table(scatterlut::Device &device);

// The scenes (bench_gpu_airlight.cpp, bench_gpu_spot.cpp, bench_gpu_nearlight.cpp): 0, or 1 after
// printing why not.
int run_airlight_scene(const gpu_harness::Gl &gl, const Options &opt);
int run_spot_scene(const gpu_harness::Gl &gl, const Options &opt);
int run_nearlight_scene(const gpu_harness::Gl &gl, const Options &opt);

} // namespace gpu_bench
