/* scatterlut — m-point Gauss–Legendre rules on [−1, 1], computed (shared code, slut_compat.h
 * rules: C99, compiles as OpenCL C and C++).
 *
 * The generator builds its airlight sweep's panel rules of every order m ≤ SLUT_GL_MAX_ORDER
 * from slut_gauss_legendre and chooses each panel's order with the error constants of
 * slut_gauss_legendre_log_error_constant. The fixed rules the kernels use (slut_gl16_x/w,
 * slut_gl8_x/w, slut_gl6_x/w in slut_airlight.h, 21 digits) agree with these to ≤ 2 ulp
 * (tests/kernels/test_quadrature.cpp).
 */
#ifndef SLUT_GAUSS_LEGENDRE_H
#define SLUT_GAUSS_LEGENDRE_H

#include "slut_compat.h"

/* The highest order the generator's panel rules use. */
#define SLUT_GL_MAX_ORDER 16

/* The m-point Gauss–Legendre rule on [−1, 1], m ≥ 1: nodes x[0 … m−1] ascending (x[m−1−k] =
 * −x[k]) and weights w[0 … m−1]. Newton's iteration on P_m from the Tricomi-style initial
 * guesses cos(π(k + ¾)/(m + ½)), k = 0 … ⌈m/2⌉ − 1, converged to rounding (Numerical Recipes
 * §4.6, gauleg); P_m by the three-term recurrence, P_m'(z) = m (z P_m − P_{m−1})/(z² − 1),
 * w = 2/((1 − z²) P_m'(z)²). */
SLUT_FN void slut_gauss_legendre(int m, double *x, double *w) {
    SLUT_CHECK_GE(m, 1);
    for (int k = 0; k < (m + 1) / 2; ++k) {
        double z = cos(SLUT_PI * (k + 0.75) / (m + 0.5)), dp = 0;
        for (int it = 0; it < 100; ++it) {
            double p0 = 1, p1 = 0;
            for (int n = 1; n <= m; ++n) { /* P_n(z) = ((2n−1) z P_{n−1} − (n−1) P_{n−2})/n */
                const double p2 = p1;
                p1 = p0;
                p0 = ((2.0 * n - 1.0) * z * p1 - (n - 1.0) * p2) / n;
            }
            dp = m * (z * p0 - p1) / (z * z - 1.0); /* P_m'(z) */
            const double dz = p0 / dp;
            z -= dz;
            if (fabs(dz) < 1e-17) break;
        }
        const double weight = 2.0 / ((1.0 - z * z) * dp * dp);
        x[k] = -z;
        x[m - 1 - k] = z;
        w[k] = weight;
        w[m - 1 - k] = weight;
    }
}

/* ln C_m, C_m = (m!)^4 / ((2m + 1) ((2m)!)^3), m ≥ 1: the m-point Gauss–Legendre error on a
 * panel of length h is h^{2m+1} C_m f^{(2m)}(ξ) for some ξ in the panel (Abramowitz & Stegun
 * 25.4.30). */
SLUT_FN double slut_gauss_legendre_log_error_constant(int m) {
    SLUT_CHECK_GE(m, 1);
    return 4.0 * lgamma(m + 1.0) - log(2.0 * m + 1.0) - 3.0 * lgamma(2.0 * m + 1.0);
}

#endif /* SLUT_GAUSS_LEGENDRE_H */
