// scatterlut generator — helpers the kinds' derivations share (add_demand, finish_plan):
// ranges gathered over the scene's media and lights, and the search's starting counts.
#pragma once

#include <algorithm>
#include <limits>

namespace scatterlut {

// The fewest nodes per axis the resolution search uses (plan_search.cpp).
inline constexpr int kMinNodesPerAxis = 8;

// The search starts at half a kind's default counts: measured refinement from there costs
// less than starting too fine.
inline int half_count(int n) { return std::max(kMinNodesPerAxis, (n + 1) / 2); }

// A range of positive numbers, widened when degenerate (an axis needs min < max).
struct Span {
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    bool empty() const { return !(lo <= hi); }
    void add(double a, double b) {
        lo = std::min(lo, a);
        hi = std::max(hi, b);
    }
    Span widened() const {
        Span s = *this;
        if (s.hi < 1.1 * s.lo) {
            s.lo /= 1.05;
            s.hi *= 1.05;
        }
        return s;
    }
};

} // namespace scatterlut
