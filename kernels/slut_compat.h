/* scatterlut — the OpenCL C / C++ common subset.
 *
 * Every formula of the project (integrands, axis maps, quadrature rules,
 * closed forms) is written once in the kernels/ headers and compiled twice: as OpenCL C
 * by the generator's kernels and as C++ by the host, the validator and the
 * runtime library. This header hides the few differences:
 *   - SLUT_FN marks a shared function (static inline in both languages);
 *   - SLUT_GLOBAL is OpenCL's __global address space, empty in C++;
 *   - SLUT_CHECK and SLUT_CHECK_{EQ,NE,LT,LE,GT,GE} stay on in every host build (release
 *     included): a failed check prints the condition, both operands' values and file:line to
 *     stderr and aborts. They guard invariants that matter at run time (launch shapes, sweep
 *     bounds, preconditions of shared functions whose callers validate user input first).
 *     SLUT_DCHECK* are the same in debug builds and vanish under NDEBUG: for hot loops.
 *     All of them vanish on the device and in the shaders.
 * Rules for shared code: C99 syntax, outputs through pointers (no
 * references), no templates, no standard library beyond <math.h> functions,
 * double precision throughout.
 *
 * The regions of kernels/ headers between SLUT_SHADER_BEGIN and SLUT_SHADER_END are
 * compiled a third time, as GLSL and HLSL in float (cmake/assemble_shaders.cmake and
 * tables/shaders/src/common.slsl, which define everything below for the GPU). There,
 * in addition: no pointers, structs or arrays; conversions only through SLUT_INT(x) and
 * SLUT_DOUBLE(x) (GLSL has no C casts and no implicit int → float); "counts as
 * infinite" thresholds as SLUT_INFINITE_ABOVE and SLUT_TINY (1e300 has no float);
 * math from log, log1p, exp, expm1, sqrt, sin, cos, sinh, atan, atan2, fabs, fmin,
 * fmax (the GPU versions keep relative precision where GPU built-ins do not).
 */
#ifndef SLUT_COMPAT_H
#define SLUT_COMPAT_H

#if defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#  ifdef cl_khr_fp64
#    pragma OPENCL EXTENSION cl_khr_fp64 : enable
#  endif
#  define SLUT_FN static inline
#  define SLUT_GLOBAL __global
#  define SLUT_CONSTANT __constant
#  define SLUT_CHECK(c) ((void)0)
#  define SLUT_CHECK_OP(a, op, b) ((void)0)
#  define SLUT_HUGE_VAL ((double)INFINITY)
#  define SLUT_ISFINITE(x) isfinite(x)
#else
#  include <math.h>
#  include <stdio.h>
#  include <stdlib.h>
#  define SLUT_FN static inline
#  define SLUT_GLOBAL
#  define SLUT_CONSTANT static const
/* Reports a failed check and aborts. Operands are printed as doubles (exact for the integers
 * checked here, |n| < 2^53); a check without operands passes NULL names. */
SLUT_FN void slut_check_failed(const char *file, int line, const char *condition, const char *a_text,
                               double a, const char *b_text, double b) {
    if (a_text)
        fprintf(stderr, "scatterlut: check failed at %s:%d: %s (%s = %.17g, %s = %.17g)\n", file, line,
                condition, a_text, a, b_text, b);
    else
        fprintf(stderr, "scatterlut: check failed at %s:%d: %s\n", file, line, condition);
    fflush(stderr);
    abort();
}
#  define SLUT_CHECK(c) ((c) ? (void)0 : slut_check_failed(__FILE__, __LINE__, #c, NULL, 0.0, NULL, 0.0))
#  define SLUT_CHECK_OP(a, op, b)                                                                     \
    do {                                                                                              \
        const double slut_check_a_ = (double)(a), slut_check_b_ = (double)(b);                       \
        if (!(slut_check_a_ op slut_check_b_))                                                        \
            slut_check_failed(__FILE__, __LINE__, #a " " #op " " #b, #a, slut_check_a_, #b, slut_check_b_); \
    } while (0)
#  define SLUT_HUGE_VAL HUGE_VAL
#  define SLUT_ISFINITE(x) isfinite(x)
#endif

#define SLUT_CHECK_EQ(a, b) SLUT_CHECK_OP(a, ==, b)
#define SLUT_CHECK_NE(a, b) SLUT_CHECK_OP(a, !=, b)
#define SLUT_CHECK_LT(a, b) SLUT_CHECK_OP(a, <, b)
#define SLUT_CHECK_LE(a, b) SLUT_CHECK_OP(a, <=, b)
#define SLUT_CHECK_GT(a, b) SLUT_CHECK_OP(a, >, b)
#define SLUT_CHECK_GE(a, b) SLUT_CHECK_OP(a, >=, b)
#if defined(NDEBUG) || defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
#  define SLUT_DCHECK(c) ((void)0)
#  define SLUT_DCHECK_OP(a, op, b) ((void)0)
#else
#  define SLUT_DCHECK(c) SLUT_CHECK(c)
#  define SLUT_DCHECK_OP(a, op, b) SLUT_CHECK_OP(a, op, b)
#endif
#define SLUT_DCHECK_LT(a, b) SLUT_DCHECK_OP(a, <, b)
#define SLUT_DCHECK_LE(a, b) SLUT_DCHECK_OP(a, <=, b)
#define SLUT_DCHECK_GT(a, b) SLUT_DCHECK_OP(a, >, b)
#define SLUT_DCHECK_GE(a, b) SLUT_DCHECK_OP(a, >=, b)

#define SLUT_INT(x) ((int)(x))
#define SLUT_DOUBLE(x) ((double)(x))
#define SLUT_INFINITE_ABOVE 1e300 /* a length, S or r above this is +∞ */
#define SLUT_TINY 1e-300          /* below this an argument counts as 0 */
#define SLUT_DBL_MIN_NORMAL 2.2250738585072014e-308 /* smallest normal double */
#define SLUT_DBL_MAX 1.7976931348623157e+308        /* largest finite double */

/* π/2 split so that π/2 − v is exact for v near π/2 (Sterbenz, plus the tail). */
#define SLUT_PI 3.14159265358979323846
#define SLUT_PIO2_HI 1.57079632679489655800e+00 /* double nearest π/2 */
#define SLUT_PIO2_LO 6.12323399573676603587e-17 /* π/2 − SLUT_PIO2_HI */
#define SLUT_INV_4PI 0.07957747154594766788    /* isotropic phase function, 1/sr */

/* π/2 − v without cancellation for v ∈ [0, π/2]. */
SLUT_FN double slut_pio2_minus(double v) { return (SLUT_PIO2_HI - v) + SLUT_PIO2_LO; }

SLUT_FN double slut_clamp(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

#endif /* SLUT_COMPAT_H */
