// scatterlut_kernel_ab: the near-light table kernel (kernels/nearlight_E.cl) built from two
// kernel directories, A (a baseline: e.g. the kernels/ of a `git worktree` at an older commit)
// and B (default: this source tree's kernels/), run on the same layout in interleaved rounds.
// Prints whether every node's value is the same bit for bit, and per round the process CPU time
// (all of PoCL's worker threads: less sensitive to other jobs on shared cores than wall time,
// which is printed too) of each, with the median and range of the per-round ratios A/B.
//
//   scatterlut_kernel_ab --baseline DIR [--kernels DIR] [--rounds N] [--table 3|4]
//                        [--local-a N] [--local-b N]
//
// Layouts: those of BM_NearLightGeneration (bench_scatterlut.cpp): --table 3 (default) E3 64³
// at S = ∞, --table 4 E4 32³ × 17 S values; the default integration tolerance. --local-a and
// --local-b: A's and B's work-groups along T (default kNearLightGroupT, the library's launch;
// 1 is the launch before it), the T extent padded to a multiple. Both programs
// are built from source with `-I DIR` (PoCL's kernel cache keys on the preprocessed source).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include <sys/resource.h>

#include "generate_nearlight.hpp"
#include "opencl_device.hpp"
#include "table_build.hpp"

extern "C" {
#include "slut_nearlight.h"
}

namespace {

double process_cpu_ms() {
    rusage u;
    getrusage(RUSAGE_SELF, &u);
    return (static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) * 1e3 +
            static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec) * 1e-3);
}

cl::Program build_from(scatterlut::Device &device, const std::string &dir) {
    cl::Program program(device.context(), std::string("#include \"nearlight_E.cl\"\n"));
    const std::vector<cl::Device> devices = device.context().getInfo<CL_CONTEXT_DEVICES>();
    const std::string options = "-cl-std=CL1.2 -I " + dir;
    try {
        program.build(devices, options.c_str());
    } catch (const cl::Error &) {
        throw std::runtime_error("build of " + dir + "/nearlight_E.cl failed:\n" +
                                 program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(devices[0]));
    }
    return program;
}

struct Timing {
    double cpu_ms, wall_ms;
};

// One launch of nearlight_ln_E over `layout` (the arguments as integrate_nearlight_ln_E passes
// them, one launch, work-groups of local_T T nodes) into `values`.
Timing run(scatterlut::Device &device, cl::Program &program, const scatterlut::Table &layout,
           const std::vector<cl::Buffer> &nodes, std::vector<double> &values, size_t local_T) {
    cl::Kernel kernel(program, "nearlight_ln_E");
    const cl::Buffer out = scatterlut::output_buffer(device, values);
    int arg = 0;
    kernel.setArg(arg++, out);
    for (size_t a = 0; a < 3; ++a) {
        kernel.setArg(arg++, nodes[a]);
        kernel.setArg(arg++, layout.axes[a].map.count);
    }
    const double inf = HUGE_VAL;
    const slut_axis thick = {inf, inf, 0.0, SLUT_WARP_LINEAR, 1};
    scatterlut::set_axis_args(kernel, &arg, layout.axes.size() == 4 ? layout.axes[3].map : thick);
    kernel.setArg(arg++, slut_nl_refine_for_tolerance(scatterlut::kNearLightIntegrationTolerance));
    const size_t groups = static_cast<size_t>((layout.axes[2].map.count + SLUT_NL_MAX_LANES - 1) / SLUT_NL_MAX_LANES);
    const double cpu0 = process_cpu_ms();
    const auto wall0 = std::chrono::steady_clock::now();
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange,
                                        cl::NDRange(groups, static_cast<size_t>(layout.axes[1].map.count),
                                                    (static_cast<size_t>(layout.axes[0].map.count) + local_T - 1) /
                                                        local_T * local_T),
                                        cl::NDRange(1, 1, local_T));
    scatterlut::wait_for_output(device, out, values);
    return {process_cpu_ms() - cpu0,
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - wall0).count()};
}

double median(std::vector<double> v) {
    std::sort(v.begin(), v.end());
    return v[v.size() / 2];
}

} // namespace

int main(int argc, char **argv) {
    std::string baseline, kernels = std::string(SLUT_SOURCE_DIR) + "/kernels";
    int rounds = 9, table = 3, local_a = scatterlut::kNearLightGroupT, local_b = scatterlut::kNearLightGroupT;
    for (int i = 1; i < argc; ++i) {
        const std::string a = argv[i];
        if (i + 1 < argc && a == "--baseline") baseline = argv[++i];
        else if (i + 1 < argc && a == "--kernels") kernels = argv[++i];
        else if (i + 1 < argc && a == "--rounds") rounds = std::atoi(argv[++i]);
        else if (i + 1 < argc && a == "--table") table = std::atoi(argv[++i]);
        else if (i + 1 < argc && a == "--local-a") local_a = std::atoi(argv[++i]);
        else if (i + 1 < argc && a == "--local-b") local_b = std::atoi(argv[++i]);
        else {
            std::fprintf(stderr, "usage: %s --baseline DIR [--kernels DIR] [--rounds N >= 1] [--table 3|4] [--local-a N >= 1] [--local-b N >= 1]\n", argv[0]);
            return 2;
        }
    }
    if (baseline.empty() || rounds < 1 || (table != 3 && table != 4) || local_a < 1 || local_b < 1) {
        std::fprintf(stderr, "usage: %s --baseline DIR [--kernels DIR] [--rounds N >= 1] [--table 3|4] [--local-a N >= 1] [--local-b N >= 1]\n", argv[0]);
        return 2;
    }
    try {
        scatterlut::Device device("");
        // BM_NearLightGeneration's layouts (bench_near_light_plan there).
        scatterlut::NearLightPlan plan = scatterlut::default_near_light_plan(table == 4);
        plan.n_T = plan.n_g = plan.n_r = table == 4 ? 32 : 64;
        plan.n_S = 17;
        const scatterlut::Table layout = scatterlut::make_nearlight_table_layout(plan);
        std::vector<cl::Buffer> nodes;
        for (size_t a = 0; a < 3; ++a) {
            std::vector<double> v(static_cast<size_t>(layout.axes[a].map.count));
            for (size_t i = 0; i < v.size(); ++i) v[i] = slut_axis_node(&layout.axes[a].map, static_cast<int>(i));
            nodes.push_back(scatterlut::input_buffer(device, v));
        }
        cl::Program program_a = build_from(device, baseline), program_b = build_from(device, kernels);
        std::vector<double> values_a(layout.node_count()), values_b(layout.node_count());
        run(device, program_a, layout, nodes, values_a, static_cast<size_t>(local_a)); // first launches: PoCL's work-group compile
        run(device, program_b, layout, nodes, values_b, static_cast<size_t>(local_b));
        size_t differing = 0;
        for (size_t i = 0; i < values_a.size(); ++i) differing += std::memcmp(&values_a[i], &values_b[i], sizeof(double)) != 0;
        std::printf("E%d layout, %zu nodes: %zu differ between A (%s) and B (%s)\n", table, values_a.size(), differing,
                    baseline.c_str(), kernels.c_str());
        std::vector<double> cpu_a, cpu_b, wall_a, wall_b, ratio, wall_ratio;
        for (int r = 0; r < rounds; ++r) {
            Timing a, b;
            if (r % 2 == 0) {
                a = run(device, program_a, layout, nodes, values_a, static_cast<size_t>(local_a));
                b = run(device, program_b, layout, nodes, values_b, static_cast<size_t>(local_b));
            } else {
                b = run(device, program_b, layout, nodes, values_b, static_cast<size_t>(local_b));
                a = run(device, program_a, layout, nodes, values_a, static_cast<size_t>(local_a));
            }
            cpu_a.push_back(a.cpu_ms);
            cpu_b.push_back(b.cpu_ms);
            wall_a.push_back(a.wall_ms);
            wall_b.push_back(b.wall_ms);
            ratio.push_back(a.cpu_ms / b.cpu_ms);
            wall_ratio.push_back(a.wall_ms / b.wall_ms);
            std::printf("round %d: CPU A %.1f ms, B %.1f ms, A/B %.3f; wall A %.1f ms, B %.1f ms\n", r, a.cpu_ms,
                        b.cpu_ms, a.cpu_ms / b.cpu_ms, a.wall_ms, b.wall_ms);
        }
        std::printf("CPU time: A %.1f ms, B %.1f ms (medians); A/B median %.3f [%.3f-%.3f]\n", median(cpu_a),
                    median(cpu_b), median(ratio), *std::min_element(ratio.begin(), ratio.end()),
                    *std::max_element(ratio.begin(), ratio.end()));
        std::printf("wall time: A %.1f ms, B %.1f ms (medians); A/B median %.3f [%.3f-%.3f]\n", median(wall_a),
                    median(wall_b), median(wall_ratio), *std::min_element(wall_ratio.begin(), wall_ratio.end()),
                    *std::max_element(wall_ratio.begin(), wall_ratio.end()));
        return differing == 0 ? 0 : 1;
    } catch (const std::exception &e) {
        std::fprintf(stderr, "scatterlut_kernel_ab: %s\n", e.what());
        return 2;
    }
}
