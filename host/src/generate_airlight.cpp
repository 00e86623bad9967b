#include "generate_airlight.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <chrono>
#include <random>
#include <thread>
#include <vector>

#include "measure_util.hpp"
#include "reference_quadrature.hpp"
#include "table_build.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"

extern "C" {
#include "slut_airlight_hg.h" /* and through it slut_airlight.h */
#include "slut_gauss_legendre.h"
}

namespace scatterlut {

Table make_airlight_table_layout(const AirlightPlan &plan) {
    const bool isotropic = plan.phase_g == 0.0;
    if (!isotropic) check_phase_g(plan.phase_g);
    const char *F = isotropic ? "F" : "F_g";
    Table t;
    t.kind = isotropic ? kKindAirlightF : kKindAirlightFg;
    t.quantity_version = isotropic ? kAirlightFQuantityVersion : kAirlightFgQuantityVersion;
    const std::string u_meaning =
        std::string("optical distance sigma_t*D*sin(gamma) (dimensionless), first argument of ") + F + "(u,v)";
    const std::string w_meaning = std::string("pi/2 - v (rad), v the second argument of ") + F + "(u,v)";
    const double peak_scale = airlight_w_peak_scale(plan.phase_g);
    t.axes = {make_axis("u", u_meaning.c_str(), 0.0, plan.u_max, plan.u_scale, SLUT_WARP_LOG1P, plan.n_u),
              make_axis("w", w_meaning.c_str(), plan.w_min, SLUT_PIO2_HI, peak_scale,
                        slut_hg_airlight_w_warp(plan.phase_g), plan.n_w)};
    Channel c;
    c.encoding = Encoding::Log;
    if (isotropic) {
        c.name = "ln_Gs";
        c.meaning =
            "ln of the scaled tail Gs(u,w) = exp(u cot w) * int_{pi/2-w}^{pi/2} exp(-u tan x) dx / w, in (0,1]";
    } else {
        c.name = "ln_Gs_g";
        c.meaning = "ln of the scaled tail Gs_g(u,w) = exp(u cot w) * int_{pi/2-w}^{pi/2} psi_g(2x) exp(-u tan x) dx "
                    "/ w, psi_g = 4 pi p_g (Henyey-Greenstein, g = phase.g), in (0, psi_max]";
        char text[32];
        std::snprintf(text, sizeof text, "%.17g", plan.phase_g);
        t.extra[kPhaseGKey] = text;
    }
    t.channels = {c};
    t.storage = plan.storage;
    return t;
}

double airlight_w_peak_scale(double phase_g) { return slut_hg_airlight_w_peak_scale(phase_g); }

double airlight_table_phase_g(const Table &table) { return table.kind == kKindAirlightFg ? table_phase_g(table) : 0.0; }

namespace {

// ------------------------------------------------------------------ quadrature nodes of the sweep

// The m-point Gauss–Legendre rules of the panels (kernels/slut_gauss_legendre.h), every order
// m ≤ kMaxOrder built once, and their error constants ln C_m. Nodes ascending.
struct GaussLegendre {
    std::vector<double> x, w;
};

constexpr int kMaxOrder = SLUT_GL_MAX_ORDER;

const GaussLegendre &gauss_legendre_cached(int m) {
    static const std::vector<GaussLegendre> rules = [] {
        std::vector<GaussLegendre> v(kMaxOrder + 1);
        for (int k = 1; k <= kMaxOrder; ++k) {
            GaussLegendre &r = v[static_cast<size_t>(k)];
            r.x.resize(static_cast<size_t>(k));
            r.w.resize(static_cast<size_t>(k));
            slut_gauss_legendre(k, r.x.data(), r.w.data());
        }
        return v;
    }();
    return rules[static_cast<size_t>(m)];
}

double log_gl_error_constant(int m) {
    static const std::vector<double> table = [] {
        std::vector<double> v(kMaxOrder + 1);
        for (int k = 1; k <= kMaxOrder; ++k) v[static_cast<size_t>(k)] = slut_gauss_legendre_log_error_constant(k);
        return v;
    }();
    return table[static_cast<size_t>(m)];
}

// The smallest order m ≤ kMaxOrder (0 if none) whose error on the panel [a, a + h] of
//   ∫ e^{−u y} / (1 + (τ + y)²) dy,  every u ∈ (0, u_max],
// is below the panel bound e^{log_eps} of the integral it belongs to, and the order for which this holds.
//  * Exponential factor: |f^{(2m)}| ≤ u^{2m} e^{−u a}, so the absolute error is
//    ≤ C_m h (u h)^{2m} e^{−u a} · f(a); the interval's integral is at least
//    ~0.63 f(τ)·min(ℓ, 1/u) (ℓ = min(Δ, |τ + i|): f halves over |τ + i|). The ratio,
//    ∝ u^{2m} max(u, 1/ℓ) e^{−u a}, is maximised in closed form over u ∈ (0, u_max].
//  * The poles of 1/(1 + t²) at y = −τ ± i: Bernstein ellipse ρ of the panel through them,
//    error ≲ 64/(15(ρ² − 1)) ρ^{−2m} relative (Trefethen, ATAP ch. 19).
// The panel bound is 1e-4 of the table's integration tolerance (the plan's; 1e-13 by
// default: panels at 1e-17). Measured, not assumed: the achieved node error reaches up to
// ~4e3 × the panel bound (at bounds 1e-10 … 1e-8; the pole term takes the ellipse through
// the pole, where the integrand is unbounded, so it is optimistic), and 1e-4 keeps every
// rung of the tolerance ladder 1e-3 … 1e-13 within its tolerance (`scatterlut report`,
// tests/commands/test_report.cpp).
constexpr double kPanelShareOfTolerance = 1e-4;

// Everything panel_order needs that does not change along one interval.
// beta2: the squared distance from the real axis of the integrand's nearest singularities
// (y = −τ ± i·β): 1 for the Lorentzian (g = 0); for the Henyey–Greenstein integrand k_g
// (kernels/slut_airlight_hg.h) β = min(1, (1 − g)/(1 + g)), the forward peak's width.
struct IntervalBounds {
    double tau, log_ell, log_inv_ell, u_split, log_u_split, u_max, log_u_max, eps, log_eps, beta2;
};

IntervalBounds interval_bounds(double tau, double ell, double u_max, double panel_eps, double beta2) {
    const double u_split = std::min(1.0 / ell, u_max);
    return {tau,           std::log(ell), -std::log(ell), u_split, std::log(u_split), u_max, std::log(u_max),
            panel_eps, std::log(panel_eps), beta2};
}

// β² of the integrand of asymmetry g (IntervalBounds): exactly 1.0 for g = 0.
double singularity_beta2(double g) {
    if (g <= 0.0) return 1.0;
    const double beta = (1.0 - g) / (1.0 + g);
    return beta * beta;
}

int panel_order(double a, double h, const IntervalBounds &b) {
    static const std::vector<double> log_int = [] { // ln k, k ≤ 2·kMaxOrder + 1
        std::vector<double> v(2 * kMaxOrder + 2, 0.0);
        for (size_t k = 1; k < v.size(); ++k) v[k] = std::log(static_cast<double>(k));
        return v;
    }();
    // Pole at y = −τ + i: with the foci at the panel ends, the ellipse through it has
    // ρ = α + √(α² − 1), α = (sum of the distances to the ends)/h. Order m holds it to
    // eps when ρ^{2m} ≥ 64/(15(ρ² − 1) eps): powers of ρ² instead of logarithms (this
    // runs ~10³ times per table).
    const double alpha =
        (std::sqrt((b.tau + a) * (b.tau + a) + b.beta2) + std::sqrt((b.tau + a + h) * (b.tau + a + h) + b.beta2)) / h;
    const double rho = alpha + std::sqrt(alpha * alpha - 1.0), rho2 = rho * rho;
    const double pole_needs = 64.0 / (15.0 * (rho2 - 1.0) * b.eps);
    double rho_2m = rho2 * rho2; // m = 2
    const double log_h = std::log(h), log_a = a > 0 ? (a == h ? log_h : std::log(a)) : 0.0;
    for (int m = 2; m <= kMaxOrder; ++m, rho_2m *= rho2) {
        if (rho_2m < pole_needs) continue;
        // max over u of u^{2m} max(u, 1/ℓ) e^{−ua}: two monotone pieces, each at its
        // stationary point (2m/a resp. u* = (2m + 1)/a) clamped to its range.
        double log_worst;
        if (a > 0 && 2.0 * m < b.u_split * a) log_worst = 2.0 * m * (log_int[2 * m] - log_a) + b.log_inv_ell - 2.0 * m;
        else log_worst = 2.0 * m * b.log_u_split + b.log_inv_ell - b.u_split * a;
        if (b.u_split < b.u_max) {
            double other;
            if (2.0 * m + 1 >= b.u_max * a) other = (2.0 * m + 1) * b.log_u_max - b.u_max * a; // u* ≥ u_max
            else if (2.0 * m + 1 <= b.u_split * a) other = (2.0 * m + 1) * b.log_u_split - b.u_split * a;
            else other = (2.0 * m + 1) * (log_int[2 * m + 1] - log_a) - (2.0 * m + 1);
            log_worst = std::max(log_worst, other);
        }
        const double log_err = log_gl_error_constant(m) + (2.0 * m + 1.0) * log_h + log_worst - std::log(0.63);
        if (log_err <= b.log_eps) return m;
    }
    return 0; // no order suffices: the panel is too long
}

// The nodes of one interval's rule for rows with u ≤ u_cap: y ∈ [0, end] with panels
// [0, h0], [h0, 2h0], [2h0, 4h0], … (the last one cut at the end), h0 = min(14/u_cap, |τ + i|)
// (16-point Gauss–Legendre integrates 14 e-folds of e^{−u y} to ~1e-17; doubling panels
// then see u·a e-folds behind them and as many across, a product that stays below 1e-18
// for every u; the first panel keeps the poles at y = −τ ± i a panel length away), each
// panel at the lowest order panel_order allows. Weights carry the Lorentzian
// 1/(1 + (τ + y)²), so the kernel forms Σ W e^{−u y}. Appends to y and weight.
// g ≠ 0: the weights carry the Henyey–Greenstein integrand k_g(τ + y) (slut_hg_air_kernel)
// instead, and the singularities sit at y = −τ ± iβ (IntervalBounds).
void append_interval_rule(double tau, double end, double u_cap, double panel_eps, std::vector<double> &y,
                          std::vector<double> &weight, double g = 0.0) {
    const double beta2 = singularity_beta2(g);
    const double pole_distance = std::sqrt(tau * tau + beta2); // |τ + iβ|: the poles at y = −τ ± iβ
    const double h0 = std::min(14.0 / u_cap, pole_distance);
    const IntervalBounds bounds = interval_bounds(tau, std::min(end, pole_distance), u_cap, panel_eps, beta2);
    for (double a = 0; a < end;) {
        double h = (a == 0) ? h0 : a;
        if (a + h >= end || end - (a + h) < 0.25 * h) h = end - a; // no sliver at the end
        int order = panel_order(a, h, bounds);
        while (order == 0) order = panel_order(a, h *= 0.5, bounds); // near a pole: shorter
        const GaussLegendre &rule = gauss_legendre_cached(order);
        for (size_t k = 0; k < rule.x.size(); ++k) {
            const double yk = a + 0.5 * h * (1.0 + rule.x[k]), ty = tau + yk;
            y.push_back(yk);
            if (g == 0.0) weight.push_back(0.5 * h * rule.w[k] / (1.0 + ty * ty));
            else weight.push_back(0.5 * h * rule.w[k] * slut_hg_air_kernel(g, 1.0, ty));
        }
        a = (h == end - a) ? end : a + h; // the last panel ends exactly at the end
    }
}

// The nodes of all intervals of the sweep (see kernels/airlight_F.cl) for rows with
// u ∈ [u_lo, u_cap]: interval j covers y ∈ [0, Δ_j] (Δ_0 = ∞), cut where u_lo·y = 40 (the
// kernel drops the same terms). No nodes where the set's rows take the large-u series or
// the Taylor form (u_cap·Δ_j ≤ 2·SLUT_GS_TAYLOR_X: every row of the set is short there).
struct RuleSet {
    std::vector<double> y, weight;
    std::vector<int> begin; // n_w + 1 offsets into y and weight
};

constexpr double kDroppedEfolds = 40.0;

// The relative error the anisotropic sweep's large-u series is held to where it replaces the
// rule: the isotropic series' 1e-16 (slut_gs_series_u_min).
constexpr double kSweepSeriesTarget = 1e-16; // e^{−40} ≈ 4e-18 of the interval's first term

RuleSet sweep_rule_set(const std::vector<double> &tau, const std::vector<double> &delta,
                       const std::vector<double> &series_u_min, double u_lo, double u_cap, double panel_eps,
                       double g = 0.0) {
    RuleSet s;
    const int n_w = static_cast<int>(tau.size());
    const double y_cut = kDroppedEfolds / u_lo;
    for (int j = 0; j < n_w; ++j) {
        const size_t k = static_cast<size_t>(j);
        s.begin.push_back(static_cast<int>(s.y.size()));
        if (u_lo >= series_u_min[k]) continue; // every item of the set uses the series
        if (j > 0 && u_cap * delta[k] <= 2.0 * SLUT_GS_TAYLOR_X) continue; // every item uses the moments
        append_interval_rule(tau[k], (j > 0) ? std::min(delta[k], y_cut) : y_cut, u_cap, panel_eps, s.y, s.weight, g);
    }
    s.begin.push_back(static_cast<int>(s.y.size()));
    return s;
}

// The Taylor moments m_jk = ((−1)^k/k!) Σ_n W_n (y_n − Δ_j/2)^k, k < SLUT_GS_TAYLOR_TERMS,
// of each interval j ≥ 1 (slut_airlight.h), from its rule for every u ≤ 2·SLUT_GS_TAYLOR_X/Δ_j
// (the rows that use them); zero for j = 0, which has no end.
std::vector<double> taylor_moments(const std::vector<double> &tau, const std::vector<double> &delta, double panel_eps,
                                   double g = 0.0) {
    constexpr size_t K = SLUT_GS_TAYLOR_TERMS;
    static const std::array<double, K> kInverse = [] { // 1/(k + 1)
        std::array<double, K> v{};
        for (size_t k = 0; k < K; ++k) v[k] = 1.0 / static_cast<double>(k + 1);
        return v;
    }();
    std::vector<double> m(tau.size() * K, 0.0), y, weight;
    for (size_t j = 1; j < tau.size(); ++j) {
        y.clear();
        weight.clear();
        append_interval_rule(tau[j], delta[j], 2.0 * SLUT_GS_TAYLOR_X / delta[j], panel_eps, y, weight, g);
        double *mj = &m[j * K];
        const double centre = 0.5 * delta[j];
        for (size_t n = 0; n < y.size(); ++n) {
            const double minus_offset = centre - y[n]; // −(y_n − Δ_j/2)
            double term = weight[n];                   // W_n (−(y_n − Δ_j/2))^k / k!
            for (size_t k = 0; k < K; ++k) {
                mj[k] += term;
                term *= minus_offset * kInverse[k];
            }
        }
    }
    return m;
}

} // namespace

// The sweep of kernels/airlight_F.cl for the integrand of asymmetry g: the Lorentzian for
// g = 0, k_g otherwise (the host's weights carry it; the kernel is the same). The large-u
// series likewise: the Lorentzian's coefficients and onset (slut_gs_large_u_coefficients,
// slut_gs_series_u_min) for g = 0, k_g's (slut_hg_sweep_large_u_coefficients, onset
// slut_hg_sweep_series_u_min at the same 1e-16) otherwise.
std::vector<double> integrate_airlight_ln_gs(Device &device, const Table &layout, double tolerance) {
    const double g = airlight_table_phase_g(layout);
    const double panel_eps = kPanelShareOfTolerance * tolerance;
    const slut_axis &au = layout.axes[0].map;
    const slut_axis &aw = layout.axes[1].map;
    constexpr int kLanes = 8; // rows per work-item (double8)
    const int row_stride = (au.count + kLanes - 1) / kLanes * kLanes;
    const int items = row_stride / kLanes;
    std::vector<double> u_rows(static_cast<size_t>(row_stride));
    double u_min_positive = HUGE_VAL;
    for (int i = 0; i < row_stride; ++i) {
        const double u = slut_axis_node(&au, std::min(i, au.count - 1)); // padding repeats the last row
        u_rows[static_cast<size_t>(i)] = u;
        if (u > 0) u_min_positive = std::min(u_min_positive, u);
    }
    if (!(u_min_positive < HUGE_VAL)) u_min_positive = 1.0; // every row u = 0: the rule is unused

    // τ_j = cot w_j and Δ_j = τ_{j−1} − τ_j. τ_{j−1}/τ_j ≤ 2 on fine axes, where the
    // difference is exact (Sterbenz): consecutive intervals meet without a gap.
    std::vector<double> w_nodes(static_cast<size_t>(aw.count)), tau(w_nodes.size()), delta(w_nodes.size(), 0.0);
    for (int j = 0; j < aw.count; ++j) {
        const size_t k = static_cast<size_t>(j);
        w_nodes[k] = slut_axis_node(&aw, j);
        tau[k] = std::cos(w_nodes[k]) / std::sin(w_nodes[k]); // as slut_w_gs_quadrature forms it
        if (j > 0) delta[k] = tau[k - 1] - tau[k];
    }
    // Where the large-u series holds (slut_gs_series_u_min) it replaces the rule; its
    // coefficients only where a work-item uses it (the kernel tests lane 0's u).
    std::vector<double> series_u_min(w_nodes.size()), series_coef(w_nodes.size() * SLUT_GS_SERIES_TERMS, 0.0);
    double u_lo_max = 0; // the largest lane-0 u of any work-item
    for (int k = 0; k < items; ++k) u_lo_max = std::max(u_lo_max, u_rows[static_cast<size_t>(kLanes * k)]);
    for (size_t k = 0; k < w_nodes.size(); ++k) {
        double *coef = &series_coef[k * SLUT_GS_SERIES_TERMS];
        if (g == 0.0) {
            series_u_min[k] = slut_gs_series_u_min(w_nodes[k]);
            if (u_lo_max >= series_u_min[k]) slut_gs_large_u_coefficients(w_nodes[k], coef);
        } else {
            // Where no lane-0 u reaches even the onset's floor 48/ρ the series is never used:
            // ∞ there, no coefficients to form (most nodes near w = π/2 for g → 1, ρ → β).
            series_u_min[k] = HUGE_VAL;
            if (u_lo_max < slut_hg_sweep_series_u_floor(std::sqrt(tau[k] * tau[k] + singularity_beta2(g)))) continue;
            double c[SLUT_HG_SERIES_TERMS];
            const double rho = slut_hg_sweep_large_u_coefficients(tau[k], g, SLUT_HG_SERIES_TERMS, c);
            series_u_min[k] = slut_hg_sweep_series_u_min(c, rho, kSweepSeriesTarget);
            std::copy(c, c + SLUT_GS_SERIES_TERMS, coef);
        }
    }

    // Rule sets for rows u ≤ cap_c = u_max/4^c: a row of small u needs no panels for a
    // layer of width 1/u_max, so each work-item takes the set of the smallest cap above its
    // largest u. Below cap ~ 1/(4 max Δ) every layer fits in its interval's first panel and
    // the poles alone set the rule: smaller caps would repeat it.
    std::vector<int> item_set(static_cast<size_t>(items), 0);
    std::vector<double> set_cap;
    const double delta_max = *std::max_element(delta.begin(), delta.end());
    double cap = std::max(au.max, u_rows.back());
    for (bool last = false; !last; cap *= 0.25) {
        last = cap < u_min_positive || cap * delta_max < 0.25;
        bool used = false;
        for (int k = 0; k < items; ++k) {
            if (u_rows[static_cast<size_t>(kLanes * k + kLanes - 1)] > cap) continue; // lane 7: the largest u
            item_set[static_cast<size_t>(k)] = static_cast<int>(set_cap.size());
            used = true;
        }
        if (used) set_cap.push_back(cap);
    }
    // Each set's rule needs to hold only down to the smallest u of the items it serves
    // (lane 0: rows ascend); sets that smaller caps took over entirely are left empty.
    std::vector<double> set_u_lo(set_cap.size(), HUGE_VAL);
    for (int k = 0; k < items; ++k) {
        double &lo = set_u_lo[static_cast<size_t>(item_set[static_cast<size_t>(k)])];
        lo = std::min(lo, std::max(u_rows[static_cast<size_t>(kLanes * k)], u_min_positive));
    }
    const std::vector<double> moments = taylor_moments(tau, delta, panel_eps, g);
    // One thread: ~0.2 ms at 257², ~0.3 ms at 1025²; threads started per call made it
    // slower and erratic on a loaded 2-core machine (0.2–3 ms).
    std::vector<RuleSet> sets(set_cap.size());
    for (size_t k = 0; k < sets.size(); ++k)
        if (set_u_lo[k] < HUGE_VAL)
            sets[k] = sweep_rule_set(tau, delta, series_u_min, set_u_lo[k], set_cap[k], panel_eps, g);
    std::vector<double> node_y, node_weight;
    std::vector<int> node_begin;
    for (RuleSet &set : sets) {
        if (set.begin.empty()) set.begin.assign(tau.size() + 1, 0); // a set no item uses
        for (int b0 : set.begin) node_begin.push_back(b0 + static_cast<int>(node_y.size()));
        node_y.insert(node_y.end(), set.y.begin(), set.y.end());
        node_weight.insert(node_weight.end(), set.weight.begin(), set.weight.end());
    }

    const char *file = "airlight_F.cl";
    cl::Program &program = device.program(file);
    cl::Kernel kernel(program, "airlight_ln_gs_sweep");
    std::vector<double> values(static_cast<size_t>(au.count) * static_cast<size_t>(aw.count));
    // The launch shape the kernel indexes by: one work-item per kLanes rows, a rule set and
    // its per-interval node ranges for each item.
    SLUT_CHECK_GT(items, 0);
    SLUT_CHECK_GE(u_rows.size(), static_cast<size_t>(kLanes) * static_cast<size_t>(items));
    SLUT_CHECK_EQ(item_set.size(), static_cast<size_t>(items));
    SLUT_CHECK_EQ(node_begin.size(), sets.size() * (tau.size() + 1));
    SLUT_CHECK_EQ(node_y.size(), node_weight.size());
    const cl::Buffer out = output_buffer(device, values);
    const cl::Buffer b_u = input_buffer(device, u_rows), b_w = input_buffer(device, w_nodes),
                     b_delta = input_buffer(device, delta), b_set = input_buffer(device, item_set),
                     b_begin = input_buffer(device, node_begin), b_y = input_buffer(device, node_y),
                     b_weight = input_buffer(device, node_weight), b_series_u = input_buffer(device, series_u_min),
                     b_series_c = input_buffer(device, series_coef),
                     b_moments = input_buffer(device, moments);
    int arg = 0;
    kernel.setArg(arg++, out);
    kernel.setArg(arg++, au.count);
    kernel.setArg(arg++, aw.count);
    for (const cl::Buffer *b : {&b_u, &b_w, &b_delta, &b_set, &b_begin, &b_y, &b_weight, &b_series_u, &b_series_c, &b_moments})
        kernel.setArg(arg++, *b);
    // Few, heavy work-items: a small local size spreads them over the cores (docs/POCL.md).
    device.queue().enqueueNDRangeKernel(kernel, cl::NullRange, cl::NDRange(static_cast<size_t>(items)), cl::NDRange(1));
    wait_for_output(device, out, values);
    device.kernels_ran(file);
    if (g != 0.0) {
        // The rows u = 0: G̃_g(0, w) is the mean of ψ_g, not 1. The recurrence at u = 0 is
        // S_j = m_j0 + S_{j−1} (m_j0 = Σ W over interval j's whole rule: its Taylor moment 0),
        // from S_0 = ∫_0^∞ k_g(τ_0 + y) dy by the panel rule of slut_airlight_hg.h. All terms
        // positive: no cancellation.
        double S = slut_hg_w_gs_quadrature(0.0, w_nodes[0], g, 1.0);
        for (size_t j = 0; j < w_nodes.size(); ++j) {
            if (j > 0) S += moments[j * SLUT_GS_TAYLOR_TERMS];
            for (int i = 0; i < au.count && u_rows[static_cast<size_t>(i)] == 0.0; ++i)
                values[j * static_cast<size_t>(au.count) + static_cast<size_t>(i)] = std::log(S / w_nodes[j]);
        }
    }
    return values;
}

Table generate_airlight_table(Device &device, const AirlightPlan &plan, const Provenance &provenance,
                              const std::function<void(double)> &progress) {
    Table t = make_airlight_table_layout(plan);
    begin_generation(t, provenance, plan.integration_tolerance);
    t.values = integrate_airlight_ln_gs(device, t, plan.integration_tolerance);
    if (progress) progress(1.0);

    // Accuracy: of the integration, of the storage type, and of sampling with the stored values.
    t.accuracy.integration_max_rel =
        measure_airlight_integration(t, airlight_measurement_nodes(t, 400, 1), IntegrationReference::FinerPanelRule);
    round_to_table_storage(t);
    SamplingStats s;
    if (plan.phase_g == 0.0) {
        const AirlightTable air(t);
        s = measure_airlight_sampling(t, [&air](double u, double w) { return air.scaled_tail(u, w); }, 20000, 2);
    } else {
        const AirlightHgTable air(t);
        s = measure_airlight_sampling(t, [&air](double u, double w) { return air.scaled_tail(u, w); }, 20000, 2);
    }
    record_sampling(t, s, std::string(plan.phase_g == 0.0 ? "Gs(u,w)" : "Gs_g(u,w)") +
                              " at uniform random unit coordinates over the whole table");
    return t;
}

std::vector<NodeIndex> airlight_measurement_nodes(const Table &table, int nodes, uint64_t seed) {
    const slut_axis &au = table.axes[0].map;
    const slut_axis &aw = table.axes[1].map;
    std::mt19937_64 rng(seed);
    std::vector<std::pair<int, int>> ij = {{0, 0}, {au.count - 1, 0}, {0, aw.count - 1}, {au.count - 1, aw.count - 1}};
    std::uniform_int_distribution<int> iu(0, au.count - 1), iw(0, aw.count - 1);
    while (static_cast<int>(ij.size()) < nodes) ij.emplace_back(iu(rng), iw(rng));
    std::vector<NodeIndex> picks(ij.size(), NodeIndex{});
    for (size_t k = 0; k < ij.size(); ++k) {
        picks[k][0] = static_cast<size_t>(ij[k].first);
        picks[k][1] = static_cast<size_t>(ij[k].second);
    }
    return picks;
}

// g = 0: slut_hg_gs_quadrature hands to slut_gs_quadrature, reference_scaled_tail_hg to
// reference_scaled_tail: the isotropic path bit for bit.
double measure_airlight_integration(const Table &table, const std::vector<NodeIndex> &nodes,
                                    IntegrationReference reference) {
    const double g = airlight_table_phase_g(table);
    const slut_axis &au = table.axes[0].map;
    const slut_axis &aw = table.axes[1].map;
    std::vector<double> err(nodes.size());
    parallel_for(static_cast<int>(nodes.size()), [&](int k) {
        const NodeIndex &p = nodes[static_cast<size_t>(k)];
        const double u = slut_axis_node(&au, static_cast<int>(p[0])), w = slut_axis_node(&aw, static_cast<int>(p[1]));
        const double stored = decode(table.channels[0].encoding, table.values[table.index(p.data())]);
        const double exact = reference == IntegrationReference::FinerPanelRule ? slut_hg_gs_quadrature(u, w, g, 3.0)
                                                                                : reference_scaled_tail_hg(u, w, g);
        err[static_cast<size_t>(k)] = std::fabs(stored - exact) / exact;
    });
    double worst = 0;
    for (double e : err) worst = std::isnan(e) ? HUGE_VAL : std::max(worst, e);
    return worst;
}

SamplingStats measure_airlight_sampling(const Table &table, const AirlightScaledTail &scaled_tail, int points,
                                        uint64_t seed) {
    const double g = airlight_table_phase_g(table);
    const slut_axis &au = table.axes[0].map;
    const slut_axis &aw = table.axes[1].map;
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<std::pair<double, double>> at(static_cast<size_t>(points));
    for (auto &p : at) p = {slut_param_from_unit(&au, unit(rng)), slut_param_from_unit(&aw, unit(rng))};
    std::vector<double> err(at.size());
    parallel_for(points, [&](int k) {
        const auto [u, w] = at[static_cast<size_t>(k)];
        const double exact = slut_hg_gs_quadrature(u, w, g, 1.0);
        err[static_cast<size_t>(k)] = std::fabs(scaled_tail(u, w) - exact) / exact;
    });
    SamplingStats s;
    const auto worst = std::max_element(err.begin(), err.end());
    s.max_rel = *worst;
    s.worst_u = at[static_cast<size_t>(worst - err.begin())].first;
    s.worst_w = at[static_cast<size_t>(worst - err.begin())].second;
    s.p99_rel = percentile(err, 0.99);
    s.median_rel = percentile(err, 0.5);
    s.points = err.size();
    return s;
}

double airlight_large_u_onset(double phase_g, double target, double w_min) {
    for (double u = 1.0; u < 1e5; u *= 1.05) {
        double worst = 0;
        for (double uu : {u, 1.3 * u, 2.0 * u})
            for (int i = 0; i < 48 && worst <= 0.5 * target; ++i) {
                const double w = w_min * std::pow(SLUT_PIO2_HI / w_min, i / 47.0);
                const double exact = slut_hg_gs_quadrature(uu, w, phase_g, 1.0);
                worst = std::max(worst, std::fabs(slut_hg_gs_large_u(uu, w, phase_g) - exact) / exact);
            }
        if (worst <= 0.5 * target) return u;
    }
    return 1e5;
}

double airlight_small_w_min(double phase_g, double target) {
    // Halve w from 1e-3 until the small-w form holds at w and below (checked at w, w/2, w/4).
    for (double w = 1e-3; w > 1e-9; w *= 0.5) {
        double worst = 0;
        for (double ww : {w, 0.5 * w, 0.25 * w})
            for (int i = 0; i < 16; ++i) {
                const double a = 1e-3 * std::pow(1e7, i / 15.0); // a = u·cot w over 1e-3 … 1e4
                const double u = a * std::tan(ww);
                const double exact = slut_hg_gs_quadrature(u, ww, phase_g, 1.0);
                worst = std::max(worst, std::fabs(slut_hg_gs_small_w(ww, a, phase_g) - exact) / exact);
            }
        if (worst <= 0.5 * target) return w;
    }
    return 1e-9;
}

} // namespace scatterlut
