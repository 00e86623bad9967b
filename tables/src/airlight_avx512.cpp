// The airlight one-panel θ-rule on 8 lanes, where the CPU has AVX-512F (AirlightTable::radiance's
// AVX2 path calls it: airlight_avx2.cpp). The library is built for the baseline x86-64: the
// rule carries the target attribute and runs only where detail::airlight_cpu_has_avx512f().
#include "airlight_simd.hpp"

extern "C" {
#include "slut_airlight.h"
}

#if SLUT_HAVE_SIMD4
// The one-panel rule's six node exponentials as one 8-lane exp where the CPU has AVX-512
// (libmvec's _ZGVeN8v_exp, ≤ 4 ulp like the 4-lane one): one_panel_radiance4's nodes, weights
// and order of additions (lanes 0–3 its first vector, 4–7 its second).
namespace {
typedef double v8d __attribute__((vector_size(64)));
} // namespace
extern "C" __attribute__((target("avx512f"))) v8d _ZGVeN8v_exp(v8d);

namespace scatterlut {

// The geometry's fields as arguments (registers), not a slut_airlight_geometry in memory.
__attribute__((target("avx512f,avx2,fma"))) __attribute__((noinline)) double
detail::airlight_one_panel_radiance8(double c, double cos_half, double sin_half, double tan_dv, double optical_distance,
                                     double scale_unattenuated, double sin_gamma) {
    const v8d x = {-slut_gl6_x[0], -slut_gl6_x[1], -slut_gl6_x[2], slut_gl6_x[0], slut_gl6_x[1], slut_gl6_x[2], 0.0, 0.0};
    const v8d w = {slut_gl6_w[0], slut_gl6_w[1], slut_gl6_w[2], slut_gl6_w[0], slut_gl6_w[1], slut_gl6_w[2], 0.0, 0.0};
    const double half_len = 0.5 * tan_dv;
    const v8d t = half_len * (1.0 + x);
    const v8d e = -c * t / (cos_half - t * sin_half) - optical_distance;
    const v8d f = w / (1.0 + t * t) * _ZGVeN8v_exp(e);
    return scale_unattenuated *
           ((half_len / sin_gamma) * (((f[0] + f[4]) + (f[1] + f[5])) + ((f[2] + f[6]) + (f[3] + f[7]))));
}

} // namespace scatterlut
#endif
