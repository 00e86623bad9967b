// The near-light math on the device and the host: the OpenCL kernel against the
// independent Boost reference (tests/nearlight_reference.hpp), the r = 0 identity between
// the near-light and the airlight quantities, and the refracted ray against explicit
// quadrature.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <limits>
#include <stdexcept>
#include <string>
#include <random>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <gtest/gtest.h>

#include "eval.hpp"
#include "generate_nearlight.hpp"
#include "nearlight_reference.hpp"
#include "nearlight_tables.hpp"
#include "opencl_device.hpp"
#include "reference_data.hpp"
#include "scatterlut/airlight.hpp"
#include "table_build.hpp"

extern "C" {
#include "slut_nearlight.h"
}

using slut_test::default_e4;
using slut_test::device;
using slut_test::query_of;
using slut_test::small_table;

// Every node of a 3-D and a 4-D table against Boost Gauss–Kronrod with break points:
// ≤ 1e-8 relative (the bound asked of the kernel; we expect ~1e-14).
TEST(NearLightKernel, EveryNodeMatchesBoostReference) {
    for (bool finite : {false, true}) {
        const scatterlut::Table &t = small_table(finite);
        const scatterlut::NearLightTable table(t);
        double worst = 0;
        size_t node[4] = {0, 0, 0, 0};
        const size_t n_axes = t.axes.size();
        for (size_t flat = 0; flat < t.node_count(); ++flat) {
            size_t rest = flat;
            for (size_t a = 0; a < n_axes; ++a) {
                node[a] = rest % static_cast<size_t>(t.axes[a].map.count);
                rest /= static_cast<size_t>(t.axes[a].map.count);
            }
            double at[4]; // T, g, r, S (+inf in a thick table) by the table's own axis maps
            table.node_params(node, at);
            const double T = at[0], g = at[1], r = at[2], S = at[3];
            // S = 0: N and H vanish; E is their limit, the attenuation at the entry point:
            // e^{−T} for r = 0 (the whole light path inside), 1 for r > 0.
            const double want = S == 0.0 ? (r == 0.0 ? std::exp(-T) : 1.0)
                                         : static_cast<double>(slut_ref::nearlight_NHE(T, g, r, S).E);
            const double got = table.node_E(node);
            const double err = slut_test::rel_err(got, want);
            ASSERT_LE(err, 1e-8) << "T=" << T << " g=" << g << " r=" << r << " S=" << S;
            worst = std::max(worst, err);
        }
        std::printf("%s: %zu nodes, max rel err vs Boost %.2e\n", t.kind.c_str(), t.node_count(), worst);
        // The default integration tolerance 1e-11 (kNearLightIntegrationTolerance) measures
        // ~1e-11; 1e-10 is the tables' contract.
        EXPECT_LE(t.accuracy.integration_max_rel, 1e-10);
    }
}

// The kernel and the header's C++ sweep (the runtime's exact fallback) at the same nodes, on
// tables stretched to the hard corners: T from 1e-5 to 100, g down to −0.999999 (the ray
// grazes the light), r from 0 through 1e-12 to 1e6, S from 1e-8 to 200; 20 r nodes (a full
// and a partial lane group).
//  - Agreement: the C++ slut_nl_E_sweep with the kernel's r group and S list (the same panel
//    mesh), ≤ 1e-13 relative at every node: both run the same rules; only the builtins'
//    rounding differs (PoCL's vector exp and log against libm's, ~1 ulp per node).
//  - Accuracy: ≤ 1e-10 (the tables' contract) at every node against an independent finer mesh
//    (the C++ sweep at refine 2.5), and against the Boost reference where it claims 1e-15
//    (T ≥ 1e-3).
TEST(NearLightKernel, MatchesHostSweepAndReferenceAtHardCorners) {
    for (bool finite : {false, true}) {
        scatterlut::NearLightPlan plan = scatterlut::default_near_light_plan(finite);
        plan.T_min = 1e-5;
        plan.T_max = 100.0;
        plan.g_min = -0.999999;
        plan.r_max = 1e6;
        plan.r_scale = 1e-12;
        plan.S_min = 1e-8;
        plan.S_max = 200.0;
        plan.n_T = 7;
        plan.n_g = 9;
        plan.n_r = 20;
        plan.n_S = 6;
        const scatterlut::Table layout = scatterlut::make_nearlight_table_layout(plan);
        const std::vector<double> values = scatterlut::integrate_nearlight_ln_E(device(), layout);
        const double refine = slut_nl_refine_for_tolerance(plan.integration_tolerance);
        const auto &ax = layout.axes;
        const int n_S = finite ? ax[3].map.count : 1;
        double worst_host = 0, worst_fine = 0, worst_boost = 0;
        for (int iT = 0; iT < plan.n_T; ++iT) {
            const double T = slut_axis_node(&ax[0].map, iT);
            for (int ig = 0; ig < plan.n_g; ++ig) {
                const double g = slut_axis_node(&ax[1].map, ig);
                double S[SLUT_NL_MAX_SWEEP];
                for (int i = 0; i < n_S; ++i) S[i] = finite ? slut_nl_S_node(&ax[3].map, T, g, i) : HUGE_VAL;
                for (int ir0 = 0; ir0 < plan.n_r; ir0 += SLUT_NL_MAX_LANES) {
                    const int lanes = std::min(SLUT_NL_MAX_LANES, plan.n_r - ir0);
                    double r[SLUT_NL_MAX_LANES];
                    for (int l = 0; l < lanes; ++l) r[l] = slut_axis_node(&ax[2].map, ir0 + l);
                    std::vector<double> host(static_cast<size_t>(n_S * lanes)), fine(host.size());
                    slut_nl_E_sweep(T, g, S, n_S, r, lanes, host.data(), refine);
                    slut_nl_E_sweep(T, g, S, n_S, r, lanes, fine.data(), 2.5);
                    for (int i = 0; i < n_S; ++i) {
                        for (int l = 0; l < lanes; ++l) {
                            const size_t node[4] = {static_cast<size_t>(iT), static_cast<size_t>(ig),
                                                    static_cast<size_t>(ir0 + l), static_cast<size_t>(i)};
                            const double base = finite ? slut_nl_E_base(T, r[l], S[i]) : 1.0;
                            const double got = std::exp(values[layout.index(node)]) * base;
                            const size_t k = static_cast<size_t>(i * lanes + l);
                            const double e_host = slut_test::rel_err(got, host[k]);
                            const double e_fine = slut_test::rel_err(got, fine[k]);
                            ASSERT_LE(e_host, 1e-13) << "T=" << T << " g=" << g << " r=" << r[l] << " S=" << S[i];
                            ASSERT_LE(e_fine, 1e-10) << "T=" << T << " g=" << g << " r=" << r[l] << " S=" << S[i];
                            worst_host = std::max(worst_host, e_host);
                            worst_fine = std::max(worst_fine, e_fine);
                            if (T >= 1e-3 && S[i] > 0.0) {
                                const double want =
                                    static_cast<double>(slut_ref::nearlight_NHE(T, g, r[l], S[i]).E);
                                const double e_boost = slut_test::rel_err(got, want);
                                ASSERT_LE(e_boost, 1e-10)
                                    << "T=" << T << " g=" << g << " r=" << r[l] << " S=" << S[i];
                                worst_boost = std::max(worst_boost, e_boost);
                            }
                        }
                    }
                }
            }
        }
        std::printf("%s corners: %zu nodes, max rel vs host sweep %.2e, vs refine 2.5 %.2e, vs Boost %.2e\n",
                    layout.kind.c_str(), values.size(), worst_host, worst_fine, worst_boost);
    }
}

// r = 0 (the light in the surface plane, its whole path inside): N is the airlight
// integral with cos γ = −g, per unit σ_s p I0 σ_t: N = σ_t^{-1}·L_air/(σ_s p I0) with
// D = T/σ_t. Two independent computations (slut_nearlight.h's E·H and the airlight θ-integral) agree.
namespace {

// One of kernels/slut_nearlight_lanes.h's lane functions (double16 → double16) on the device:
// `function` applied to `args` (their count a multiple of 16), the program built with
// `extra_options` (a failed build throws with its log). Also whether the build took the
// AVX-512 integer steps (SLUT_NL_EXP_AVX512).
struct LaneResults {
    std::vector<double> out;
    int avx512;
};
LaneResults run_lane_function(const std::string &function, const std::vector<double> &args,
                              const std::string &extra_options = "") {
    scatterlut::Device &dev = device();
    const std::string source = "#include \"slut_nearlight_lanes.h\"\n"
                               "__kernel void lane_function(__global const double *in, __global double *out) {\n"
                               "    size_t i = get_global_id(0);\n"
                               "    vstore16(" + function + "(vload16(i, in)), i, out);\n"
                               "}\n"
                               "__kernel void exp_variant(__global int *avx512) { avx512[0] = SLUT_NL_EXP_AVX512; }\n";
    cl::Program program(dev.context(), source);
    const std::vector<cl::Device> devices = dev.context().getInfo<CL_CONTEXT_DEVICES>();
    const std::string options = std::string("-cl-std=CL1.2 -I ") + SLUT_SOURCE_DIR + "/kernels " + extra_options;
    try {
        program.build(devices, options.c_str());
    } catch (const cl::Error &) {
        throw std::runtime_error("build of " + function + " failed: " +
                                 program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(devices[0]));
    }
    LaneResults r{std::vector<double>(args.size()), -1};
    const cl::Buffer in = scatterlut::input_buffer(dev, args);
    const cl::Buffer out(dev.context(), CL_MEM_WRITE_ONLY, args.size() * sizeof(double));
    cl::Kernel kernel(program, "lane_function");
    kernel.setArg(0, in);
    kernel.setArg(1, out);
    dev.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(args.size() / 16), cl::NullRange);
    dev.queue().enqueueReadBuffer(out, CL_TRUE, 0, args.size() * sizeof(double), r.out.data());
    const cl::Buffer variant(dev.context(), CL_MEM_WRITE_ONLY, sizeof(int));
    cl::Kernel variant_kernel(program, "exp_variant");
    variant_kernel.setArg(0, variant);
    dev.queue().enqueueNDRangeKernel(variant_kernel, cl::NullRange, cl::NDRange(1), cl::NullRange);
    dev.queue().enqueueReadBuffer(variant, CL_TRUE, 0, sizeof(int), &r.avx512);
    return r;
}

// Arguments for a lane function: n uniform draws from [a, b], or (log_uniform) 2^U(a, b) times
// sign; `finish` appends the special values and pads to a multiple of 16 with `pad`.
struct LaneArguments {
    std::vector<double> values;
    std::mt19937_64 rng{20261203};
    void uniform(double a, double b, int n) {
        std::uniform_real_distribution<double> d(a, b);
        for (int i = 0; i < n; ++i) values.push_back(d(rng));
    }
    void log_uniform(double a, double b, int n, double sign = 1.0) {
        std::uniform_real_distribution<double> d(a, b);
        for (int i = 0; i < n; ++i) values.push_back(sign * std::exp2(d(rng)));
    }
    void finish(std::initializer_list<double> specials, double pad) {
        values.insert(values.end(), specials);
        while (values.size() % 16 != 0) values.push_back(pad);
    }
};

// |got − want| in ulps of the double nearest want (want finite and non-zero).
double ulps_from(double got, long double want) {
    const double want_d = static_cast<double>(want);
    const long double ulp = std::fabs(static_cast<long double>(std::nextafter(want_d, HUGE_VAL)) - want_d);
    return static_cast<double>(std::fabs(static_cast<long double>(got) - want) / ulp);
}

const double kInf = std::numeric_limits<double>::infinity();
const double kNaN = std::numeric_limits<double>::quiet_NaN();

} // namespace

// slut_nl_lanes_exp2 (the sweep's node-loop 2^v, kernels/slut_nearlight_lanes.h) against
// long double exp2l: ≤ 3 ulps wherever the result is normal, ≤ 3 subnormal steps below, 0 below
// v = −1100, +∞ above 1100, NaN for NaN; over the whole range the sweep can reach and beyond
// (the sweep's exponents, the polynomial's interval alone, the subnormal results of the
// two-step 2^k, the rint ties of v, both cut-offs, ±0, ±∞). Both ways of the integer steps:
// the device's own (AVX-512 where its compiler targets it) and the portable one; they must
// give the same doubles (vscalefpd rounds u·2^k once, as the two products do).
TEST(NearLightKernel, LaneExp2WithinThreeUlps) {
    LaneArguments a;
    a.uniform(-1150.0, 1150.0, 1 << 19);   // everything: overflow, normal, subnormal, zero
    a.uniform(-90.0, 0.0, 1 << 19);        // the sweep's exponents −T(τ + η q)·log2(e)
    a.uniform(-0.5, 0.5, 1 << 18);         // the polynomial alone (k = 0)
    a.uniform(-1e-6, 1e-6, 1 << 14);       // 2^v next to 1
    a.uniform(-1076.0, -1020.0, 1 << 17);  // subnormal results (the two-step 2^k)
    a.uniform(-1100.5, -1099.5, 1 << 12);  // the zero cut-off
    a.uniform(1023.0, 1100.5, 1 << 12);    // overflow and the +∞ cut-off
    for (int k = -1100; k <= 1100; ++k)    // v at and next to half-integers (rint's ties)
        for (double t : {-1.0, 0.0, 1.0}) a.values.push_back(std::nextafter(k + 0.5, t * 1e300));
    a.finish({0.0, -0.0, kInf, -kInf, kNaN, 1e-300, -1e-300, 5e-324, -1e300, 1e300, 1023.9999999999999, 1024.0,
              -1022.0, -1074.0, -1075.0, -1100.0, 1100.0},
             0.0);
    const std::vector<double> &v = a.values;
    std::vector<std::vector<double>> results;
    for (const char *variant : {"", "-DSLUT_NL_EXP_AVX512=0"}) {
        SCOPED_TRACE(std::string("build options: ") + variant);
        LaneResults r = run_lane_function("slut_nl_lanes_exp2", v, variant);
        double worst_ulps = 0, worst_at = 0;
        size_t normal = 0, subnormal = 0;
        for (size_t i = 0; i < v.size(); ++i) {
            const double x = v[i], got = r.out[i];
            if (std::isnan(x)) {
                ASSERT_TRUE(std::isnan(got));
                continue;
            }
            if (x > 1100.0) {
                ASSERT_EQ(got, kInf) << "v = " << x;
                continue;
            }
            if (x < -1100.0) {
                ASSERT_EQ(got, 0.0) << "v = " << x;
                continue;
            }
            const long double want = exp2l(static_cast<long double>(x));
            if (want > static_cast<long double>(std::numeric_limits<double>::max())) {
                // Above 2^1024 in long double: the double rounds to +∞ (the last double below
                // it, 2^1024(1 − 2^−54) and up, rounds to +∞ too).
                ASSERT_EQ(got, kInf) << "v = " << x;
                continue;
            }
            if (want < static_cast<long double>(std::numeric_limits<double>::min())) {
                // Subnormal or zero: within 3 steps of the subnormal grid (2^−1074, the ulp of
                // the subnormals and of the smallest normals alike).
                ASSERT_LE(std::fabs(static_cast<long double>(got) - want), 3 * 0x1p-1074L) << "v = " << x;
                ++subnormal;
                continue;
            }
            const double ulps = ulps_from(got, want);
            ASSERT_LE(ulps, 3.0) << "v = " << x << ": " << got << ", exp2l " << static_cast<double>(want);
            if (ulps > worst_ulps) worst_ulps = ulps, worst_at = x;
            ++normal;
        }
        std::printf("lane exp2%s%s (SLUT_NL_EXP_AVX512 = %d): %zu arguments, %zu normal results (worst %.3f ulp at "
                    "v = %.17g), %zu subnormal or zero within 3 steps (%s)\n",
                    *variant ? " " : "", variant, r.avx512, v.size(), normal, worst_ulps, worst_at, subnormal,
                    device().info().platform_name.c_str());
        results.push_back(std::move(r.out));
    }
    size_t differing = 0;
    for (size_t i = 0; i < v.size(); ++i)
        differing += std::memcmp(&results[0][i], &results[1][i], sizeof(double)) != 0 &&
                     !(std::isnan(results[0][i]) && std::isnan(results[1][i]));
    EXPECT_EQ(differing, 0u) << "arguments where the device's integer steps and the portable ones differ";
}

// slut_nl_lanes_expm1 (the 4-D table kernel's value base, kernels/slut_nearlight_lanes.h)
// against long double expm1l: ≤ 3 ulps for y ≤ 0, the value base's side (−40 ≤ y ≤ 0 and
// down to −1000), ≤ 4 for y > 0 (up to the overflow); next to 0, the rint ties of y·log2(e);
// +∞ above 709.78, −1 below −42, NaN for NaN, 0 for ±0.
TEST(NearLightKernel, LaneExpm1WithinUlpBounds) {
    LaneArguments a;
    a.uniform(-40.0, 0.0, 1 << 19);           // the value base's −x
    a.uniform(-1000.0, 720.0, 1 << 18);       // everything
    a.uniform(-0.35, 0.35, 1 << 18);          // k = 0: the polynomial alone
    a.log_uniform(-997.0, 0.0, 1 << 16, -1.0); // next to 0, both signs
    a.log_uniform(-997.0, 0.0, 1 << 16, 1.0);
    a.uniform(705.0, 710.0, 1 << 14);         // k = 1024 and the overflow
    for (int k = -70; k <= 1030; ++k)         // y·log2(e) at and next to half-integers (rint's ties)
        for (double t : {-1.0, 0.0, 1.0})
            a.values.push_back(std::nextafter((k + 0.5) * 0.6931471805599453, t * 1e300));
    a.finish({0.0, -0.0, kInf, -kInf, kNaN, 5e-324, -5e-324, -41.6, -42.0, 709.782712893384, 709.7827128933841,
              1e300, -1e300},
             0.0);
    const std::vector<double> &y = a.values;
    const LaneResults r = run_lane_function("slut_nl_lanes_expm1", y);
    double worst_negative = 0, worst_positive = 0, worst_base = 0;
    for (size_t i = 0; i < y.size(); ++i) {
        const double x = y[i], got = r.out[i];
        if (std::isnan(x)) {
            ASSERT_TRUE(std::isnan(got));
            continue;
        }
        if (x == 0.0) {
            ASSERT_EQ(got, 0.0); // +0 for −0 too (no caller tells them apart)
            continue;
        }
        const long double want = expm1l(static_cast<long double>(x));
        if (want > static_cast<long double>(std::numeric_limits<double>::max())) {
            ASSERT_EQ(got, kInf) << "y = " << x;
            continue;
        }
        const double ulps = ulps_from(got, want);
        // y > 0 at k = 1 (y ≈ ln 2/2 … 3 ln 2/2): 2(2^f − 1) and 2 − 1 partly cancel.
        ASSERT_LE(ulps, x > 0.0 ? 4.0 : 3.0) << "y = " << x << ": " << got << ", expm1l " << static_cast<double>(want);
        double &worst = x > 0.0 ? worst_positive : worst_negative;
        worst = std::max(worst, ulps);
        if (x >= -40.0 && x <= 0.0) worst_base = std::max(worst_base, ulps);
    }
    std::printf("lane expm1: %zu arguments, worst %.3f ulp for y <= 0 (%.3f on [-40, 0], the value base's range), "
                "%.3f for y > 0 (%s)\n",
                y.size(), worst_negative, worst_base, worst_positive, device().info().platform_name.c_str());
}

// slut_nl_lanes_log (the table kernel's stored ln E, kernels/slut_nearlight_lanes.h) against
// long double logl: < 1 ulp over the doubles, subnormals and the neighbourhood of 1 included
// (where ln x is smallest against x); −∞ for ±0, NaN below 0 and for NaN, +∞ for +∞.
TEST(NearLightKernel, LaneLogWithinAnUlp) {
    LaneArguments a;
    a.log_uniform(-1074.0, 1024.0, 1 << 19);     // every binade, subnormals included
    a.log_uniform(-80.0, 1.0, 1 << 19);          // the kernel's E and E/B
    a.uniform(0.7, 1.45, 1 << 18);               // k = 0: the polynomial alone
    a.uniform(1.0 - 1e-6, 1.0 + 1e-6, 1 << 14);  // next to 1
    a.uniform(0.5, 2.0, 1 << 16);
    a.finish({0.0, -0.0, kInf, -kInf, -1.0, -5e-324, kNaN, 5e-324, 0x1p-1022, std::nextafter(0x1p-1022, 0.0), 1.0,
              std::nextafter(1.0, 0.0), std::nextafter(1.0, 2.0), 0.7071067811865476, 1.4142135623730951,
              std::numeric_limits<double>::max()},
             1.0);
    const std::vector<double> &x = a.values;
    const LaneResults r = run_lane_function("slut_nl_lanes_log", x);
    double worst_ulps = 0, worst_at = 0;
    for (size_t i = 0; i < x.size(); ++i) {
        const double v = x[i], got = r.out[i];
        if (std::isnan(v) || v < 0.0) {
            ASSERT_TRUE(std::isnan(got)) << "x = " << v;
            continue;
        }
        if (v == 0.0 || v == kInf) {
            ASSERT_EQ(got, v == 0.0 ? -kInf : kInf) << "x = " << v;
            continue;
        }
        const long double want = logl(static_cast<long double>(v));
        if (want == 0.0L) {
            ASSERT_EQ(got, 0.0) << "x = " << v;
            continue;
        }
        const double ulps = ulps_from(got, want);
        ASSERT_LT(ulps, 1.0) << "x = " << v << ": " << got << ", logl " << static_cast<double>(want);
        if (ulps > worst_ulps) worst_ulps = ulps, worst_at = v;
    }
    std::printf("lane log: %zu arguments, worst %.3f ulp at x = %.17g (%s)\n", x.size(), worst_ulps, worst_at,
                device().info().platform_name.c_str());
}

TEST(NearLightIdentity, ZeroRIsTheAirlight) {
    for (double T : {0.05, 1.0, 7.0})
        for (double g : {-0.9, -0.3, 0.0, 0.6, 0.99})
            for (double S : {0.5, 4.0, std::numeric_limits<double>::infinity()}) {
                const double N = slut_nl_E(T, g, 0.0, S) * slut_nl_H(T, g, S);
                scatterlut::AirlightQuery q{1.0, 0.0, 4.0 * M_PI, T, std::acos(-g), S}; // σ_t = 1: D = T, s = S
                const double L = scatterlut::airlight_radiance_exact(q);
                EXPECT_LE(slut_test::rel_err(N, L), 1e-11) << "T=" << T << " g=" << g << " S=" << S;
            }
}

// Eye-side refraction: the radiance along the refracted ray by explicit 3-D quadrature
// (point P = O − x ω_t; the light path below the plane is |P − light|·depth/(depth + height))
// times the unpolarised Fresnel transmittance, against near_light_radiance_exact with
// eta and fresnel. Boost Gauss–Kronrod with break points at e-folds; 1e-9.
TEST(NearLightRefraction, MatchesExplicitQuadratureAlongTheRefractedRay) {
    const double eta = 1.45, sigma_s = 0.8, sigma_a = 0.3, sigma_t = sigma_s + sigma_a, I0 = 2.0;
    const double n[3] = {0, 0, 1};
    const double c = std::cos(0.9), sn = std::sin(0.9);
    const double eye[3] = {sn, 0, c};
    const double light[3] = {-0.4, 0.3, 0.5};
    for (double s : {0.7, std::numeric_limits<double>::infinity()}) {
        // ω_t by Snell's law, written out independently of the header.
        const double sin_t = sn / eta, cos_t = std::sqrt(1 - sin_t * sin_t);
        const double wt[3] = {sin_t, 0, cos_t};
        auto integrand = [&](double x) {
            const double P[3] = {-x * wt[0], -x * wt[1], -x * wt[2]};
            const double d[3] = {light[0] - P[0], light[1] - P[1], light[2] - P[2]};
            const double h = std::sqrt(d[0] * d[0] + d[1] * d[1] + d[2] * d[2]);
            const double depth = -P[2], height = light[2];
            const double inside = h * depth / (depth + height);
            return std::exp(-sigma_t * (x + inside)) / (h * h);
        };
        const double end = std::isinf(s) ? 60.0 / sigma_t : s;
        double integral = 0;
        for (double a = 0; a < end; a += 0.25) {
            const double b = std::min(end, a + 0.25);
            integral += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(integrand, a, b, 15, 1e-14);
        }
        const double rs = (c - eta * cos_t) / (c + eta * cos_t), rp = (eta * c - cos_t) / (eta * c + cos_t);
        const double fresnel = 1 - 0.5 * (rs * rs + rp * rp);
        const double want = fresnel * sigma_s / (4 * M_PI) * I0 * integral;
        scatterlut::NearLightQuery q;
        q.sigma_s_per_m = sigma_s;
        q.sigma_a_per_m = sigma_a;
        q.intensity_W_per_sr = I0;
        for (int k = 0; k < 3; ++k) {
            q.normal[k] = n[k];
            q.eye_dir[k] = eye[k];
            q.light_rel_m[k] = light[k];
        }
        q.length_m = s;
        q.eta = eta;
        q.fresnel = true;
        EXPECT_LE(slut_test::rel_err(scatterlut::near_light_radiance_exact(q), want), 1e-9) << "s=" << s;
        q.fresnel = false;
        EXPECT_LE(slut_test::rel_err(scatterlut::near_light_radiance_exact(q), want / fresnel), 1e-9) << "s=" << s;
    }
}
