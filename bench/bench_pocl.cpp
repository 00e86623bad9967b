// Device facts the kernels are written around (docs/POCL.md), measured on the OpenCL
// device `scatterlut generate` would use:
//
//  - BM_DeviceBuiltin/<fn>: the cost per element of one builtin (exp, log, expm1, atan2,
//    sqrt, a divide) called on a scalar, a double8 and a double16 in a work-item loop whose
//    trip count is a kernel argument (as in the generators' kernels), and on a scalar in a
//    loop-free kernel (one element per work-item, the shape a work-group vectoriser can
//    pack across work-items). Each round runs the four kernels back to back; the counters
//    give ns per element (wall time over all cores, median of the rounds) and the median
//    per-round ratio of the scalar loop to the double8 loop.
//  - BM_DeviceLocalSize: 33 heavy work-items (a double8 exp loop each) launched with local
//    size 1 and with the local size left to the driver, back to back; the median per-round
//    ratio of the two times.
//  - BM_BoostNarrowPiece: Boost.Math gauss_kronrod<double, 15> on a piece of width 1e-6 at
//    tol 1e-10, integrated directly and as ∫_0^1 (b − a) f(a + (b − a)x) dx: evaluations
//    and time of each (bench/baselines.hpp integrates every piece the second way).
//
// Speed is a ratio within one round (a shared machine drifts between rounds); nothing here
// asserts a time.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>
#include <vector>

#include <benchmark/benchmark.h>
#include <boost/math/quadrature/gauss_kronrod.hpp>

#include "measure_util.hpp"
#include "opencl_device.hpp"

namespace {

using Clock = std::chrono::steady_clock;
double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }
double median(std::vector<double> v) { return scatterlut::percentile(std::move(v), 0.5); }

scatterlut::Device &device() {
    static scatterlut::Device d("");
    return d;
}

struct Builtin {
    const char *name;
    const char *expr; // of x (a scalar or a vector), x ∈ [0.5, 1.6]
};
constexpr Builtin kBuiltins[] = {
    {"exp", "exp(-x)"},     {"log", "log(x)"},   {"expm1", "expm1(-x)"},
    {"atan2", "atan2(x, 1.75 - x)"}, {"sqrt", "sqrt(x)"}, {"divide", "1.0 / x"},
};

// One kernel per (builtin, width): acc += f(x) over n steps of x, one output per work-item.
std::string loop_kernel(const Builtin &b, int width) {
    const std::string w = width == 1 ? "" : std::to_string(width);
    const std::string type = "double" + w;
    std::string lanes;
    if (width > 1) {
        lanes = " + (" + type + ")(";
        for (int k = 0; k < width; ++k) lanes += (k ? ", " : "") + std::to_string(k) + ".0";
        lanes += ") * 1e-4";
    }
    std::string reduce = "acc";
    if (width == 16) reduce = "(acc.lo + acc.hi)";
    std::string sum = width == 1 ? reduce : "";
    if (width >= 8) sum = "s8.s0 + s8.s1 + s8.s2 + s8.s3 + s8.s4 + s8.s5 + s8.s6 + s8.s7";
    std::string src = "__kernel void " + std::string(b.name) + "_" + (width == 1 ? "1" : w) +
                      "(__global double *out, int n) {\n"
                      "    size_t i = get_global_id(0);\n"
                      "    " + type + " x = (" + type + ")(0.5 + 1e-3 * (double)i)" + lanes + ";\n"
                      "    " + type + " acc = (" + type + ")(0.0);\n"
                      "    for (int k = 0; k < n; ++k) { acc += " + b.expr + "; x += 1e-6; }\n";
    if (width >= 8) src += "    double8 s8 = " + reduce + ";\n";
    src += "    out[i] = " + sum + ";\n}\n";
    return src;
}

// One element per work-item, no loop.
std::string item_kernel(const Builtin &b) {
    return "__kernel void " + std::string(b.name) + "_item(__global double *out) {\n"
           "    size_t i = get_global_id(0);\n"
           "    double x = 0.5 + 1e-6 * (double)(i & 1048575);\n"
           "    out[i] = " + b.expr + ";\n}\n";
}

std::string heavy_kernel() {
    return "__kernel void heavy(__global double *out, int n) {\n"
           "    size_t i = get_global_id(0);\n"
           "    double8 x = (double8)(0.5 + 1e-3 * (double)i), acc = (double8)(0.0);\n"
           "    for (int k = 0; k < n; ++k) { acc += exp(-x); x += 1e-6; }\n"
           "    double4 a = acc.lo + acc.hi;\n"
           "    out[i] = a.x + a.y + a.z + a.w;\n}\n";
}

cl::Program &program() {
    static cl::Program p = [] {
        std::string src = "#pragma OPENCL EXTENSION cl_khr_fp64 : enable\n";
        for (const Builtin &b : kBuiltins) {
            for (int w : {1, 8, 16}) src += loop_kernel(b, w);
            src += item_kernel(b);
        }
        src += heavy_kernel();
        cl::Program prog(device().context(), src);
        try {
            prog.build();
        } catch (const cl::BuildError &) {
            for (const auto &[dev, log] : prog.getBuildInfo<CL_PROGRAM_BUILD_LOG>())
                std::fprintf(stderr, "bench_pocl: build log:\n%s\n", log.c_str());
            throw;
        }
        return prog;
    }();
    return p;
}

// Enqueue and wait; seconds of wall time.
double run(cl::Kernel &k, size_t global, const cl::NDRange &local) {
    const auto t0 = Clock::now();
    device().queue().enqueueNDRangeKernel(k, cl::NullRange, cl::NDRange(global), local);
    device().queue().finish();
    return seconds_since(t0);
}

void BM_DeviceBuiltin(benchmark::State &state, const Builtin &b) {
    constexpr size_t kItems = 64;        // work-items of the loop kernels (local size 1, as the generators)
    constexpr int kElements = 1 << 14;   // elements per work-item
    constexpr size_t kTotal = kItems * kElements;
    cl::Buffer out(device().context(), CL_MEM_WRITE_ONLY, kTotal * sizeof(double));
    std::vector<cl::Kernel> loops;
    for (int w : {1, 8, 16}) {
        loops.emplace_back(program(), (std::string(b.name) + "_" + std::to_string(w)).c_str());
        loops.back().setArg(0, out);
        loops.back().setArg(1, kElements / w);
    }
    cl::Kernel item(program(), (std::string(b.name) + "_item").c_str());
    item.setArg(0, out);
    for (auto &k : loops) run(k, kItems, cl::NDRange(1)); // untimed: the lazy per-kernel JIT
    run(item, kTotal, cl::NullRange);
    std::vector<double> t1, t8, t16, titem, ratio;
    for (auto _ : state) {
        t1.push_back(run(loops[0], kItems, cl::NDRange(1)));
        t8.push_back(run(loops[1], kItems, cl::NDRange(1)));
        t16.push_back(run(loops[2], kItems, cl::NDRange(1)));
        titem.push_back(run(item, kTotal, cl::NullRange));
        ratio.push_back(t1.back() / t8.back());
    }
    const double ns = 1e9 / kTotal;
    state.counters["ns_scalar_loop"] = ns * median(t1);
    state.counters["ns_double8"] = ns * median(t8);
    state.counters["ns_double16"] = ns * median(t16);
    state.counters["ns_scalar_per_item"] = ns * median(titem);
    state.counters["scalar_over_d8"] = median(ratio);
    state.counters["scalar_over_d8_min"] = *std::min_element(ratio.begin(), ratio.end());
    state.counters["scalar_over_d8_max"] = *std::max_element(ratio.begin(), ratio.end());
}

void BM_DeviceLocalSize(benchmark::State &state) {
    constexpr size_t kItems = 33;
    cl::Buffer out(device().context(), CL_MEM_WRITE_ONLY, kItems * sizeof(double));
    cl::Kernel k(program(), "heavy");
    k.setArg(0, out);
    k.setArg(1, 1 << 17);
    run(k, kItems, cl::NDRange(1));
    run(k, kItems, cl::NullRange);
    std::vector<double> t_one, t_auto, ratio;
    for (auto _ : state) {
        t_one.push_back(run(k, kItems, cl::NDRange(1)));
        t_auto.push_back(run(k, kItems, cl::NullRange));
        ratio.push_back(t_auto.back() / t_one.back());
    }
    state.counters["ms_local1"] = 1e3 * median(t_one);
    state.counters["ms_driver_choice"] = 1e3 * median(t_auto);
    state.counters["driver_over_local1"] = median(ratio);
    state.counters["driver_over_local1_min"] = *std::min_element(ratio.begin(), ratio.end());
    state.counters["driver_over_local1_max"] = *std::max_element(ratio.begin(), ratio.end());
}
BENCHMARK(BM_DeviceLocalSize)->Iterations(9)->Unit(benchmark::kMillisecond);

void BM_BoostNarrowPiece(benchmark::State &state) {
    using Rule = boost::math::quadrature::gauss_kronrod<double, 15>;
    const double a = 1.0, b = 1.0 + 1e-6, tol = 1e-10;
    long evals_direct = 0, evals_scaled = 0;
    double v_direct = 0, v_scaled = 0;
    std::vector<double> t_direct, t_scaled;
    for (auto _ : state) {
        evals_direct = evals_scaled = 0;
        auto t0 = Clock::now();
        v_direct = Rule::integrate([&](double x) { ++evals_direct; return std::exp(-x); }, a, b, 15, tol);
        t_direct.push_back(seconds_since(t0));
        t0 = Clock::now();
        v_scaled = (b - a) * Rule::integrate([&](double x) { ++evals_scaled; return std::exp(-(a + (b - a) * x)); },
                                             0.0, 1.0, 15, tol);
        t_scaled.push_back(seconds_since(t0));
        benchmark::DoNotOptimize(v_direct + v_scaled);
    }
    const double exact = std::exp(-a) * -std::expm1(-(b - a));
    state.counters["evals_direct"] = static_cast<double>(evals_direct);
    state.counters["evals_scaled"] = static_cast<double>(evals_scaled);
    state.counters["ms_direct"] = 1e3 * median(t_direct);
    state.counters["ms_scaled"] = 1e3 * median(t_scaled);
    state.counters["rel_err_direct"] = std::fabs(v_direct - exact) / exact;
    state.counters["rel_err_scaled"] = std::fabs(v_scaled - exact) / exact;
}
BENCHMARK(BM_BoostNarrowPiece)->Iterations(5)->Unit(benchmark::kMillisecond);

} // namespace

int main(int argc, char **argv) {
    for (const Builtin &b : kBuiltins)
        benchmark::RegisterBenchmark((std::string("BM_DeviceBuiltin/") + b.name).c_str(), BM_DeviceBuiltin, b)
            ->Iterations(9)
            ->Unit(benchmark::kMillisecond);
    benchmark::Initialize(&argc, argv);
    if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
    benchmark::RunSpecifiedBenchmarks();
    benchmark::Shutdown();
    return 0;
}
