// scatterlut -- GLSL sampling snippet for the airlight table (kind "airlight_F",
// quantity version 1). Samples the table exactly as the C++ runtime does
// (scatterlut::AirlightTable::scaled_tail / radiance, tables/src/airlight.cpp) and
// evaluates the airlight radiance of a point light in a homogeneous medium.
//
// WRITTEN BY HAND, in single precision, from kernels/slut_axes.h and
// kernels/slut_airlight.h (the one home of every formula; read the derivations there and
// in docs/AIRLIGHT.md). The part between the SHARED BODY markers is byte-identical in
// scatterlut_airlight.hlsl. tests/test_shaders.cpp keeps both from drifting: it checks
// that the bodies are identical and that the constants equal the C header's, compiles
// both files with glslang, and runs them on the GPU (Mesa llvmpipe through EGL) against
// the C++ sampler on a real table. Usage and measured precision: docs/SHADERS.md.
//
// Requirements: GLSL 3.30+ / GLSL ES 3.00+ (texelFetch, uintBitsToFloat), highp float,
// or Vulkan GLSL. Include it (paste it, or #include with GL_GOOGLE_include_directive)
// after your #version line and before code that calls it.
//
// The texture (one 2-D texture, no mipmaps):
//   format     R32F (single channel, 32-bit float; never 16-bit, never sRGB)
//   texel      (iu, iw) = stored value of channel 0 "ln_Gs" = ln Gs at node iu of axis 0
//              (u) and node iw of axis 1 (w): width = u count, height = w count. Axis 0
//              varies fastest in the file payload, so the payload is the texture's rows.
//   sampler    default path: any (texelFetch, the bilinear is done in the shader);
//              SLUT_AIRLIGHT_HARDWARE_FILTER: GL_LINEAR min/mag (not a mipmap filter),
//              GL_CLAMP_TO_EDGE on both axes.
//
// The table metadata (uniforms / constants; read them from the file's axes):
//   u_max    axes[0].max    (u axis: min 0, warp log1p)          e.g. 64
//   u_scale  axes[0].scale  (the log1p scale)                    e.g. 1e-7
//   u_count  axes[0].count  (texture width)                      e.g. 512
//   w_min    axes[1].min    (w axis: max pi/2, warp asinh_cot)    e.g. 1e-3
//   w_count  axes[1].count  (texture height)                     e.g. 256
// Build a SlutAirlightTable with slut_airlight_table(u_max, u_scale, u_count, w_min,
// w_count); for other warps fill its two SlutAxis fields yourself (SLUT_WARP_* ids as in
// the file).
//
// Coordinates: node i of an axis sits at unit coordinate x = i/(n - 1) (the domain ends
// are the first and last texel centres); the texture coordinate is (x*(n - 1) + 0.5)/n;
// x is clamped (clamp-to-edge, never wrap). Beyond the table the asymptotic forms take
// over (u > u_max: Watson series; w < w_min: the e^a E_n form), never a clamp.
//
// Entry points (texture arguments: SLUT_TEX_ARG-style, i.e. the sampler2D):
//   float slut_airlight_radiance(sampler2D t, SlutAirlightTable tbl, float sigma_s_per_m,
//       float sigma_a_per_m, float intensity_W_per_sr, float distance_m,
//       float sin_gamma, float cos_gamma, float length_m)
//     radiance in W/(m^2*sr). gamma = angle between the view direction and the direction
//     FROM THE VIEWER TO THE LIGHT (gamma = 0: looking at the light). Pass sin gamma = |d x l|
//     and cos gamma = d*l of the normalised vectors (never 1 - cos from a dot product).
//     length_m = ray length inside the medium; >= SLUT_AIRLIGHT_INFINITE_LENGTH (1e30) or
//     +inf for a ray that never leaves it. Returns +inf when the ray passes through the
//     light (sin gamma = 0, cos gamma > 0, length >= distance), 0 for sigma_s = 0, I0 = 0, length = 0.
//   float slut_airlight_radiance_points(sampler2D t, SlutAirlightTable tbl,
//       vec3 viewer_m, vec3 view_dir, vec3 light_m, float length_m,
//       float sigma_s_per_m, float sigma_a_per_m, float intensity_W_per_sr)
//     the same from positions (view_dir need not be normalised).
//   float slut_airlight_scaled_tail(sampler2D t, SlutAirlightTable tbl, float u, float w,
//       float a)                          Gs(u, w) with a = u*cot w given by the caller
//   float slut_airlight_scaled_tail_uw(sampler2D t, SlutAirlightTable tbl, float u, float w)
//
// Options (#define before including):
//   SLUT_AIRLIGHT_HARDWARE_FILTER  one bilinear texture fetch instead of four texelFetch.
//     Cheaper, but GPUs filter with 8-bit fixed-point weights: ~1e-4 relative error in Gs
//     at 512x256 instead of ~1e-6 (see docs/SHADERS.md for the measured numbers).

#ifndef SCATTERLUT_AIRLIGHT_GLSL
#define SCATTERLUT_AIRLIGHT_GLSL

// ------------------------------------------------------------ GLSL prelude (language glue)

#define SLUT_TEX_PARAM sampler2D slut_ln_gs_tex
#define SLUT_TEX_ARG slut_ln_gs_tex
#define SLUT_FLOAT3 vec3

float slut_inf() { return uintBitsToFloat(0x7F800000u); }

// Stored ln Gs at node (iu, iw).
float slut_ln_gs_texel(SLUT_TEX_PARAM, int iu, int iw) {
    return texelFetch(slut_ln_gs_tex, ivec2(iu, iw), 0).r;
}
// Hardware bilinear of the stored ln Gs at texture coordinate (tcu, tcw).
float slut_ln_gs_filtered(SLUT_TEX_PARAM, float tcu, float tcw) {
    return textureLod(slut_ln_gs_tex, vec2(tcu, tcw), 0.0).r;
}

// 16-point Gauss-Legendre on [-1, 1]: positive nodes and weights (slut_gl16_x/_w rounded).
const float slut_gl16_x[8] = float[8](
    0.0950125098376374401853, 0.28160355077925891323, 0.458016777657227386342,
    0.617876244402643748447, 0.755404408355003033895, 0.86563120238783174388,
    0.944575023073232576078, 0.989400934991649932596);
const float slut_gl16_w[8] = float[8](
    0.189450610455068496285, 0.182603415044923588867, 0.169156519395002538189,
    0.149595988816576732082, 0.124628971255533872052, 0.0951585116824927848099,
    0.0622535239386478928628, 0.0271524594117540948518);

// ==== BEGIN SHARED BODY (identical in scatterlut_airlight.glsl and .hlsl) ====

// Warp ids as stored in table files (kernels/slut_axes.h; never renumber).
#define SLUT_WARP_LINEAR 0
#define SLUT_WARP_LOG 1
#define SLUT_WARP_LOG1P 2
#define SLUT_WARP_ASINH_COT 3
#define SLUT_WARP_SQRT1P 4
#define SLUT_WARP_LOGLIN 5
// The near-light slab axis: its unit coordinate also needs T and g (slut_nl_unit_from_S in
// kernels/slut_nearlight.h); as a one-parameter warp it is log in S, exact at g = 1 only.
#define SLUT_WARP_NL_QODDS 6
// Which representation serves Gs(u, w) (kernels/slut_airlight.h, slut_gs_regime).
#define SLUT_GS_TABLE 0
#define SLUT_GS_LARGE_U 1
#define SLUT_GS_SMALL_W 2

// pi/2 = SLUT_PIO2_HI + SLUT_PIO2_LO: the float nearest pi/2 (above it) and the rest.
#define SLUT_PIO2_HI 1.57079637050628662109375
#define SLUT_PIO2_LO (-4.37113900018624283e-8)
// pi = SLUT_PI_HI + SLUT_PI_LO, likewise.
#define SLUT_PI_HI 3.1415927410125732421875
#define SLUT_PI_LO (-8.74227800037248566e-8)
// Isotropic phase function, 1/sr.
#define SLUT_INV_4PI 0.0795774715459476679
// Ray lengths >= this are infinite rays (as is +inf).
#define SLUT_AIRLIGHT_INFINITE_LENGTH 1e30
// sin gamma = 0 is nudged to this (the limits are finite; the C code uses 1e-300).
#define SLUT_SIN_GAMMA_FLOOR 1e-20
// Bound on the theta-integral's panels (the C code allows 20000; float needs far fewer).
#define SLUT_THETA_MAX_PANELS 400

// One axis as the maps need it (slut_axis in kernels/slut_axes.h).
struct SlutAxis {
    float p_min; // parameter at node 0
    float p_max; // parameter at node count - 1
    float scale; // warp parameter (LOG1P: s); unused by the others
    int warp;    // SLUT_WARP_*
    int count;   // nodes = texels along this axis, >= 2
};

// The airlight table: axis 0 u = sigma_t D sin gamma in [0, u_max], axis 1
// w = pi/2 - v in [w_min, pi/2].
struct SlutAirlightTable {
    SlutAxis u;
    SlutAxis w;
};

SlutAirlightTable slut_airlight_table(float u_max, float u_scale, int u_count, float w_min,
                                      int w_count) {
    SlutAirlightTable t;
    t.u.p_min = 0.0;
    t.u.p_max = u_max;
    t.u.scale = u_scale;
    t.u.warp = SLUT_WARP_LOG1P;
    t.u.count = u_count;
    t.w.p_min = w_min;
    t.w.p_max = SLUT_PIO2_HI;
    t.w.scale = 1.0;
    t.w.warp = SLUT_WARP_ASINH_COT;
    t.w.count = w_count;
    return t;
}

// sin x and cos x for x in [0, pi/2 + 1e-7] with ~1 ulp relative error: Taylor polynomials
// on [0, pi/4] (truncation < 3e-9) and pi/2 - x (hi/lo split: exact) above. GPU sin/cos are
// only specified to an absolute error (2^-11 in GLSL), useless for sin of a small angle.
void slut_sincos(float x, out float s, out float c) {
    bool upper = x > 0.785398163397448;
    float r = upper ? ((SLUT_PIO2_HI - x) + SLUT_PIO2_LO) : x;
    float r2 = r * r;
    float sr = r * (1.0 + r2 * (-1.0 / 6.0 + r2 * (1.0 / 120.0 + r2 * (-1.0 / 5040.0 +
                      r2 * (1.0 / 362880.0)))));
    float cr = 1.0 + r2 * (-0.5 + r2 * (1.0 / 24.0 + r2 * (-1.0 / 720.0 + r2 * (1.0 / 40320.0 +
                      r2 * (-1.0 / 3628800.0)))));
    s = upper ? cr : sr;
    c = upper ? sr : cr;
}

float slut_sin(float x) {
    float s;
    float c;
    slut_sincos(x, s, c);
    return s;
}

// atan2(y, x) with ~2e-7 relative error over the whole range, small results included.
// GPU atan is specified to an absolute error only (Mesa llvmpipe: 2e-5 relative at
// atan(5e-4)), while w1, w2 and dv are small angles whose relative error goes straight
// into the radiance. Reduction to t = min/max in [0, 1], then to |t| <= tan(pi/8), and
// the minimax polynomial of Cephes' atanf (S. L. Moshier, Cephes Math Library).
float slut_atan2(float y, float x) {
    float ax = abs(x);
    float ay = abs(y);
    if (!(ay > 0.0) && !(ax > 0.0)) return 0.0;
    bool swap = ay > ax;
    float t = swap ? ax / ay : ay / ax;
    float base = 0.0;
    if (t > 0.414213562373095) {
        base = 0.785398163397448;
        t = (t - 1.0) / (t + 1.0);
    }
    float z = t * t;
    float a = base + ((((8.05374449538e-2 * z - 1.38776856032e-1) * z + 1.99777106478e-1) * z -
                       3.33329491539e-1) * z * t + t);
    if (swap) a = (SLUT_PIO2_HI - a) + SLUT_PIO2_LO;
    if (x < 0.0) a = (SLUT_PI_HI - a) + SLUT_PI_LO;
    return (y < 0.0) ? -a : a;
}

// Warp g(p) (slut_warp_forward). Only absolute accuracy of g matters here (it becomes a
// texel position), so log(1 + z) serves for log1p. ASINH_COT: -asinh(cot p) =
// ln(sin p/(1 + cos p)), full precision as p -> 0.
float slut_warp_forward(int warp, float p, float p_min, float scale) {
    if (warp == SLUT_WARP_LOG) return log(p);
    if (warp == SLUT_WARP_LOG1P) return log(1.0 + (p - p_min) / scale);
    if (warp == SLUT_WARP_ASINH_COT) {
        float s;
        float c;
        slut_sincos(p, s, c);
        return log(s / (1.0 + c));
    }
    if (warp == SLUT_WARP_SQRT1P) return sqrt(max(1.0 + p, 0.0));
    if (warp == SLUT_WARP_LOGLIN) return log(p) + p / scale;
    if (warp == SLUT_WARP_NL_QODDS) return log(p);
    return p;
}

// Parameter -> position in texels from node 0, clamped to [0, count - 1]: x*(count - 1)
// with x the unit coordinate (slut_unit_from_param, clamped as slut_cell_from_unit does).
float slut_axis_texel_position(SlutAxis a, float p) {
    float g0 = slut_warp_forward(a.warp, a.p_min, a.p_min, a.scale);
    float g1 = slut_warp_forward(a.warp, a.p_max, a.p_min, a.scale);
    float x = (slut_warp_forward(a.warp, p, a.p_min, a.scale) - g0) / (g1 - g0);
    return clamp(x, 0.0, 1.0) * float(a.count - 1);
}

// Interpolated stored ln Gs at (u, w): bilinear in the unit coordinates, on the stored
// values, exactly the C++ sampler (scatterlut::sample_encoded).
float slut_airlight_ln_gs(SLUT_TEX_PARAM, SlutAirlightTable tbl, float u, float w) {
    float tu = slut_axis_texel_position(tbl.u, u);
    float tw = slut_axis_texel_position(tbl.w, w);
#ifdef SLUT_AIRLIGHT_HARDWARE_FILTER
    // Texel centres: (x*(n - 1) + 0.5)/n.
    return slut_ln_gs_filtered(SLUT_TEX_ARG, (tu + 0.5) / float(tbl.u.count),
                               (tw + 0.5) / float(tbl.w.count));
#else
    int iu = min(int(tu), tbl.u.count - 2);
    int iw = min(int(tw), tbl.w.count - 2);
    float fu = tu - float(iu);
    float fw = tw - float(iw);
    float v00 = slut_ln_gs_texel(SLUT_TEX_ARG, iu, iw);
    float v10 = slut_ln_gs_texel(SLUT_TEX_ARG, iu + 1, iw);
    float v01 = slut_ln_gs_texel(SLUT_TEX_ARG, iu, iw + 1);
    float v11 = slut_ln_gs_texel(SLUT_TEX_ARG, iu + 1, iw + 1);
    return (1.0 - fw) * ((1.0 - fu) * v00 + fu * v10) + fw * ((1.0 - fu) * v01 + fu * v11);
#endif
}

// e^a E_n(a), n >= 1, a >= 0 (slut_exp_expint): continued fraction (modified Lentz) for
// a >= 1, series for E_1 and the upward recurrence below; 1/(a + n) once a > 1e6
// (relative error n/a^2 < 1e-11; also keeps a = +inf finite).
float slut_exp_expint(int n, float a) {
    float fn = float(n);
    if (a > 1e6) return 1.0 / (a + fn);
    if (a >= 1.0) {
        float b = a + fn;
        float c = 1e30;
        float d = 1.0 / b;
        float h = d;
        for (int i = 1; i < 100; ++i) {
            float an = -float(i) * (fn - 1.0 + float(i));
            b += 2.0;
            d = 1.0 / (an * d + b);
            c = b + an / c;
            float del = c * d;
            h *= del;
            if (abs(del - 1.0) < 1e-7) break;
        }
        return h;
    }
    if (a <= 0.0) return (n == 1) ? slut_inf() : 1.0 / (fn - 1.0);
    float sum = 0.0;
    float term = 1.0;
    for (int k = 1; k < 30; ++k) {
        term *= -a / float(k); // (-a)^k / k!
        sum += term / float(k);
        if (abs(term) < 1e-9) break;
    }
    float e_m = exp(a) * (-0.57721566490153286061 - log(a) - sum); // e^a E_1(a)
    for (int m = 1; m < n; ++m) e_m = (1.0 - a * e_m) / float(m);
    return e_m;
}

// Gs as w -> 0 at fixed a = u*cot w (slut_gs_small_w):
// (tan w / w)*[e^a E_2(a) - tan^2 w * e^a E_4(a)], error <= w^4/5.
float slut_gs_small_w(float w, float a) {
    float s;
    float c;
    slut_sincos(w, s, c);
    float tw = s / c;
    float ratio = (w > 1e-20) ? tw / w : 1.0;
    return ratio * (slut_exp_expint(2, a) - tw * tw * slut_exp_expint(4, a));
}

// Gs for large u (slut_gs_large_u), Watson's lemma summed to its smallest term:
// (1/w) sum_k (-1)^k k! (sin w)^{k+1} sin((k+1) w) / u^{k+1}. sin((k+1)w) by rotation
// (no cancellation, no large arguments). Gs(u, 0) = 0.
float slut_gs_large_u(float u, float w) {
    float sw;
    float cw;
    slut_sincos(w, sw, cw);
    float x = sw / u;
    float power = x;
    float sum = 0.0;
    float last = slut_inf();
    float sk = sw; // sin((k+1) w)
    float ck = cw; // cos((k+1) w)
    for (int k = 0; k < 12; ++k) {
        float term = power * sk;
        if (abs(term) > last && k > 2) break;
        sum += ((k & 1) != 0) ? -term : term;
        last = abs(term);
        power *= x * float(k + 1);
        float sn = sk * cw + ck * sw;
        ck = ck * cw - sk * sw;
        sk = sn;
    }
    return (w > 0.0) ? sum / w : 0.0;
}

int slut_gs_regime(float u, float w, float u_max, float w_min) {
    if (u > u_max) return SLUT_GS_LARGE_U;
    if (w < w_min) return SLUT_GS_SMALL_W;
    return SLUT_GS_TABLE;
}

// Gs(u, w) with a = u*cot w given by the caller (AirlightTable::scaled_tail): the table
// inside its domain, the asymptotic forms outside (never clamped).
float slut_airlight_scaled_tail(SLUT_TEX_PARAM, SlutAirlightTable tbl, float u, float w,
                                float a) {
    int regime = slut_gs_regime(u, w, tbl.u.p_max, tbl.w.p_min);
    if (regime == SLUT_GS_LARGE_U) return slut_gs_large_u(u, w);
    if (regime == SLUT_GS_SMALL_W) return slut_gs_small_w(w, a);
    return exp(slut_airlight_ln_gs(SLUT_TEX_ARG, tbl, u, w));
}

float slut_airlight_scaled_tail_uw(SLUT_TEX_PARAM, SlutAirlightTable tbl, float u, float w) {
    float s;
    float c;
    slut_sincos(w, s, c);
    return slut_airlight_scaled_tail(SLUT_TEX_ARG, tbl, u, w, u * (c / s));
}

// Everything the radiance needs (slut_airlight_geometry). kind: 0 finite, 1 zero
// radiance, 2 divergent (the ray passes through the light).
struct SlutAirlightGeometry {
    int kind;
    float scale;           // sigma_s/(4pi)*I0*2e^{-sigma_t D}/D
    float sin_gamma;       // sin gamma, >= SLUT_SIN_GAMMA_FLOOR
    float u;               // sigma_t D sin gamma
    float w2;              // pi/2 - gamma/2: viewer end
    float a2;              // u*cot w2 = sigma_t D (1 - cos gamma)
    float w1;              // 0.5 atan2(D sin gamma, s - D cos gamma): far end (0: infinite ray)
    float a1;              // u*cot w1 = sigma_t (s + d(s) - D cos gamma)
    float far_attenuation; // e^{-sigma_t Delta}, Delta = s + d(s) - D >= 0
    float c;               // 2sigma_t D sin(gamma/2)
    float dv;              // w2 - w1 = 0.5 atan2(s sin gamma, D - s cos gamma)
};

// slut_airlight_setup in float: every quantity from sin gamma and cos gamma without cancellation;
// d(s) and Delta are scaled so that no square overflows.
SlutAirlightGeometry slut_airlight_setup(float sigma_s, float sigma_a, float intensity,
                                         float distance_m, float sin_gamma, float cos_gamma,
                                         float length_m) {
    SlutAirlightGeometry g;
    g.kind = 0;
    g.scale = 0.0;
    g.sin_gamma = 1.0;
    g.u = 0.0;
    g.w2 = 0.0;
    g.a2 = 0.0;
    g.w1 = 0.0;
    g.a1 = 0.0;
    g.far_attenuation = 0.0;
    g.c = 0.0;
    g.dv = 0.0;
    float sigma_t = sigma_s + sigma_a;
    float dist = distance_m;
    float s = length_m;
    if (!(sigma_s > 0.0) || !(intensity > 0.0) || !(s > 0.0)) {
        g.kind = 1;
        return g;
    }
    if (!(sin_gamma > 0.0) && cos_gamma > 0.0 && s >= dist) {
        g.kind = 2;
        return g;
    }
    float sg = max(sin_gamma, SLUT_SIN_GAMMA_FLOOR);
    // 1 - cos gamma and sin(gamma/2) without cancellation on either side.
    float one_minus_cos = (cos_gamma > 0.0) ? sg * (sg / (1.0 + cos_gamma)) : 1.0 - cos_gamma;
    float sin_half = (cos_gamma > 0.0) ? sg / sqrt(2.0 * (1.0 + cos_gamma))
                                       : sqrt(0.5 * (1.0 - cos_gamma));
    g.sin_gamma = sg;
    g.scale = sigma_s * SLUT_INV_4PI * intensity * 2.0 * exp(-sigma_t * dist) / dist;
    g.u = sigma_t * dist * sg;
    g.w2 = 0.5 * slut_atan2(sg, -cos_gamma);
    g.a2 = sigma_t * dist * one_minus_cos;
    g.c = 2.0 * sigma_t * dist * sin_half;
    if (!(s < SLUT_AIRLIGHT_INFINITE_LENGTH)) { // an infinite ray: the far end is at xi = pi/2
        g.w1 = 0.0;
        g.a1 = slut_inf();
        g.far_attenuation = 0.0;
        g.dv = g.w2;
        return g;
    }
    // d(s)^2 = (s - D)^2 + 4sD sin^2(gamma/2); Delta = s + d - D = s + s(s - 2D cos gamma)/(d + D).
    float m = max(s, dist);
    float sm = s / m;
    float dm = dist / m;
    float d_far = m * sqrt((sm - dm) * (sm - dm) + 4.0 * sm * dm * sin_half * sin_half);
    g.w1 = 0.5 * slut_atan2(dist * sg, s - dist * cos_gamma);
    g.a1 = sigma_t * (s + d_far - dist * cos_gamma);
    float delta = s + s * ((s - 2.0 * dist * cos_gamma) / (d_far + dist));
    g.far_attenuation = exp(-sigma_t * max(delta, 0.0));
    g.dv = 0.5 * slut_atan2(s * sg, dist - s * cos_gamma);
    return g;
}

// int_0^{dv} exp(-c sin theta / sin(w2 - theta)) dtheta (slut_airlight_theta_integral): panels of
// 16-point Gauss-Legendre placed by the distance delta to the pole theta = w2, length <= delta/4 and
// <= 4/lambda (lambda = c sin w2 / sin^2 delta, the local decay rate); stops when the log-concave
// remainder bound drops below 1e-8 of the sum (float).
float slut_airlight_theta_integral(float c, float w2, float dv) {
    if (dv <= 0.0) return 0.0;
    if (c <= 0.0) return dv;
    float sin_w2 = slut_sin(w2);
    float delta = w2;     // distance from the panel start to the pole
    float remaining = dv; // distance from the panel start to the end
    float sum = 0.0;
    for (int panel = 0; panel < SLUT_THETA_MAX_PANELS && remaining > 0.0; ++panel) {
        float theta = dv - remaining;
        float sd = slut_sin(delta);
        float rate = c * sin_w2 / sd / sd;
        float f_start = exp(-c * slut_sin(theta) / sd);
        if (panel > 0 && f_start <= 1e-8 * sum * rate) break;
        float h = min(remaining, min(0.25 * delta, 4.0 / rate));
        float hl = 0.5 * h;
        float part = 0.0;
        for (int k = 0; k < 8; ++k) {
            float x0 = hl - hl * slut_gl16_x[k]; // offsets in the panel
            float x1 = hl + hl * slut_gl16_x[k];
            part += slut_gl16_w[k] * (exp(-c * slut_sin(theta + x0) / slut_sin(delta - x0)) +
                                      exp(-c * slut_sin(theta + x1) / slut_sin(delta - x1)));
        }
        sum += hl * part;
        remaining -= h;
        delta -= h;
    }
    return sum;
}

// Radiance from Gs at the two ends (slut_airlight_from_gs), the theta-integral where the
// difference would cancel (far-end term > half the viewer-end term).
float slut_airlight_from_gs(SlutAirlightGeometry g, float gs2, float gs1) {
    if (g.kind == 1) return 0.0;
    if (g.kind == 2) return slut_inf();
    float viewer_term = (g.w2 / g.sin_gamma) * gs2;
    float far_term = (g.w1 > 0.0) ? g.far_attenuation * (g.w1 / g.sin_gamma) * gs1 : 0.0;
    if (far_term <= 0.5 * viewer_term) return g.scale * (viewer_term - far_term);
    return g.scale * (slut_airlight_theta_integral(g.c, g.w2, g.dv) / g.sin_gamma);
}

// Airlight radiance, W/(m^2*sr) for I0 in W/sr, coefficients in 1/m, lengths in m
// (AirlightTable::radiance). gamma: view direction <-> direction viewer -> light.
float slut_airlight_radiance(SLUT_TEX_PARAM, SlutAirlightTable tbl, float sigma_s_per_m,
                             float sigma_a_per_m, float intensity_W_per_sr, float distance_m,
                             float sin_gamma, float cos_gamma, float length_m) {
    SlutAirlightGeometry g = slut_airlight_setup(sigma_s_per_m, sigma_a_per_m,
                                                 intensity_W_per_sr, distance_m, sin_gamma,
                                                 cos_gamma, length_m);
    if (g.kind != 0) return slut_airlight_from_gs(g, 0.0, 0.0);
    float gs2 = slut_airlight_scaled_tail(SLUT_TEX_ARG, tbl, g.u, g.w2, g.a2);
    float gs1 = (g.w1 > 0.0) ? slut_airlight_scaled_tail(SLUT_TEX_ARG, tbl, g.u, g.w1, g.a1)
                             : 0.0;
    return slut_airlight_from_gs(g, gs2, gs1);
}

// The same from positions (airlight_query_from_points): gamma = atan2(|d x l|, d*l), passed
// as the normalised pair, so gamma -> 0 and gamma -> pi keep their precision. A viewer at the
// light sees a divergent integral (+inf).
float slut_airlight_radiance_points(SLUT_TEX_PARAM, SlutAirlightTable tbl, SLUT_FLOAT3 viewer_m,
                                    SLUT_FLOAT3 view_dir, SLUT_FLOAT3 light_m, float length_m,
                                    float sigma_s_per_m, float sigma_a_per_m,
                                    float intensity_W_per_sr) {
    SLUT_FLOAT3 to_light = light_m - viewer_m;
    float dist = length(to_light);
    if (!(dist > 0.0)) return slut_inf();
    float sin_part = length(cross(view_dir, to_light));
    float cos_part = dot(view_dir, to_light);
    float norm = sqrt(sin_part * sin_part + cos_part * cos_part);
    return slut_airlight_radiance(SLUT_TEX_ARG, tbl, sigma_s_per_m, sigma_a_per_m,
                                  intensity_W_per_sr, dist, sin_part / norm, cos_part / norm,
                                  length_m);
}

// ==== END SHARED BODY ====

#endif // SCATTERLUT_AIRLIGHT_GLSL
