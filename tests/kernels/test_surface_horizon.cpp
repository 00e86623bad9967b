// What the missing horizon costs in Sun et al. 2005's specular term S_n (docs/PHYSICS.md §1.5).
// S_n weights the incident airlight L_in(ω) by the lobe max(ω·ρ, 0)^n over ALL directions; a
// surface only receives light from above its horizon, N·ω > 0 (N the unit normal). This prints
// the clipped term over the unclipped one for n ∈ {1, 20, 200}, T = σ_t D ∈ {0.1, 1, 10}, as the
// angle α between ρ and N goes from 0 to 90° (ρ, the mirror of a view direction, never lies
// below the horizon), in two configurations where both reduce to one integral over γ (the angle
// from ω to the light, L_in ∝ A(T, γ) sin γ / sin γ: slut_surface_incident_sin):
//  - "light at rho" (the highlight itself, θ_r = 0): in polar coordinates (γ, φ) about ρ = ω_l the
//    lobe is cos^n γ and the horizon keeps the azimuths cos φ > −cot α cot γ, 2 φ0(α, γ) of them:
//      clipped = ∫_0^{π/2} A sin γ · cos^n γ · 2 φ0 dγ,  unclipped = G_n(T, 0);
//  - "light at N" (θ_s = 0, ρ tilted by α, θ_r = α): about ω_l = N the horizon is γ < π/2:
//      clipped = ∫_0^{π/2} A sin γ · K_n(α, γ) dγ,      unclipped = G_n(T, α).
// Asserted are physics facts only: 0 < clipped ≤ unclipped; both equal at α = 0 in the first
// configuration (the lobe about the normal lies wholly above the horizon: checks this quadrature
// against surface_G_exact) and clipped/unclipped = 1/2 exactly at α = 90° (the horizon plane then
// holds ρ = ω_l and cuts lobe and L_in into mirror halves); clipped falls as α grows there.
// Gauss–Kronrod (Boost.Math, 61 points, adaptive) on panels split at π/2 − α (where φ0 leaves π),
// θ_r ± k/√n (the lobe) and 1/T (A's scale near the light).
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>

#include <boost/math/quadrature/gauss_kronrod.hpp>
#include <gtest/gtest.h>

#include "scatterlut/surface.hpp"

extern "C" {
#include "slut_surface.h"
}

namespace {

constexpr double kPi = 3.14159265358979323846;

template <class F> double integrate_panels(F f, std::vector<double> breaks) {
    std::sort(breaks.begin(), breaks.end());
    double sum = 0.0;
    for (size_t i = 0; i + 1 < breaks.size(); ++i)
        if (breaks[i + 1] > breaks[i])
            sum += boost::math::quadrature::gauss_kronrod<double, 61>::integrate(f, breaks[i], breaks[i + 1], 12, 1e-12);
    return sum;
}

// The break points in [0, π/2] for a lobe of exponent n centred at γ = centre, plus `extra`.
std::vector<double> breaks_in_upper_half(int n, double T, double centre, double extra) {
    std::vector<double> b = {0.0, 0.5 * kPi, extra};
    const double width = 1.0 / std::sqrt(static_cast<double>(n));
    for (double k : {-12.0, -4.0, 0.0, 4.0, 12.0}) b.push_back(centre + k * width);
    if (T > 1.0) b.push_back(1.0 / T);
    std::vector<double> kept;
    for (double x : b)
        if (x >= 0.0 && x <= 0.5 * kPi) kept.push_back(x);
    return kept;
}

// "Light at rho": the lobe about ρ = ω_l clipped by the horizon of a normal at α from ρ.
double clipped_light_at_rho(int n, double T, double alpha) {
    const double edge = 0.5 * kPi - alpha; // γ below this: the whole ring is above the horizon
    auto f = [&](double gamma) {
        double phi0 = kPi;
        if (gamma > edge) {
            const double c = -std::cos(alpha) * std::cos(gamma) / (std::sin(alpha) * std::sin(gamma));
            phi0 = std::acos(std::clamp(c, -1.0, 1.0));
        }
        return slut_surface_incident_sin(T, gamma) * std::pow(std::cos(gamma), n) * 2.0 * phi0;
    };
    return integrate_panels(f, breaks_in_upper_half(n, T, 0.0, edge));
}

// "Light at N": the lobe about ρ (θ_r = α from ω_l = N), the directions γ < π/2 kept.
double clipped_light_at_normal(int n, double T, double alpha) {
    auto f = [&](double gamma) { return slut_surface_integrand(n, T, alpha, gamma); };
    return integrate_panels(f, breaks_in_upper_half(n, T, alpha, std::fabs(0.5 * kPi - alpha)));
}

TEST(SurfaceHorizon, WhatTheMissingHorizonCosts) {
    const double alphas_deg[] = {0, 30, 60, 75, 85, 90};
    std::printf("S_n clipped to the horizon (N.w > 0) / unclipped (Sun et al. 2005), alpha = angle(rho, N)\n");
    std::printf("%-13s %5s %4s", "config", "T", "n");
    for (double a : alphas_deg) std::printf("  a=%-5g", a);
    std::printf("\n");
    for (int config = 0; config < 2; ++config)
        for (double T : {0.1, 1.0, 10.0})
            for (int n : {1, 20, 200}) {
                std::printf("%-13s %5g %4d", config == 0 ? "light at rho" : "light at N", T, n);
                double previous = 2.0;
                for (double a_deg : alphas_deg) {
                    const double alpha = a_deg * kPi / 180.0;
                    const double unclipped = scatterlut::surface_G_exact(n, T, config == 0 ? 0.0 : alpha);
                    const double clipped =
                        config == 0 ? clipped_light_at_rho(n, T, alpha) : clipped_light_at_normal(n, T, alpha);
                    const double ratio = clipped / unclipped;
                    std::printf("  %7.5f", ratio);
                    EXPECT_GT(clipped, 0.0) << "n=" << n << " T=" << T << " alpha=" << a_deg;
                    EXPECT_LE(ratio, 1.0 + 1e-9) << "n=" << n << " T=" << T << " alpha=" << a_deg;
                    if (config == 0) {
                        if (a_deg == 0) {
                            EXPECT_NEAR(ratio, 1.0, 1e-9) << "n=" << n << " T=" << T;
                        }
                        if (a_deg == 90) {
                            EXPECT_NEAR(ratio, 0.5, 1e-9) << "n=" << n << " T=" << T;
                        }
                        EXPECT_LE(ratio, previous + 1e-12) << "n=" << n << " T=" << T << " alpha=" << a_deg;
                        previous = ratio;
                    }
                }
                std::printf("\n");
            }
}

} // namespace
