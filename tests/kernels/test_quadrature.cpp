// The computed Gauss–Legendre rules (kernels/slut_gauss_legendre.h): they reproduce the fixed
// 16-, 8- and 6-point rules the kernels carry as 21-digit constants (kernels/slut_airlight.h),
// are symmetric, integrate polynomials of degree ≤ 2m − 1 exactly, and miss x^{2m} by exactly
// the error term their constant ln C_m predicts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstring>
#include <vector>

extern "C" {
#include "slut_airlight.h"
#include "slut_gauss_legendre.h"
}

namespace {

// Units in the last place between two finite doubles of the same sign.
uint64_t ulp_distance(double a, double b) {
    EXPECT_EQ(std::signbit(a), std::signbit(b)) << a << " vs " << b;
    int64_t ia, ib;
    std::memcpy(&ia, &a, sizeof a);
    std::memcpy(&ib, &b, sizeof b);
    return ia > ib ? static_cast<uint64_t>(ia - ib) : static_cast<uint64_t>(ib - ia);
}

struct Rule {
    std::vector<double> x, w;
};

Rule computed_rule(int m) {
    Rule r{std::vector<double>(static_cast<size_t>(m)), std::vector<double>(static_cast<size_t>(m))};
    slut_gauss_legendre(m, r.x.data(), r.w.data());
    return r;
}

// The positive half of the computed m-point rule (m even) against the header's constants
// (correctly rounded): nodes to ≤ 2 ulp (measured ≤ 1). The weights, 2/((1 − z²) P_m'(z)²) in
// double, carry the rounding of the recurrence for P_m' (twice) and of 1 − z²: ≤ 2m ulp
// (measured 17 ulp for m = 16, 6 for m = 8, 5 for m = 6). A construction exact to 2 ulp
// changes the generator's panel rules and with them the bytes of the default airlight table,
// which must not change.
void expect_matches_fixed_rule(int m, const double *fixed_x, const double *fixed_w) {
    const Rule r = computed_rule(m);
    const int half = m / 2;
    for (int i = 0; i < half; ++i) {
        const size_t k = static_cast<size_t>(half + i); // ascending: the positive nodes come second
        EXPECT_LE(ulp_distance(r.x[k], fixed_x[i]), 2u)
            << m << "-point node " << i << ": computed " << r.x[k] << ", fixed " << fixed_x[i];
        EXPECT_LE(ulp_distance(r.w[k], fixed_w[i]), static_cast<uint64_t>(2 * m))
            << m << "-point weight " << i << ": computed " << r.w[k] << ", fixed " << fixed_w[i];
    }
}

TEST(GaussLegendre, ReproducesTheKernelsFixedRules) {
    expect_matches_fixed_rule(16, slut_gl16_x, slut_gl16_w);
    expect_matches_fixed_rule(8, slut_gl8_x, slut_gl8_w);
    expect_matches_fixed_rule(6, slut_gl6_x, slut_gl6_w);
}

TEST(GaussLegendre, NodesAscendingSymmetricInsideTheInterval) {
    for (int m = 1; m <= SLUT_GL_MAX_ORDER; ++m) {
        const Rule r = computed_rule(m);
        for (int k = 0; k < m; ++k) {
            const size_t i = static_cast<size_t>(k), j = static_cast<size_t>(m - 1 - k);
            EXPECT_EQ(r.x[i], -r.x[j]) << "m = " << m << ", k = " << k;
            EXPECT_EQ(r.w[i], r.w[j]) << "m = " << m << ", k = " << k;
            EXPECT_GT(r.w[i], 0.0) << "m = " << m << ", k = " << k;
            EXPECT_LT(std::fabs(r.x[i]), 1.0) << "m = " << m << ", k = " << k;
            if (k > 0) {
                EXPECT_LT(r.x[i - 1], r.x[i]) << "m = " << m << ", k = " << k;
            }
        }
        if (m % 2 == 1) {
            EXPECT_LE(std::fabs(r.x[static_cast<size_t>(m / 2)]), 1e-16) << "m = " << m;
        }
    }
}

// Σ w_k x_k^j against ∫_{−1}^{1} x^j dx = 2/(j + 1) (j even; 0 for odd j by symmetry).
TEST(GaussLegendre, IntegratesPolynomialsOfDegreeBelow2mExactly) {
    for (int m = 1; m <= SLUT_GL_MAX_ORDER; ++m) {
        const Rule r = computed_rule(m);
        for (int j = 0; j <= 2 * m - 1; ++j) {
            double sum = 0;
            for (size_t k = 0; k < r.x.size(); ++k) sum += r.w[k] * std::pow(r.x[k], j);
            const double exact = (j % 2 == 0) ? 2.0 / (j + 1) : 0.0;
            EXPECT_NEAR(sum, exact, 8e-16 * 2.0) << "m = " << m << ", degree " << j;
        }
    }
}

// A&S 25.4.30 on [−1, 1] (h = 2) with f = x^{2m}, f^{(2m)} = (2m)! everywhere:
// 2/(2m + 1) − Σ w_k x_k^{2m} = 2^{2m+1} C_m (2m)!, and C_m = (m!)^4 / ((2m + 1) ((2m)!)^3).
TEST(GaussLegendre, ErrorConstantPredictsTheFirstInexactDegree) {
    for (int m = 1; m <= SLUT_GL_MAX_ORDER; ++m) {
        const double log_c = slut_gauss_legendre_log_error_constant(m);
        // C_m from exact factorials (long double; (2m)! ≤ 32! ≈ 2.6e35).
        long double fm = 1, f2m = 1;
        for (int k = 2; k <= m; ++k) fm *= k;
        for (int k = 2; k <= 2 * m; ++k) f2m *= k;
        const long double c = fm * fm * fm * fm / ((2 * m + 1) * f2m * f2m * f2m);
        EXPECT_NEAR(log_c, static_cast<double>(std::log(c)), 1e-13 * std::fabs(log_c)) << "m = " << m;

        const Rule r = computed_rule(m);
        double sum = 0;
        for (size_t k = 0; k < r.x.size(); ++k) sum += r.w[k] * std::pow(r.x[k], 2 * m);
        const double missed = 2.0 / (2 * m + 1) - sum;
        const double predicted = std::exp(log_c + (2 * m + 1) * std::log(2.0) + std::lgamma(2 * m + 1.0));
        EXPECT_NEAR(missed, predicted, 1e-6 * predicted + 16 * 2.2e-16) << "m = " << m;
    }
}

} // namespace
