// scatterlut generator — small helpers shared by the accuracy measurements.
#pragma once

#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <random>
#include <thread>
#include <vector>

#include "measurement.hpp"

namespace scatterlut {

// Runs f(i) for i in [0, n) on all hardware threads. Each i is handled by exactly one
// thread and writes only its own slot, so results do not depend on scheduling.
template <class F> void parallel_for(int n, F f) {
    const int threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::vector<std::thread> pool;
    for (int t = 0; t < threads; ++t)
        pool.emplace_back([=, &f] {
            for (int i = t; i < n; i += threads) f(i);
        });
    for (auto &th : pool) th.join();
}

// The q-quantile (nearest rank) of v; 0 for an empty v.
inline double percentile(std::vector<double> v, double q) {
    if (v.empty()) return 0.0;
    const size_t k = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
    std::nth_element(v.begin(), v.begin() + static_cast<long>(k), v.end());
    return v[k];
}

// `nodes` nodes of `table` drawn uniformly from `seed`, each axis's index independently: where
// the near-light and surface generators measure their integration error.
inline std::vector<NodeIndex> random_table_nodes(const Table &table, int nodes, uint64_t seed) {
    std::mt19937_64 rng(seed);
    std::vector<NodeIndex> picks(static_cast<size_t>(nodes), NodeIndex{});
    for (auto &p : picks)
        for (size_t a = 0; a < table.axes.size(); ++a)
            p[a] = std::uniform_int_distribution<size_t>(0, static_cast<size_t>(table.axes[a].map.count - 1))(rng);
    return picks;
}

} // namespace scatterlut
