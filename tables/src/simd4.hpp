// scatterlut runtime (internal) — four doubles at a time: AVX2 + FMA vectors and glibc's
// libmvec for their exp, expm1, log, atan, sin, cos and tan.
//
// Why: a radiance call's cost is its transcendentals (tables/src/airlight_avx2.cpp); several of
// them are independent (the six nodes of the one-panel θ-rule; the same step of four queries
// in a batch), and libmvec evaluates four in about the time of one scalar call. libmvec is
// glibc's vector math library (the functions GCC calls for `#pragma omp simd` loops under
// -ffast-math), documented to ≤ 4 ulp (glibc manual, "Known Maximum Errors in Math
// Functions"); the tests compare every vectorised path with the scalar one per query.
//
// Only in functions compiled for the target (SLUT_SIMD4_TARGET) and called where
// simd4_available() (the CPU has AVX2 and FMA): the library itself is built for the
// baseline x86-64 and dispatches at run time. Without libmvec (another libc, another
// architecture) SLUT_HAVE_SIMD4 is 0 and the callers keep their scalar code.
#pragma once

#if defined(SCATTERLUT_HAVE_LIBMVEC) && defined(__x86_64__) && defined(__GNUC__)
#define SLUT_HAVE_SIMD4 1
#else
#define SLUT_HAVE_SIMD4 0
#endif

#if SLUT_HAVE_SIMD4
#include <immintrin.h>

#define SLUT_SIMD4_TARGET __attribute__((target("avx2,fma")))

namespace scatterlut::simd4 {

typedef double v4d __attribute__((vector_size(32)));
typedef long long v4l __attribute__((vector_size(32))); // comparison masks: all ones or 0 per lane
// Two doubles (SSE): one meaningful lane where a scalar computation's `?:` must be blends,
// not branches (angle_over_sine.hpp).
typedef double v2d __attribute__((vector_size(16)));

} // namespace scatterlut::simd4

// libmvec's AVX2 variants (the x86-64 vector ABI's names, 4 lanes).
extern "C" {
SLUT_SIMD4_TARGET scatterlut::simd4::v4d _ZGVdN4v_exp(scatterlut::simd4::v4d);
SLUT_SIMD4_TARGET scatterlut::simd4::v4d _ZGVdN4v_log(scatterlut::simd4::v4d);
SLUT_SIMD4_TARGET scatterlut::simd4::v4d _ZGVdN4v_atan(scatterlut::simd4::v4d);
SLUT_SIMD4_TARGET scatterlut::simd4::v4d _ZGVdN4v_sin(scatterlut::simd4::v4d);
SLUT_SIMD4_TARGET scatterlut::simd4::v4d _ZGVdN4v_cos(scatterlut::simd4::v4d);
SLUT_SIMD4_TARGET scatterlut::simd4::v4d _ZGVdN4v_tan(scatterlut::simd4::v4d);
SLUT_SIMD4_TARGET scatterlut::simd4::v4d _ZGVdN4v_expm1(scatterlut::simd4::v4d);
}

namespace scatterlut::simd4 {

// Whether the CPU has AVX2 and FMA (cpuid; simd4.cpp).
bool cpu_has_avx2_fma();
// True where the CPU runs the SLUT_SIMD4_TARGET code: checked once, inline so that each
// radiance call pays a load and a branch, not a call into another translation unit.
inline bool available() {
    static const bool yes = cpu_has_avx2_fma();
    return yes;
}

SLUT_SIMD4_TARGET inline v4d exp4(v4d x) { return _ZGVdN4v_exp(x); }
SLUT_SIMD4_TARGET inline v4d log4(v4d x) { return _ZGVdN4v_log(x); }
SLUT_SIMD4_TARGET inline v4d atan4(v4d x) { return _ZGVdN4v_atan(x); }
SLUT_SIMD4_TARGET inline v4d sin4(v4d x) { return _ZGVdN4v_sin(x); }
SLUT_SIMD4_TARGET inline v4d cos4(v4d x) { return _ZGVdN4v_cos(x); }
SLUT_SIMD4_TARGET inline v4d tan4(v4d x) { return _ZGVdN4v_tan(x); }
SLUT_SIMD4_TARGET inline v4d expm1_4(v4d x) { return _ZGVdN4v_expm1(x); }
// True if any lane of the mask is set.
SLUT_SIMD4_TARGET inline bool any(v4l mask) { return _mm256_movemask_pd(_mm256_castsi256_pd(__m256i(mask))) != 0; }
SLUT_SIMD4_TARGET inline v4d sqrt4(v4d x) { return _mm256_sqrt_pd(x); }
SLUT_SIMD4_TARGET inline v4d splat(double x) { return v4d{x, x, x, x}; }
// Lane-wise a ? b : c for a comparison mask a.
SLUT_SIMD4_TARGET inline v4d select(v4l mask, v4d if_true, v4d if_false) {
    return _mm256_blendv_pd(if_false, if_true, _mm256_castsi256_pd(__m256i(mask)));
}
// |x| lane-wise (the sign bit cleared: |−0| = +0, as fabs).
SLUT_SIMD4_TARGET inline v4d abs4(v4d x) { return _mm256_andnot_pd(_mm256_set1_pd(-0.0), x); }
SLUT_SIMD4_TARGET inline v4d min4(v4d a, v4d b) { return _mm256_min_pd(a, b); }
SLUT_SIMD4_TARGET inline v4d max4(v4d a, v4d b) { return _mm256_max_pd(a, b); }
SLUT_SIMD4_TARGET inline v4d load4(const double *p) { return _mm256_loadu_pd(p); }
SLUT_SIMD4_TARGET inline void store4(double *p, v4d x) { _mm256_storeu_pd(p, x); }

} // namespace scatterlut::simd4

#endif
