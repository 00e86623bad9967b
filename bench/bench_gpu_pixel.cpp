// scatterlut_gpu_bench: the GPU per-pixel cost and accuracy of the sampling snippets' tiers
// against the per-pixel forms engines use today, on a GPU through a surfaceless EGL context
// (Mesa llvmpipe where there is none; host/src/egl_context.hpp). Three scenes (gpu_bench.hpp):
//   airlight   a foggy street, every 32 x 32 tile its own lamp (bench_gpu_airlight.cpp):
//              fast, accurate, airlight_F, sun2005, closed, inputs;
//   spot       the same street, every lamp a spot light (bench_gpu_spot.cpp): the point light and
//              the spot in each tier (fast / spot_fast, accurate / spot_accurate, airlight_F /
//              spot_airlight_F), inputs;
//   nearlight  a translucent floor lit by lamps above it (bench_gpu_nearlight.cpp):
//              nearlight_fast, nearlight_accurate, thin, inputs.
// Every cost is a ratio per round to a baseline drawn in the same round; errors are per pixel
// against exact double quadrature. bench/README.md, "GPU snippet tiers", has the figures.
//
// Usage: scatterlut_gpu_bench [--scene airlight|spot|nearlight|all] [--width N] [--height N]
//                             [--frames N] [--rounds N] [--stride N] [--compare-snippet FILE]
// --compare-snippet adds a method "compare" to the airlight scene: FILE (another
// scatterlut_airlight.glsl, e.g. one generated before a change) the way airlight_F runs; and
// "spot_compare" to the spot scene: FILE's spot the way spot_fast runs.
#include <cstdio>
#include <cstdlib>
#include <string>

#include "gpu_bench.hpp"

namespace {

bool parse_int(const char *text, int lo, int hi, int *out) {
    char *end = nullptr;
    const long v = std::strtol(text, &end, 10);
    if (end == text || *end != '\0' || v < lo || v > hi) return false;
    *out = static_cast<int>(v);
    return true;
}

int usage_error(const std::string &what) {
    std::fprintf(stderr, "scatterlut_gpu_bench: %s\nusage: scatterlut_gpu_bench [--scene airlight|spot|nearlight|all] "
                         "[--width 16..8192] [--height 16..8192] [--frames 1..1000] [--rounds 1..1000] "
                         "[--stride 1..1000000] [--compare-snippet FILE]\n",
                 what.c_str());
    return 2;
}

} // namespace

int main(int argc, char **argv) {
    gpu_bench::Options opt;
    for (int k = 1; k < argc; ++k) {
        const std::string a = argv[k];
        if (a == "--compare-snippet" || a == "--scene") {
            if (k + 1 >= argc) return usage_error("option " + a + " needs a value");
            const std::string v = argv[++k];
            if (a == "--compare-snippet") {
                opt.compare_snippet = v;
            } else if (v == "airlight" || v == "spot" || v == "nearlight" || v == "all") {
                opt.airlight = v == "airlight" || v == "all";
                opt.spot = v == "spot" || v == "all";
                opt.nearlight = v == "nearlight" || v == "all";
            } else {
                return usage_error("--scene: expected airlight, spot, nearlight or all, got '" + v + "'");
            }
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

    gpu_harness::GpuContext &context = gpu_harness::gpu();
    if (!context.ok) {
        std::fprintf(stderr, "scatterlut_gpu_bench: no OpenGL context: %s\n", context.why_not.c_str());
        return 1;
    }
    const char *threads = std::getenv("LP_NUM_THREADS");
    std::printf("renderer: %s (LP_NUM_THREADS=%s)\n", context.renderer.c_str(), threads ? threads : "unset");
    if (opt.airlight && gpu_bench::run_airlight_scene(context.gl, opt) != 0) return 1;
    if (opt.spot && gpu_bench::run_spot_scene(context.gl, opt) != 0) return 1;
    if (opt.nearlight && gpu_bench::run_nearlight_scene(context.gl, opt) != 0) return 1;
    return 0;
}
