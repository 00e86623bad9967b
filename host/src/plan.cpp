#include "plan.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {
namespace {

constexpr double kPi = 3.14159265358979323846;

// The airlight radiance is σ_s p I0 · 2/(D sin γ) · [a − b] with a = e^{−σ_t D}(π/2 − v2) G̃(A1, v2)
// and b = e^{−σ_t(s+d(s))}(π/2 − v1) G̃(A1, v1); the runtime uses this difference only where
// b ≤ a/2 (slut_airlight_from_gs; elsewhere the θ-integral). Relative errors ε on both G̃
// samples give |δ(a − b)| ≤ ε(a + b) ≤ 3ε(a − b): the table must hold a third of the
// radiance target. Near light: L = σ_s p I0 σ_t H E with H in closed form, so the
// relative error of E is that of the radiance.
constexpr double kAirlightRadiancePerTableError = 3.0;

// The search: accept a trial whose measured maximum is within kAccept of the target (the
// margin covers a worse point the 20000 random samples missed); refine towards kAim of it.
// A trial far inside the target (below kShrinkBelow) is followed by one smaller trial.
constexpr double kAccept = 0.8;
constexpr double kAim = 0.5;
constexpr double kShrinkBelow = 0.25;
constexpr int kMaxTrials = 6;
// Integration must be negligible against the interpolation it is measured with.
constexpr double kIntegrationShare = 0.01;
// Each refinement changes an axis by at most these factors (the h² model is local).
constexpr double kMaxGrowth = 3.0, kMaxShrink = 0.5;
constexpr int kMinNodes = 8, kMaxNodesPerAxis = 8192;
// Near-light measurements skip E < 1e-6 (generate_nearlight.cpp); so does the estimate.
const double kNearLightLnFloor = std::log(1e-6);

std::string fmt(const char *format, double x) {
    char buf[64];
    std::snprintf(buf, sizeof buf, format, x);
    return buf;
}

// A range of positive numbers, widened when degenerate (an axis needs min < max).
struct Span {
    double lo = std::numeric_limits<double>::infinity(), hi = 0;
    bool empty() const { return !(lo <= hi); }
    void add(double a, double b) {
        lo = std::min(lo, a);
        hi = std::max(hi, b);
    }
    Span widened() const {
        Span s = *this;
        if (s.hi < 1.1 * s.lo) {
            s.lo /= 1.05;
            s.hi *= 1.05;
        }
        return s;
    }
};

// The smallest u from which on the runtime's large-u series (slut_gs_large_u, used beyond
// the table's u_max) holds half of `target`, measured against the quadrature at u, 1.3u and
// 2u on 48 log-spaced w in [w_min, π/2] (its error falls with u like k!/u^k at the
// smallest term). The airlight table must reach at least this u.
double large_u_series_onset(double target, double w_min) {
    for (double u = 1.0; u < 1e4; u *= 1.05) {
        double worst = 0;
        for (double uu : {u, 1.3 * u, 2.0 * u})
            for (int i = 0; i < 48; ++i) {
                const double w = w_min * std::pow(SLUT_PIO2_HI / w_min, i / 47.0);
                const double exact = slut_gs_quadrature(uu, w, 1.0);
                worst = std::max(worst, std::fabs(slut_gs_large_u(uu, w) - exact) / exact);
            }
        if (worst <= 0.5 * target) return u;
    }
    return 1e4;
}

int half(int n) { return std::max(kMinNodes, (n + 1) / 2); }

size_t bytes_of(const std::vector<int> &c, Storage storage) {
    size_t n = storage_bytes(storage);
    for (int k : c) n *= static_cast<size_t>(k);
    return n;
}

// The next resolution from the measured error and the h² model per axis: with e_a the
// per-axis estimate, calibrated by c = measured/Σe_a so that the model reproduces the
// measurement, the error after scaling axis a's spacing by 1/k_a is c Σ e_a/k_a². The
// fewest nodes (Π k_a) for a given error make all terms equal: k_a = √(c d e_a / aim).
std::vector<int> next_counts(const std::vector<int> &n, const std::vector<double> &e, double measured, double aim) {
    const double sum = std::accumulate(e.begin(), e.end(), 0.0);
    const int d = static_cast<int>(std::count_if(e.begin(), e.end(), [](double x) { return x > 0; }));
    std::vector<int> out(n.size());
    for (size_t a = 0; a < n.size(); ++a) {
        double k = (sum > 0 && d > 0) ? std::sqrt((measured / sum) * d * e[a] / aim) : std::sqrt(measured / aim);
        k = std::clamp(k, kMaxShrink, kMaxGrowth);
        out[a] = std::clamp(static_cast<int>(std::lround((n[a] - 1) * k)) + 1, kMinNodes, kMaxNodesPerAxis);
    }
    return out;
}

// Scales all axes down together until the table fits `budget` bytes.
std::vector<int> fit_budget(std::vector<int> c, Storage storage, size_t budget) {
    while (bytes_of(c, storage) > budget) {
        bool shrunk = false;
        for (int &k : c)
            if (k > kMinNodes) {
                k = std::max(kMinNodes, static_cast<int>(k * 0.95));
                shrunk = true;
            }
        if (!shrunk) break;
    }
    return c;
}

Table generate_trial(PlannedTable &t, Storage storage, Device &device, const Provenance &provenance,
                     const std::function<void(double)> &progress) {
    if (t.kind == kKindAirlightF) {
        t.airlight.storage = storage;
        return generate_airlight_table(device, t.airlight, provenance, progress);
    }
    t.near_light.storage = storage;
    return generate_nearlight_table(device, t.near_light, provenance, progress);
}

std::string requests_text(const PlannedTable &t) {
    std::string s;
    for (const auto &r : t.requested_by) s += (s.empty() ? "" : "; ") + r.medium + " <- " + r.light + ": " + r.need;
    return s;
}

void resolve_table(PlannedTable &t, const ScenePlan &plan, Device &device, const Provenance &provenance,
                   const std::function<void(const std::string &, double)> &progress) {
    const size_t budget = static_cast<size_t>(plan.scene.max_table_MiB * 1024.0 * 1024.0);
    std::vector<int> counts = counts_of(t);
    if (!t.fixed_resolution) counts = fit_budget(counts, plan.storage, budget);
    const double target = t.target_rel;
    bool shrink_tried = false;
    std::string stop = "the trial limit (" + std::to_string(kMaxTrials) + ") is reached";
    Table best;
    auto better = [&](const PlanTrial &a, const PlanTrial &b) { // is a a better keeper than b?
        const bool ok_a = a.sampling_max_rel <= kAccept * target, ok_b = b.sampling_max_rel <= kAccept * target;
        if (ok_a != ok_b) return ok_a;
        return ok_a ? a.bytes < b.bytes : a.sampling_max_rel < b.sampling_max_rel;
    };
    for (int k = 0; k < kMaxTrials; ++k) {
        set_counts(t, counts);
        const std::string label = t.kind + " trial " + std::to_string(k + 1) + " (" + counts_text(counts) + ")";
        const auto start = std::chrono::steady_clock::now();
        // No callback without a listener: the near-light kernel then runs in one launch.
        std::function<void(double)> trial_progress;
        if (progress) trial_progress = [&](double f) { progress(label, f); };
        Table table = generate_trial(t, plan.storage, device, provenance, trial_progress);
        PlanTrial trial;
        trial.counts = counts;
        trial.bytes = bytes_of(counts, plan.storage);
        trial.sampling_max_rel = table.accuracy.sampling_max_rel;
        trial.sampling_p99_rel = table.accuracy.sampling_p99_rel;
        trial.integration_max_rel = table.accuracy.integration_max_rel;
        trial.storage_max_rel = table.accuracy.storage_max_rel;
        trial.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
        t.trials.push_back(trial);
        if (t.chosen < 0 || better(trial, t.trials[static_cast<size_t>(t.chosen)])) {
            t.chosen = k;
            best = std::move(table);
        }
        const double err = trial.sampling_max_rel;
        if (t.fixed_resolution) {
            stop = "resolution fixed on the command line";
            break;
        }
        if (err <= kAccept * target) { // within the target: stop, or try once a smaller table
            if (err >= kShrinkBelow * target || shrink_tried) {
                stop = "within the target";
                break;
            }
            const std::vector<double> e =
                axis_interpolation_estimate(t.chosen == k ? best : table, t.kind == kKindAirlightF ? -HUGE_VAL : kNearLightLnFloor);
            std::vector<int> smaller = next_counts(counts, e, err, kAim * target);
            for (size_t a = 0; a < smaller.size(); ++a) smaller[a] = std::min(smaller[a], counts[a]);
            shrink_tried = true;
            if (bytes_of(smaller, plan.storage) > 0.8 * static_cast<double>(trial.bytes)) {
                stop = "within the target";
                break;
            }
            counts = smaller;
            continue;
        }
        if (shrink_tried) { // the smaller table missed: keep the previous one
            stop = "within the target (a smaller trial missed it)";
            break;
        }
        if (k > 0) {
            const PlanTrial &prev = t.trials[static_cast<size_t>(k - 1)];
            // A real refinement (≥ 1.5× the nodes) that did not reduce the error: a floor
            // (storage rounding, the parametrization) that more nodes do not lower.
            if (static_cast<double>(trial.bytes) >= 1.5 * static_cast<double>(prev.bytes) &&
                err > 0.9 * prev.sampling_max_rel) {
                stop = "the error stopped falling with resolution (" + fmt("%.3g", prev.sampling_max_rel) + " -> " +
                       fmt("%.3g", err) + "; storage rounding alone " + fmt("%.2g", trial.storage_max_rel) + ")";
                break;
            }
        }
        const std::vector<double> e =
            axis_interpolation_estimate(t.chosen == k ? best : table, t.kind == kKindAirlightF ? -HUGE_VAL : kNearLightLnFloor);
        std::vector<int> next = next_counts(counts, e, err, kAim * target);
        // Refining: no axis shrinks, and the axis the estimate blames most grows.
        for (size_t a = 0; a < next.size(); ++a) next[a] = std::max(next[a], counts[a]);
        if (next == counts) {
            const size_t worst = static_cast<size_t>(std::max_element(e.begin(), e.end()) - e.begin());
            next[worst] = std::min(kMaxNodesPerAxis, counts[worst] + counts[worst] / 2);
        }
        next = fit_budget(next, plan.storage, budget);
        if (bytes_of(next, plan.storage) <= trial.bytes) {
            stop = "the size bound accuracy.max_table_MiB = " + fmt("%g", plan.scene.max_table_MiB) + " is reached";
            break;
        }
        counts = next;
    }
    const PlanTrial &c = *t.chosen_trial();
    set_counts(t, c.counts);
    t.reached = c.sampling_max_rel <= target;
    if (t.fixed_resolution)
        t.verdict = stop + ": measured " + fmt("%.3g", c.sampling_max_rel) + (t.reached ? " meets" : " MISSES") +
                    " the target " + fmt("%.3g", target);
    else if (t.reached)
        t.verdict = "measured " + fmt("%.3g", c.sampling_max_rel) + " <= target " + fmt("%.3g", target) + " at " +
                    counts_text(c.counts) + " after " + std::to_string(t.trials.size()) + " trial(s): " + stop;
    else
        t.verdict = "UNREACHABLE: best measured " + fmt("%.3g", c.sampling_max_rel) + " at " + counts_text(c.counts) +
                    " misses the target " + fmt("%.3g", target) + "; " + stop;
    if (c.integration_max_rel > kIntegrationShare * target)
        t.verdict += "; WARNING: integration error " + fmt("%.3g", c.integration_max_rel) + " exceeds " +
                     fmt("%g", kIntegrationShare) + " of the target";

    best.extra["plan.requested_by"] = requests_text(t);
    best.extra["plan.scene_relative_error"] = fmt("%.17g", plan.scene.relative_error);
    best.extra["plan.target_rel"] = fmt("%.17g", target);
    best.extra["plan.predicted_max_rel"] = fmt("%.17g", c.sampling_max_rel);
    best.extra["plan.reached"] = t.reached ? "true" : "false";
    best.extra["plan.verdict"] = t.verdict;
    if (!plan.scene.name.empty()) best.extra["scene.name"] = plan.scene.name;
    t.table = std::move(best);
}

} // namespace

std::vector<int> counts_of(const PlannedTable &t) {
    if (t.kind == kKindAirlightF) return {t.airlight.n_u, t.airlight.n_w};
    std::vector<int> c = {t.near_light.n_T, t.near_light.n_g, t.near_light.n_r};
    if (t.near_light.finite_thickness) c.push_back(t.near_light.n_S);
    return c;
}

void set_counts(PlannedTable &t, const std::vector<int> &c) {
    if (t.kind == kKindAirlightF) {
        t.airlight.n_u = c[0];
        t.airlight.n_w = c[1];
        return;
    }
    t.near_light.n_T = c[0];
    t.near_light.n_g = c[1];
    t.near_light.n_r = c[2];
    if (t.near_light.finite_thickness) t.near_light.n_S = c[3];
}

std::string counts_text(const std::vector<int> &c, const char *separator) {
    std::string s;
    for (int k : c) s += (s.empty() ? "" : separator) + std::to_string(k);
    return s;
}

std::vector<double> axis_interpolation_estimate(const Table &table, double ln_floor) {
    const size_t n_axes = table.axes.size(), channels = table.channels.size();
    std::vector<size_t> stride(n_axes);
    size_t s = channels;
    for (size_t a = 0; a < n_axes; ++a) {
        stride[a] = s;
        s *= static_cast<size_t>(table.axes[a].map.count);
    }
    std::vector<double> out(n_axes, 0.0);
    const size_t nodes = table.node_count();
    for (size_t a = 0; a < n_axes; ++a) {
        const size_t count = static_cast<size_t>(table.axes[a].map.count);
        for (size_t node = 0; node < nodes; ++node) {
            const size_t i = node / (stride[a] / channels) % count;
            if (i == 0 || i + 1 == count) continue;
            const size_t at = node * channels;
            const double v0 = table.values[at - stride[a]], v1 = table.values[at], v2 = table.values[at + stride[a]];
            if (v0 < ln_floor || v1 < ln_floor || v2 < ln_floor) continue;
            out[a] = std::max(out[a], std::fabs(v0 - 2 * v1 + v2) / 8.0);
        }
    }
    return out;
}

ScenePlan derive_plan(const Scene &scene, Storage storage, const AirlightOverrides &overrides) {
    ScenePlan plan;
    plan.scene = scene;
    plan.storage = storage;
    if (scene.media.empty()) {
        plan.notes.push_back("no medium in the scene: nothing to tabulate");
        return plan;
    }
    const double view = scene.view.max_view_angle_deg * kPi / 180.0;
    const double light = scene.view.max_light_angle_deg * kPi / 180.0;

    PlannedTable air, thick, slab;
    air.kind = kKindAirlightF;
    thick.kind = kKindNearLightE3;
    slab.kind = kKindNearLightE4;
    double u_max = 0;
    Span T_thick, T_slab, S_slab;
    // A table serves several media: it holds the strictest of their accepted errors.
    double err_air = HUGE_VAL, err_thick = HUGE_VAL, err_slab = HUGE_VAL;
    for (const SceneMedium &m : scene.media) {
        const double sigma_t = m.sigma_t_per_m();
        if (m.sigma_s_per_m == 0) {
            plan.notes.push_back("medium '" + m.name + "': sigma_s = 0, nothing scatters light towards the viewer: no table");
            continue;
        }
        bool lit = false;
        for (const SceneLight &l : scene.lights) {
            if (!Scene::lights_medium(l, m)) continue;
            lit = true;
            if (l.type == LightType::Directional) {
                plan.notes.push_back("medium '" + m.name + "' lit by directional light '" + l.name +
                                     "': the closed form serves (distant light, Gath 2008 eq. 5: L = albedo p L_in "
                                     "(1 - exp(-sigma_t (1+c) s))/(1+c)); no table");
                continue;
            }
            const double d_lo = l.distance_m.min, d_hi = l.distance_m.max;
            if (m.viewer_inside) {
                u_max = std::max(u_max, sigma_t * d_hi);
                err_air = std::min(err_air, m.relative_error);
                air.requested_by.push_back({m.name, l.name,
                                            "viewer inside, light at D <= " + fmt("%g", d_hi) +
                                                " m: u up to sigma_t*D_max = " + fmt("%.4g", sigma_t * d_hi)});
                continue;
            }
            const std::string T_text = "T = sigma_t*l in [" + fmt("%.4g", sigma_t * d_lo) + ", " +
                                       fmt("%.4g", sigma_t * d_hi) + "]";
            if (m.thick) {
                T_thick.add(sigma_t * d_lo, sigma_t * d_hi);
                err_thick = std::min(err_thick, m.relative_error);
                thick.requested_by.push_back({m.name, l.name, "thick, seen from outside: " + T_text});
            }
            if (m.has_thickness) {
                // The path inside along the view ray: the thickness, longer by 1/cos at the
                // largest view angle (a slab seen obliquely).
                const double s_lo = sigma_t * m.thickness_m.min, s_hi = sigma_t * m.thickness_m.max / std::cos(view);
                T_slab.add(sigma_t * d_lo, sigma_t * d_hi);
                err_slab = std::min(err_slab, m.relative_error);
                S_slab.add(s_lo, s_hi);
                slab.requested_by.push_back({m.name, l.name,
                                             "finite thickness, seen from outside: " + T_text +
                                                 ", S = sigma_t*s in [" + fmt("%.4g", s_lo) + ", " + fmt("%.4g", s_hi) +
                                                 "]"});
            }
        }
        if (!lit) plan.notes.push_back("medium '" + m.name + "': no light lights it: no table");
    }
    if (!air.requested_by.empty()) {
        AirlightPlan &a = air.airlight;
        air.target_rel = err_air / kAirlightRadiancePerTableError;
        if (overrides.w_min) a.w_min = *overrides.w_min;
        // u up to σ_t·D_max, and at least to where the large-u series takes over at the target.
        const double onset = large_u_series_onset(air.target_rel, a.w_min);
        a.u_max = std::max(u_max, onset);
        if (u_max < onset)
            air.domain_notes.push_back("u_max raised from " + fmt("%.3g", u_max) + " to " + fmt("%.3g", onset) +
                                       ": from there on the large-u series holds the target (measured)");
        if (overrides.u_max) a.u_max = *overrides.u_max;
        a.n_u = half(a.n_u);
        a.n_w = half(a.n_w);
        if (overrides.n_u || overrides.n_w) {
            air.fixed_resolution = true;
            a.n_u = overrides.n_u.value_or(AirlightPlan{}.n_u);
            a.n_w = overrides.n_w.value_or(AirlightPlan{}.n_w);
        }
        plan.tables.push_back(air);
    }
    // Both near-light tables: g ≥ cos(view + light angle) (the eye and light directions both
    // above the surface), r = μ_l/μ_e ≤ 1/cos(view angle).
    auto near = [&](PlannedTable &t, const Span &T, const Span *S, double target) {
        NearLightPlan &p = t.near_light;
        p = default_near_light_plan(S != nullptr);
        const Span Tw = T.widened();
        p.T_min = std::max(Tw.lo, 1e-6);
        p.T_max = Tw.hi;
        p.g_min = std::max(p.g_min, std::cos(std::min(kPi, view + light)));
        p.r_max = 1.0 / std::cos(view);
        if (S) {
            const Span Sw = S->widened();
            p.S_min = std::max(Sw.lo, 1e-6);
            p.S_max = Sw.hi;
        }
        p.n_T = half(p.n_T);
        p.n_g = half(p.n_g);
        p.n_r = half(p.n_r);
        p.n_S = half(p.n_S);
        t.target_rel = target;
        plan.tables.push_back(t);
    };
    if (!thick.requested_by.empty()) near(thick, T_thick, nullptr, err_thick);
    if (!slab.requested_by.empty()) near(slab, T_slab, &S_slab, err_slab);
    if (plan.tables.empty() && plan.notes.empty()) plan.notes.push_back("no effect needs a table");
    return plan;
}

void resolve_plan(ScenePlan &plan, Device &device, const Provenance &provenance,
                  const std::function<void(const std::string &, double)> &progress) {
    Provenance p = provenance;
    p.scene = plan.scene.text;
    const auto start = std::chrono::steady_clock::now();
    for (PlannedTable &t : plan.tables) resolve_table(t, plan, device, p, progress);
    plan.search_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace scatterlut
