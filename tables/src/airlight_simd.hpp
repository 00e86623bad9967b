// The airlight runtime's vector functions that one translation unit calls in another
// (internal; not installed), each defined where its instruction set's code lives:
// airlight_avx2.cpp (AVX2 + FMA: the portable path's steps on 4 lanes, called where
// simd4::available()) and airlight_avx512.cpp (the one-panel rule on 8 lanes, where the CPU
// has AVX-512F). Declared with their definitions' target attributes.
#pragma once

#include "simd4.hpp"

struct slut_airlight_geometry; // kernels/slut_airlight.h

#if SLUT_HAVE_SIMD4
namespace scatterlut::detail {

// airlight_avx2.cpp: AirlightTable::one_panel_radiance, theta_rule8 (slut_airlight_theta_integral_rule
// with 8 points), two_sample_radiance's three logs and two exps, each as 4-lane vector operations.
SLUT_SIMD4_TARGET double airlight_one_panel_radiance4(const slut_airlight_geometry &g);
SLUT_SIMD4_TARGET double airlight_theta_rule8_simd(double c, double w2, double dv);
SLUT_SIMD4_TARGET void airlight_logs3_simd(double a, double b, double c, double *la, double *lb, double *lc);
SLUT_SIMD4_TARGET void airlight_exps2_simd(double a, double b, double *ea, double *eb);

// Whether the CPU has AVX-512F (cpuid, checked once; inline, as simd4::available(): each
// radiance call pays a load and a branch, not a call into another translation unit).
inline bool airlight_cpu_has_avx512f() {
    static const bool yes = [] {
        __builtin_cpu_init();
        return __builtin_cpu_supports("avx512f") != 0;
    }();
    return yes;
}
// airlight_avx512.cpp: the one-panel rule's six node exponentials as one 8-lane exp where the
// CPU has AVX-512F (AirlightTable::radiance's AVX2 path calls it).
__attribute__((target("avx512f,avx2,fma"))) double
airlight_one_panel_radiance8(double c, double cos_half, double sin_half, double tan_dv, double optical_distance,
                             double scale_unattenuated, double sin_gamma);

} // namespace scatterlut::detail
#endif
