#include "scatterlut/surface.hpp"

#include "require.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

extern "C" {
#include "slut_surface.h"
#include "slut_surface_frontend.h" /* slut_surface_scattered_scale */
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

bool finite_non_negative(double x) { return std::isfinite(x) && x >= 0.0; }

// 15-point Gauss–Kronrod on [−1, 1] (QUADPACK qk15): the Kronrod nodes x ≥ 0, their weights,
// and the weights of the embedded 7-point Gauss rule at the odd-indexed nodes.
constexpr double kGkX[8] = {0.991455371120812639206854697526329, 0.949107912342758524526189684047851,
                            0.864864423359769072789712788640926, 0.741531185599394439863864773280788,
                            0.586087235467691130294144845693013, 0.405845151377397166906606412076961,
                            0.207784955007898467600689403773245, 0.0};
constexpr double kGkW[8] = {0.022935322010529224963732008058970, 0.063092092629978553290700663189204,
                            0.104790010322250183839876322541518, 0.140653259715525918745189590510238,
                            0.169004726639267902826583426598550, 0.190350578064785409913256402421014,
                            0.204432940075298892414161999234649, 0.209482141084727828012999174891714};
constexpr double kGaussW[4] = {0.129484966168869693270611432679082, 0.279705391489276667901467771423780,
                               0.381830050505118944950369775488975, 0.417959183673469387755102040816327};

struct Panel {
    double lo, hi;     // in the panel's own variable (t for the first panel, γ otherwise)
    bool squared;      // γ = lo_gamma + (first panel's length)·t², t ∈ [lo, hi] ⊂ [0, 1]
    double value, error;
};

class GIntegrand {
public:
    GIntegrand(int n, double T, double theta, double first_end)
        : n_(n), T_(T), theta_(theta), first_end_(first_end) {}
    // f(γ) or, on the first panel, f(γ_1 t²)·2γ_1 t.
    double operator()(double x, bool squared) const {
        if (!squared) return slut_surface_integrand(n_, T_, theta_, x);
        double gamma = first_end_ * x * x;
        return slut_surface_integrand(n_, T_, theta_, gamma) * 2.0 * first_end_ * x;
    }

private:
    int n_;
    double T_, theta_, first_end_;
};

void evaluate(const GIntegrand &f, Panel &p) {
    double half = 0.5 * (p.hi - p.lo), mid = 0.5 * (p.hi + p.lo);
    double centre = f(mid, p.squared);
    double kronrod = kGkW[7] * centre, gauss = kGaussW[3] * centre;
    for (int k = 0; k < 7; ++k) {
        double dx = half * kGkX[k];
        double pair = f(mid - dx, p.squared) + f(mid + dx, p.squared);
        kronrod += kGkW[k] * pair;
        if (k % 2 == 1) gauss += kGaussW[k / 2] * pair;
    }
    p.value = half * kronrod;
    p.error = std::fabs(half * (kronrod - gauss));
}

// The break points of G_n's integrand in γ ∈ [0, π] (kernels/slut_surface.h, shared with the
// generator's fixed rule).
std::vector<double> break_points(int n, double T, double theta) {
    double b[SLUT_SURFACE_MAX_BREAKS];
    const int count = slut_surface_break_points(n, T, theta, b);
    return std::vector<double>(b, b + count);
}

} // namespace

void check_surface_query(const SurfaceQuery &q) {
    require(finite_non_negative(q.sigma_s_per_m), "sigma_s must be finite and >= 0 (1/m)");
    require(finite_non_negative(q.sigma_a_per_m), "sigma_a must be finite and >= 0 (1/m)");
    require(finite_non_negative(q.intensity_W_per_sr), "intensity must be finite and >= 0 (W/sr)");
    require(q.distance_m > 0.0 && std::isfinite(q.distance_m), "distance must be finite and > 0 (m)");
    require(q.theta_rad >= 0.0 && q.theta_rad <= SLUT_PI + 1e-15, "theta must be in [0, pi] (rad)");
}

double surface_G_exact(int exponent, double optical_distance, double theta_rad) {
    require(exponent >= 1 && exponent <= kSurfaceMaxExponent,
            "exponent must be an integer in [1, " + std::to_string(kSurfaceMaxExponent) + "]");
    require(finite_non_negative(optical_distance), "optical distance sigma_t*D must be finite and >= 0");
    require(theta_rad >= 0.0 && theta_rad <= SLUT_PI + 1e-15, "theta must be in [0, pi] (rad)");
    double theta = std::min(theta_rad, SLUT_PI);
    std::vector<double> b = break_points(exponent, optical_distance, theta);
    GIntegrand f(exponent, optical_distance, theta, b[1]);
    std::vector<Panel> panels;
    for (size_t i = 0; i + 1 < b.size(); ++i) {
        Panel p = (i == 0) ? Panel{0.0, 1.0, true, 0, 0} : Panel{b[i], b[i + 1], false, 0, 0};
        evaluate(f, p);
        panels.push_back(p);
    }
    // Global adaptive bisection: split the panel with the largest error estimate until the
    // estimates add up to 1e-12 of the total (Kronrod's |K15 − G7| overestimates the error of
    // K15 by orders of magnitude on smooth panels, so this is ~1e-10 with room to spare).
    constexpr int kMaxPanels = 4000;
    while (true) {
        double total = 0.0, error = 0.0;
        size_t worst = 0;
        for (size_t i = 0; i < panels.size(); ++i) {
            total += panels[i].value;
            error += panels[i].error;
            if (panels[i].error > panels[worst].error) worst = i;
        }
        if (error <= 1e-12 * std::fabs(total) || error <= 1e-300 ||
            static_cast<int>(panels.size()) >= kMaxPanels)
            return std::max(total, 0.0);
        Panel left = panels[worst], right = panels[worst];
        double mid = 0.5 * (left.lo + left.hi);
        left.hi = mid;
        right.lo = mid;
        evaluate(f, left);
        evaluate(f, right);
        panels[worst] = left;
        panels.push_back(right);
    }
}

double surface_irradiance_exact(const SurfaceQuery &q) {
    check_surface_query(q);
    double prefactor = slut_surface_scattered_scale(q.sigma_s_per_m, q.intensity_W_per_sr, q.distance_m);
    if (prefactor == 0.0) return 0.0;
    double T = (q.sigma_s_per_m + q.sigma_a_per_m) * q.distance_m;
    return prefactor * surface_G_exact(1, T, q.theta_rad);
}

double surface_specular_exact(const SurfaceQuery &q, int exponent) {
    check_surface_query(q);
    double prefactor = slut_surface_scattered_scale(q.sigma_s_per_m, q.intensity_W_per_sr, q.distance_m);
    if (prefactor == 0.0) {
        require(exponent >= 1 && exponent <= kSurfaceMaxExponent,
                "exponent must be an integer in [1, " + std::to_string(kSurfaceMaxExponent) + "]");
        return 0.0;
    }
    double T = (q.sigma_s_per_m + q.sigma_a_per_m) * q.distance_m;
    return prefactor * surface_G_exact(exponent, T, q.theta_rad);
}

double surface_irradiance_no_extinction(const SurfaceQuery &q) {
    check_surface_query(q);
    double prefactor = slut_surface_scattered_scale(q.sigma_s_per_m, q.intensity_W_per_sr, q.distance_m);
    return prefactor * slut_surface_G0_no_extinction(std::min(q.theta_rad, SLUT_PI));
}

} // namespace scatterlut
