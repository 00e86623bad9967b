// The surface terms of Sun et al. 2005 (kernels/slut_surface.h, tables/src/surface.cpp;
// docs/PHYSICS.md §1.5) against independent references:
//  - the 30-digit mpmath values of tests/reference/surface_ref.json (make_reference.py: the
//    γ-integral with A from the complex exponential integral and K_n from Legendre functions
//    and ₂F₁, each checked there against its own definition by quadrature);
//  - Boost.Math tanh–sinh quadrature of the definitions as 2-D integrals over directions in
//    the frame of the normal (or of the mirror direction), with the incident radiance from
//    airlight_radiance_exact along the infinite ray: no γ reduction, no azimuthal kernel;
//  - the azimuthal kernels K_n against Boost quadrature in φ; the σ_t → 0 closed form against
//    Boost's ellint_2.
// Every check records its worst error as the test's worst_rel_err property.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>
#include <string>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <boost/math/quadrature/tanh_sinh.hpp>
#include <boost/math/special_functions/ellint_2.hpp>
#include <gtest/gtest.h>

#include "reference_data.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/surface.hpp"

extern "C" {
#include "slut_surface.h"
}

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kPio2 = 1.5707963267948966;

double rel(double a, double b) {
    if (a == b) return 0.0;
    return std::fabs(a - b) / std::fabs(b);
}

std::string sci(double x) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.3g", x);
    return buf;
}

struct SurfaceRef {
    std::string quantity;
    double sigma_s, sigma_a, intensity, distance, theta;
    int exponent;
    long double G, E;
};

std::vector<SurfaceRef> load_surface_refs() {
    std::vector<SurfaceRef> out;
    const nlohmann::json file = slut_test::load_json("surface_ref.json");
    for (const auto &c : file.at("cases")) {
        const std::string q = c.at("quantity").get<std::string>();
        out.push_back({q, c.at("sigma_s").get<double>(), c.at("sigma_a").get<double>(), c.at("intensity").get<double>(),
                       c.at("distance").get<double>(), c.at("theta").get<double>(),
                       q == "surface_specular" ? c.at("exponent").get<int>() : 1, slut_test::ref_number(c.at("G")),
                       slut_test::ref_number(c.at("E"))});
    }
    if (out.empty()) throw std::runtime_error("surface_ref.json has no cases");
    return out;
}

// K_n(θ, γ) = ∫_0^{2π} max(cos θ cos γ + sin θ sin γ cos φ, 0)^n dφ by Gauss–Kronrod in φ on
// [0, φ_end] (the part of the ring inside the lobe), with break points at the lobe's width.
double ref_kernel(int n, double theta, double gamma) {
    const double a = std::cos(theta) * std::cos(gamma), b = std::sin(theta) * std::sin(gamma);
    if (b <= 0.0) return a > 0.0 ? 2.0 * kPi * std::pow(a, n) : 0.0;
    if (a <= -b) return 0.0;
    const double end = (a >= b) ? kPi : std::acos(-a / b);
    auto f = [&](double phi) { return std::pow(std::fmax(a + b * std::cos(phi), 0.0), n); };
    double sum = 0.0, lo = 0.0;
    for (double k : {1.0, 4.0, 16.0, 64.0}) {
        const double hi = std::fmin(end, k / std::sqrt(static_cast<double>(n)));
        if (hi <= lo) continue;
        sum += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, lo, hi, 6, 1e-14);
        lo = hi;
    }
    if (end > lo) sum += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, lo, end, 6, 1e-14);
    return 2.0 * sum;
}

// ∫ L_in(ω) max(ω·z, 0)^n dω over directions around the pole z (the normal for n = 1, the
// mirror direction otherwise), the light at polar angle θ in the x–z plane. β from the pole,
// ψ the azimuth; the integrand is even in ψ. L_in from airlight_radiance_exact along the
// infinite ray (an independent code path), γ = 2 atan2(|ω − l|, |ω + l|). tanh–sinh on
// panels split where the integrand has its integrable 1/γ peak (β = θ, ψ = 0) and, for
// narrow lobes, at the lobe's width. W/m².
double ref_surface_2d(double sigma_s, double sigma_a, double intensity, double distance, double theta, int n) {
    const double lx = std::sin(theta), lz = std::cos(theta);
    scatterlut::AirlightQuery q;
    q.sigma_s_per_m = sigma_s;
    q.sigma_a_per_m = sigma_a;
    q.intensity_W_per_sr = intensity;
    q.distance_m = distance;
    q.length_m = std::numeric_limits<double>::infinity();
    boost::math::quadrature::tanh_sinh<double> ts(12);
    auto inner = [&](double beta) {
        const double sb = std::sin(beta), cb = std::cos(beta);
        const double weight = std::pow(cb, n) * sb;
        if (weight <= 0.0) return 0.0;
        auto f = [&](double psi) {
            const double wx = sb * std::cos(psi), wy = sb * std::sin(psi), wz = cb;
            const double dx = wx - lx, dz = wz - lz, sx = wx + lx, sz = wz + lz;
            q.gamma_rad = 2.0 * std::atan2(std::sqrt(dx * dx + wy * wy + dz * dz), std::sqrt(sx * sx + wy * wy + sz * sz));
            // The ray through the light (γ = 0 after rounding, at β = θ, ψ = 0 where tanh–sinh
            // sits within ~1e-300 of a panel's end): L_in diverges like 1/γ there, integrably;
            // that node's weight is ~1e-300, so it is dropped.
            const double L = scatterlut::airlight_radiance_exact(q);
            return std::isfinite(L) ? L : 0.0;
        };
        double err = 0.0;
        return 2.0 * weight * ts.integrate(f, 0.0, kPi, 1e-11, &err);
    };
    std::vector<double> cuts = {0.0, kPio2};
    if (theta > 0.0 && theta < kPio2) cuts.push_back(theta);
    if (n > 1)
        for (double k : {2.0, 6.0, 16.0}) {
            const double x = k / std::sqrt(static_cast<double>(n));
            if (x < kPio2) cuts.push_back(x);
        }
    std::sort(cuts.begin(), cuts.end());
    double sum = 0.0;
    for (size_t i = 0; i + 1 < cuts.size(); ++i) {
        if (cuts[i + 1] <= cuts[i]) continue;
        double err = 0.0;
        sum += ts.integrate(inner, cuts[i], cuts[i + 1], 1e-10, &err);
    }
    return sum;
}

scatterlut::SurfaceQuery query(double sigma_s, double sigma_a, double intensity, double distance, double theta) {
    scatterlut::SurfaceQuery q;
    q.sigma_s_per_m = sigma_s;
    q.sigma_a_per_m = sigma_a;
    q.intensity_W_per_sr = intensity;
    q.distance_m = distance;
    q.theta_rad = theta;
    return q;
}

TEST(SurfaceTerms, MatchTheMpmathReferences) {
    const auto refs = load_surface_refs();
    double worst = 0.0;
    for (const auto &r : refs) {
        const auto q = query(r.sigma_s, r.sigma_a, r.intensity, r.distance, r.theta);
        const double e = (r.quantity == "surface") ? scatterlut::surface_irradiance_exact(q)
                                                   : scatterlut::surface_specular_exact(q, r.exponent);
        const double g = scatterlut::surface_G_exact(r.exponent, (r.sigma_s + r.sigma_a) * r.distance, r.theta);
        const double err = std::fmax(rel(e, (double)r.E), rel(g, (double)r.G));
        worst = std::fmax(worst, err);
        EXPECT_LE(err, 1e-12) << r.quantity << " T = " << (r.sigma_s + r.sigma_a) * r.distance << " theta = " << r.theta
                              << " n = " << r.exponent << ": " << e << " vs " << (double)r.E;
    }
    EXPECT_GE(refs.size(), 80u);
    RecordProperty("worst_rel_err", sci(worst));
}

TEST(SurfaceTerms, MatchABoostQuadratureOverDirections) {
    struct Case { double sigma_s, sigma_a, intensity, distance, theta; int n; };
    const Case cases[] = {
        {0.75, 0.25, 100.0, 1.0, 0.0, 1},    {0.75, 0.25, 100.0, 1.0, 0.3, 1},  {0.75, 0.25, 100.0, 1.0, kPio2, 1},
        {0.75, 0.25, 100.0, 1.0, 2.5, 1},    {0.75, 0.25, 100.0, 1.0, kPi, 1},  {0.02, 0.005, 3.0, 7.5, 1.2, 1},
        {0.75, 0.25, 100.0, 0.001, 0.3, 1},  {0.75, 0.25, 100.0, 10.0, 2.5, 1}, {0.75, 0.25, 100.0, 40.0, 1.0, 1},
        {0.75, 0.25, 100.0, 1.0, 0.3, 20},   {0.75, 0.25, 100.0, 1.0, 2.5, 20}, {0.3, 0.2, 10.0, 3.0, 0.01, 100},
        {0.75, 0.25, 100.0, 0.1, 0.7, 1000},
    };
    double worst = 0.0;
    for (const auto &c : cases) {
        const auto q = query(c.sigma_s, c.sigma_a, c.intensity, c.distance, c.theta);
        const double mine = (c.n == 1) ? scatterlut::surface_irradiance_exact(q) : scatterlut::surface_specular_exact(q, c.n);
        const double ref = ref_surface_2d(c.sigma_s, c.sigma_a, c.intensity, c.distance, c.theta, c.n);
        worst = std::fmax(worst, rel(mine, ref));
        EXPECT_LE(rel(mine, ref), 1e-10) << "T = " << (c.sigma_s + c.sigma_a) * c.distance << " theta = " << c.theta
                                        << " n = " << c.n << ": " << mine << " vs " << ref;
    }
    RecordProperty("worst_rel_err", sci(worst));
}

TEST(SurfaceTerms, AzimuthalKernelMatchesQuadratureInPhi) {
    double worst = 0.0;
    const double thetas[] = {0.0, 0.2, 1.0, kPio2, 2.0, 3.0, kPi};
    const int exponents[] = {1, 2, 7, 20, 200, 1000};
    for (int n : exponents)
        for (double theta : thetas)
            for (int i = 0; i <= 64; ++i) {
                const double gamma = kPi * i / 64.0;
                const double mine = slut_surface_kernel(n, theta, gamma);
                const double ref = ref_kernel(n, theta, gamma);
                ASSERT_GE(mine, 0.0);
                // Relative where the kernel matters; absolute 1e-14 of its largest value 2π below.
                const double err = std::fabs(mine - ref) / std::fmax(std::fabs(ref), 2.0 * kPi * 1e-4);
                worst = std::fmax(worst, err);
                EXPECT_LE(err, 1e-11) << "n = " << n << " theta = " << theta << " gamma = " << gamma << ": " << mine
                                      << " vs " << ref;
            }
    RecordProperty("worst_rel_err", sci(worst));
}

TEST(SurfaceTerms, NoExtinctionLimitIsTheEllipticClosedForm) {
    double worst = 0.0;
    for (int i = 0; i <= 32; ++i) {
        const double theta = kPi * i / 32.0;
        const double closed = 2.0 * kPi * (std::cos(theta) + boost::math::ellint_2(std::sin(theta)));
        worst = std::fmax(worst, rel(slut_surface_G0_no_extinction(theta), closed));
        EXPECT_LE(rel(slut_surface_G0_no_extinction(theta), closed), 1e-14) << theta;
        EXPECT_LE(rel(scatterlut::surface_G_exact(1, 0.0, theta), closed), 1e-10) << theta;
        // E_ss tends to it as σ_t → 0, from below (extinction only removes light).
        const auto q = query(1e-9, 0.0, 1.0, 1.0, theta);
        const double e = scatterlut::surface_irradiance_exact(q), bound = scatterlut::surface_irradiance_no_extinction(q);
        EXPECT_LE(e, bound * (1.0 + 1e-12)) << theta;
        EXPECT_LE(rel(e, bound), 1e-7) << theta;
    }
    // The values derived in docs/PHYSICS.md §1.5.
    EXPECT_NEAR(slut_surface_G0_no_extinction(0.0), kPi * kPi + 2.0 * kPi, 1e-13);
    EXPECT_NEAR(slut_surface_G0_no_extinction(kPio2), 2.0 * kPi, 1e-13);
    EXPECT_NEAR(slut_surface_G0_no_extinction(kPi), kPi * kPi - 2.0 * kPi, 1e-13);
    RecordProperty("worst_rel_err", sci(worst));
}

TEST(SurfaceTerms, NeverNaNNeverNegativeAtTheHardCases) {
    const double Ts[] = {0.0, 1e-300, 1e-12, 1e-6, 1e-3, 0.1, 1.0, 10.0, 40.0, 100.0, 700.0, 800.0, 1e6};
    const double thetas[] = {0.0, 1e-300, 1e-12, 1e-6, kPio2 - 1e-12, kPio2, kPio2 + 1e-12, 3.0, kPi - 1e-12, kPi};
    const int exponents[] = {1, 2, 20, 1000, scatterlut::kSurfaceMaxExponent};
    for (int n : exponents)
        for (double T : Ts)
            for (double theta : thetas) {
                const double g = scatterlut::surface_G_exact(n, T, theta);
                ASSERT_TRUE(std::isfinite(g)) << n << " " << T << " " << theta;
                ASSERT_GE(g, 0.0) << n << " " << T << " " << theta;
                if (T <= 100.0) { // light reaches every direction
                    EXPECT_GT(g, 0.0) << n << " " << T << " " << theta;
                }
            }
    // θ_s = π (light straight below the surface): still positive, and the airlight itself there
    // is e^{T} E_2(2T)·σ_s I0/(4π D) per direction away from the light.
    EXPECT_GT(scatterlut::surface_irradiance_exact(query(0.75, 0.25, 100.0, 10.0, kPi)), 0.0);
    // A sin γ at the ends: π e^{−T} at γ = 0, and sin γ → 0 at γ = π.
    EXPECT_NEAR(slut_surface_incident_sin(2.0, 0.0), kPi * std::exp(-2.0), 1e-14);
    EXPECT_NEAR(slut_surface_incident_sin(0.0, 1.0), kPi - 1.0, 1e-14);
    EXPECT_LE(slut_surface_incident_sin(2.0, kPi), 1e-15);
}

TEST(SurfaceTerms, ZeroAndBadInput) {
    EXPECT_EQ(scatterlut::surface_irradiance_exact(query(0.0, 0.5, 100.0, 2.0, 1.0)), 0.0);
    EXPECT_EQ(scatterlut::surface_specular_exact(query(0.5, 0.5, 0.0, 2.0, 1.0), 20), 0.0);
    const double nan = std::numeric_limits<double>::quiet_NaN(), inf = std::numeric_limits<double>::infinity();
    EXPECT_THROW(scatterlut::surface_irradiance_exact(query(-1.0, 0.0, 1.0, 1.0, 0.5)), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_irradiance_exact(query(1.0, nan, 1.0, 1.0, 0.5)), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_irradiance_exact(query(1.0, 0.0, inf, 1.0, 0.5)), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_irradiance_exact(query(1.0, 0.0, 1.0, 0.0, 0.5)), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_irradiance_exact(query(1.0, 0.0, 1.0, 1.0, 3.5)), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_irradiance_exact(query(1.0, 0.0, 1.0, 1.0, -0.1)), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_specular_exact(query(1.0, 0.0, 1.0, 1.0, 0.5), 0), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_specular_exact(query(0.0, 0.0, 1.0, 1.0, 0.5), 0), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_G_exact(1, nan, 0.5), std::invalid_argument);
    EXPECT_THROW(scatterlut::surface_G_exact(scatterlut::kSurfaceMaxExponent + 1, 1.0, 0.5), std::invalid_argument);
}

} // namespace
