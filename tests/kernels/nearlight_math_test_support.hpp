// The near-light math tests' shared helpers (tests/kernels/test_nearlight_math*.cpp): the worst
// error's bookkeeping, random hard (T, g), the node count of one evaluation.
#pragma once

#include <gtest/gtest.h>

#include <boost/math/special_functions/expint.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <random>
#include <vector>

#include "nearlight_reference.hpp"
#include "reference_data.hpp"
#include "slut_nearlight.h"

namespace {

using slut_ref::real;
const double kInf = std::numeric_limits<double>::infinity();

struct Worst {
    double err = 0;
    double T = 0, g = 0, r = 0, S = 0;
    void add(double e, double T_, double g_, double r_, double S_) {
        if (e > err || std::isnan(e)) { err = e; T = T_; g = g_; r = r_; S = S_; }
    }
    void print(const char *what) const {
        std::printf("  worst %-28s %.3e  at T=%.6g g=%.9g r=%.6g S=%.6g\n", what, err, T, g, r, S);
    }
};

// A random hard (T, g): T log-uniform in [1e-3, 100]; g within 1e-6..1 of −1 a third of the
// time (the peak), near 1 a tenth, else uniform (MatchesBoostReferenceOnCornersAndRandomPoints).
void random_hard_T_g(std::mt19937_64 &rng, double *T, double *g) {
    std::uniform_real_distribution<double> U(0.0, 1.0);
    *T = std::pow(10.0, -3.0 + 5.0 * U(rng));
    const double pick = U(rng);
    *g = pick < 0.33 ? -1.0 + std::pow(10.0, -6.0 + 6.0 * U(rng))
         : pick < 0.43 ? 1.0 - std::pow(10.0, -6.0 + 6.0 * U(rng)) * U(rng)
                       : -1.0 + 2.0 * U(rng);
}

int nodes_of(double T, double g, double r, double S) {
    double E = 0;
    return slut_nl_E_lanes(T, g, S, &r, 1, &E, 1.0);
}

} // namespace
