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
 * A third compiler: the headers the GPU snippets list (SLUT_SHADER_HEADERS in the top-level
 * CMakeLists.txt: slut_axes.h, slut_airlight.h and its parts, the near-light parts but the
 * sweep, slut_phase.h and slut_airlight_hg.h and its parts) are
 * compiled once more, whole, as GLSL, GLSL ES 3.00 and HLSL in float, for the GPU sampling snippets
 * (cmake/assemble_shaders.cmake; the SLUT_SHADER branch below, the float math of
 * tables/shaders/src/common.slsl and the per-language preludes). Code the snippets
 * compile keeps to the subset the five languages share:
 *   - structs passed and returned by value (never pointers to them), declared with
 *     SLUT_STRUCT_BEGIN(name) ... SLUT_STRUCT_END(name);
 *   - constant arrays as SLUT_CONST_ARRAY3/4/8(name, values...), an array output
 *     parameter as SLUT_OUT_ARRAY(type, name, size);
 *   - conversions only through SLUT_INT(x) and SLUT_DOUBLE(x) (GLSL has no C casts and
 *     no implicit int → float); a condition is a comparison, never a bare int, and an int
 *     made from a comparison is written `cond ? 1 : 0`;
 *   - every threshold or iteration cap that depends on the precision is a macro defined
 *     here for both (SLUT_TINY, SLUT_INFINITE_ABOVE, SLUT_CF_CONVERGED, ...): 1e300 or
 *     1e-17 has no float;
 *   - math only from the functions the SLUT_SHADER branch maps, each explicitly (to a float
 *     version that keeps relative precision, or to the GPU built-in where that is enough:
 *     common.slsl says which and why); a call to anything else fails the snippet build.
 *   - a conditional value whose operands compute something is SLUT_SELECT(c, a, b) (c ? a : b,
 *     both operands evaluated in the shaders: a select). ANGLE, WebGL's GLSL ES compiler on
 *     Vulkan, lowers `c ? a : b` with computed operands to a branch; SwiftShader (Chromium's
 *     WebGL2 without a GPU) compiles a chain of such branches in time that grows exponentially:
 *     one spot light (kernels/slut_spot_rule.h) took 148 s with `?:` and 0.2 s with
 *     SLUT_SELECT (bench/README.md, "Compile cost on SwiftShader"). Operands must be side-effect
 *     free and defined for every input (both are computed on the GPU).
 * Code outside that subset (the generator's quadratures, the runtime's fast paths) sits in
 * `#ifndef SLUT_SHADER` blocks.
 */
#ifndef SLUT_COMPAT_H
#define SLUT_COMPAT_H

#ifdef SLUT_SHADER
/* GLSL / GLSL ES 3.00 / HLSL in float. The per-language prelude defines slut_inf and the
 * SLUT_CONST_ARRAY* macros; tables/shaders/src/common.slsl the float math mapped below. */
#  define SLUT_FN
#  define SLUT_GLOBAL
#  define SLUT_CHECK(c)
#  define SLUT_CHECK_OP(a, op, b)
#  define SLUT_HUGE_VAL slut_inf()
#  define SLUT_ISFINITE(x) (abs(x) < SLUT_INFINITE_ABOVE) /* lengths ≥ 1e30 are infinite rays */
#  define SLUT_STRUCT_BEGIN(name) struct name {
#  define SLUT_STRUCT_END(name) }
#  define SLUT_OUT_ARRAY(type, name, size) out type name[size]
#  define SLUT_INT(x) int(x)
#  define SLUT_DOUBLE(x) float(x)
/* Every math function shared code may call (undefined again after the shared code). */
#  define double float
#  define fabs(x) abs(x)
#  define fmin(a, b) min(a, b)
#  define fmax(a, b) max(a, b)
#  define sqrt(x) slut_sqrt(x)
#  define exp(x) slut_exp(x)
#  define log(x) slut_log(x)
#  define log1p(x) slut_log1p(x)
#  define expm1(x) slut_expm1(x)
#  define sin(x) slut_sin(x)
#  define cos(x) slut_cos(x)
#  define tan(x) slut_tan(x)
#  define sinh(x) slut_sinh(x)
#  define atan(x) slut_atan2(x, 1.0)
#  define atan2(y, x) slut_atan2(y, x)
#  define pow(x, y) slut_pow(x, y)
/* float's thresholds and caps (the double ones below). */
#  define SLUT_INFINITE_ABOVE 1e30
#  define SLUT_TINY 1e-30
#  define SLUT_REAL_MIN_NORMAL 1.17549435e-38
#  define SLUT_REAL_MAX 3.40282347e38
#  define SLUT_SQUARABLE_MIN 1e-18
#  define SLUT_SQUARABLE_MAX 1e18
#  define SLUT_CF_CONVERGED 1e-7
#  define SLUT_SERIES_NEGLIGIBLE 1e-9
#  define SLUT_REMAINDER_NEGLIGIBLE 1e-8
#  define SLUT_HG_SERIES_ACCEPT 1e-6
#  define SLUT_EXPINT_CF_MAX_ITER 100
#  define SLUT_EXPINT_SERIES_MAX_TERMS 30
#  define SLUT_EXPINT_LEADING_ABOVE 1e6
#  define SLUT_THETA_MAX_PANELS 400
#  define SLUT_IN_PLANE_TOLERANCE 1e-6
#  define SLUT_LOGLIN_MAX_STEPS 60
#  define SLUT_LOGLIN_CONVERGED 2.4e-7
#  define SLUT_SPOT_TANGENT_SLACK 1e-6
#  define SLUT_SPOT_MIN_MISS 1e-12
/* (1 + cos x)/sin x for x in (0, π/2] from one polynomial sin/cos pair (common.slsl): the
   values of slut_cos and slut_sin, half their work (slut_warp_forward). */
#  define SLUT_ONE_PLUS_COS_OVER_SIN(x) slut_one_plus_cos_over_sin(x)
/* c ? a : b as a select (the prelude's slut_select overloads for float, int and bool; WGSL's
   prelude defines it as the ternary, which tables/shaders/wgsl/slut_wgsl.py writes as select()). */
#  ifndef SLUT_SELECT
#    define SLUT_SELECT(c, a, b) slut_select((c), (a), (b))
#  endif
/* SLUT_PIO2_HI and SLUT_PIO2_LO, π/2 split for float, come from common.slsl (its float
 * math needs them before this header). */
#endif

#ifndef SLUT_SHADER /* OpenCL C and C++ (the snippets drop this block) */
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
#endif /* !SLUT_SHADER */

#define SLUT_CHECK_EQ(a, b) SLUT_CHECK_OP(a, ==, b)
#define SLUT_CHECK_NE(a, b) SLUT_CHECK_OP(a, !=, b)
#define SLUT_CHECK_LT(a, b) SLUT_CHECK_OP(a, <, b)
#define SLUT_CHECK_LE(a, b) SLUT_CHECK_OP(a, <=, b)
#define SLUT_CHECK_GT(a, b) SLUT_CHECK_OP(a, >, b)
#define SLUT_CHECK_GE(a, b) SLUT_CHECK_OP(a, >=, b)
#if defined(SLUT_SHADER)
#  define SLUT_DCHECK(c)
#  define SLUT_DCHECK_OP(a, op, b)
#elif defined(NDEBUG) || defined(__OPENCL_VERSION__) || defined(__OPENCL_C_VERSION__)
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

#ifndef SLUT_SHADER
#define SLUT_SELECT(c, a, b) ((c) ? (a) : (b))
#define SLUT_STRUCT_BEGIN(name) typedef struct name {
#define SLUT_STRUCT_END(name) } name
#define SLUT_OUT_ARRAY(type, name, size) type *name
#define SLUT_CONST_ARRAY3(name, a0, a1, a2) SLUT_CONSTANT double name[3] = {a0, a1, a2}
#define SLUT_CONST_ARRAY4(name, a0, a1, a2, a3) SLUT_CONSTANT double name[4] = {a0, a1, a2, a3}
#define SLUT_CONST_ARRAY8(name, a0, a1, a2, a3, a4, a5, a6, a7) \
    SLUT_CONSTANT double name[8] = {a0, a1, a2, a3, a4, a5, a6, a7}
#define SLUT_INT(x) ((int)(x))
#define SLUT_DOUBLE(x) ((double)(x))
/* Thresholds and caps that depend on the precision (float values in the SLUT_SHADER branch). */
#define SLUT_INFINITE_ABOVE 1e300 /* a length, S or r above this is +∞ */
#define SLUT_TINY 1e-300          /* below this an argument counts as 0 */
#define SLUT_DBL_MIN_NORMAL 2.2250738585072014e-308 /* smallest normal double */
#define SLUT_DBL_MAX 1.7976931348623157e+308        /* largest finite double */
#define SLUT_REAL_MIN_NORMAL SLUT_DBL_MIN_NORMAL    /* smallest normal of the working type */
#define SLUT_REAL_MAX SLUT_DBL_MAX                  /* largest finite of the working type */
#define SLUT_SQUARABLE_MIN 1e-150 /* lengths in [MIN, MAX]: their squares and pairwise products stay normal */
#define SLUT_SQUARABLE_MAX 1e150
#define SLUT_CF_CONVERGED 1e-16       /* a continued fraction's step factor this close to 1: converged */
#define SLUT_SERIES_NEGLIGIBLE 1e-18  /* a series term this small against a sum of order 1: done */
#define SLUT_REMAINDER_NEGLIGIBLE 1e-17 /* a quadrature's remainder bound this small against its sum: done */
#define SLUT_HG_SERIES_ACCEPT 1e-13     /* an asymptotic series whose error bound is this small against its sum: used */
#define SLUT_EXPINT_CF_MAX_ITER 500       /* e^a E_n(a): continued-fraction steps */
#define SLUT_EXPINT_SERIES_MAX_TERMS 40   /* e^a E_1(a), a < 1: power-series terms */
#define SLUT_EXPINT_LEADING_ABOVE 1e300   /* e^a E_n(a) = 1/(a + n) above this (relative error n/a²) */
#define SLUT_THETA_MAX_PANELS 20000       /* θ-integral panels */
#define SLUT_IN_PLANE_TOLERANCE 1e-15     /* a unit-vector cosine this far below 0 is 0 (rounding) */
#define SLUT_LOGLIN_MAX_STEPS 60          /* slut_loglin_inverse: Newton steps at most */
#define SLUT_LOGLIN_CONVERGED 4e-16       /* slut_loglin_inverse: a relative step this small is the root */
#define SLUT_SPOT_TANGENT_SLACK 1.8e-15   /* a ray–cone discriminant this far below 0 (8 ulps of its terms): a tangent */
#define SLUT_SPOT_MIN_MISS 1e-12          /* the spot's band rule: the light's distance from the ray at least this × the scale */
/* (1 + cos x)/sin x (the ASINH_COT warps' log argument; one sin/cos pair in the shaders). */
#define SLUT_ONE_PLUS_COS_OVER_SIN(x) ((1.0 + cos(x)) / sin(x))

/* π/2 split so that π/2 − v is exact for v near π/2 (Sterbenz, plus the tail). */
#define SLUT_PIO2_HI 1.57079632679489655800e+00 /* double nearest π/2 */
#define SLUT_PIO2_LO 6.12323399573676603587e-17 /* π/2 − SLUT_PIO2_HI */
#endif /* !SLUT_SHADER */
#define SLUT_PI 3.14159265358979323846
#define SLUT_INV_4PI 0.07957747154594766788    /* isotropic phase function, 1/sr */

/* π/2 − v without cancellation for v ∈ [0, π/2]. */
SLUT_FN double slut_pio2_minus(double v) { return (SLUT_PIO2_HI - v) + SLUT_PIO2_LO; }

SLUT_FN double slut_clamp(double x, double lo, double hi) { return x < lo ? lo : (x > hi ? hi : x); }

#endif /* SLUT_COMPAT_H */
