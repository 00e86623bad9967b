// What the scatterlut benchmarks share (bench/bench_*.cpp, one executable: scatterlut_bench): the
// OpenCL device (one per process), timing, the pause between a device run and its baseline, the
// per-round ratios as counters, and sampled table nodes.
#pragma once

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <memory>
#include <random>
#include <string>
#include <thread>
#include <vector>

#include <benchmark/benchmark.h>
#include <fcntl.h>
#include <spawn.h>
#include <time.h>
#include <sys/wait.h>

#include "airlight_reference.hpp"
#include "baselines.hpp"
#include "generate_airlight.hpp"
#include "generate_nearlight.hpp"
#include "measure_util.hpp"
#include "opencl_device.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/nearlight.hpp"

extern "C" {
#include "slut_airlight.h"
#include "slut_nearlight.h"
}

namespace slut_bench {

using Clock = std::chrono::steady_clock;
inline double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

inline scatterlut::Device &device() {
    static scatterlut::Device d("");
    return d;
}

// A pause (untimed) between the device run and the baseline, so that the device's worker
// threads are idle again and do not compete with the single-threaded baseline.
inline void settle(benchmark::State &state) {
    state.PauseTiming();
    std::this_thread::sleep_for(std::chrono::milliseconds(200));
    state.ResumeTiming();
}

inline double median(std::vector<double> v) { return scatterlut::percentile(std::move(v), 0.5); }

// Per-round ratios → counters.
inline void report_rounds(benchmark::State &state, const std::vector<double> &device_s, const std::vector<double> &baseline_s,
                          double cells) {
    std::vector<double> ratio(device_s.size());
    for (size_t k = 0; k < ratio.size(); ++k) ratio[k] = baseline_s[k] / device_s[k];
    state.counters["ratio_median"] = median(ratio);
    state.counters["ratio_min"] = *std::min_element(ratio.begin(), ratio.end());
    state.counters["ratio_max"] = *std::max_element(ratio.begin(), ratio.end());
    state.counters["device_ms"] = 1e3 * median(device_s);
    state.counters["device_cells_per_s"] = cells / median(device_s);
    state.counters["boost_cells_per_s"] = cells / median(baseline_s);
}

// Node indices of a table: uniform random ones plus every corner of the index box.
template <size_t D> std::vector<std::array<int, D>> sample_nodes(const std::array<int, D> &count, int n, uint64_t seed) {
    std::vector<std::array<int, D>> out;
    for (unsigned mask = 0; mask < (1u << D); ++mask) {
        std::array<int, D> c{};
        for (size_t a = 0; a < D; ++a) c[a] = (mask >> a & 1u) ? count[a] - 1 : 0;
        out.push_back(c);
    }
    std::mt19937_64 rng(seed);
    while (static_cast<int>(out.size()) < n) {
        std::array<int, D> c{};
        for (size_t a = 0; a < D; ++a) c[a] = std::uniform_int_distribution<int>(0, count[a] - 1)(rng);
        out.push_back(c);
    }
    return out;
}

} // namespace slut_bench
