// scatterlut generator — the planner's resolution search: generate a trial table of each
// planned kind, measure its sampled error, refine the node counts by the h² model per axis
// (docs/SCENES.md).
#include "plan.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>

#include "kinds/derivation.hpp"
#include "spot_measure.hpp"
#include "text_format.hpp"

namespace scatterlut {
namespace {

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
constexpr int kMinNodes = kMinNodesPerAxis, kMaxNodesPerAxis = 8192;

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
    t.kind->set_storage(t.plan, storage);
    return t.kind->generate(device, t.plan, provenance, progress);
}

std::string requests_text(const PlannedTable &t) {
    std::string s;
    for (const auto &r : t.requested_by) s += (s.empty() ? "" : "; ") + r.medium + " <- " + r.light + ": " + r.need;
    return s;
}

// Spot lights served by the chosen table (docs/SPOT.md): the table path cuts each ray at the
// cone and integrates the falloff band by parts, so its error is the table's plus the band
// rule's. Measured on kSpotRaysPerView rays of each view of the beams against the exact spot
// airlight, it must hold the scene's accepted radiance error, else the table misses.
constexpr size_t kSpotRaysPerView = 200;
constexpr uint64_t kSpotSeed = 21;

void check_spot_lights(PlannedTable &t, const ScenePlan &plan, Table &best) {
    const std::optional<SpotServing> serving = t.kind->spot_serving(plan.scene, t.plan, best);
    if (!serving) return;
    const SpotMeasurement m = measure_spot_lights(*serving, kSpotRaysPerView, kSpotSeed);
    if (m.lit() == 0) return;
    const double max_rel = m.table_max(), accepted = plan.scene.relative_error;
    const bool holds = max_rel <= accepted;
    t.spot_max_rel = max_rel;
    t.verdict += "; spot lights: measured " + fmt("%.3g", max_rel) + (holds ? " <= " : " MISSES ") +
                 "the scene's error " + fmt("%.3g", accepted) + " on " + std::to_string(m.lit()) +
                 " lit rays inside, beside and along the beams";
    if (!holds) t.reached = false;
    best.extra["plan.spot_max_rel"] = fmt("%.17g", max_rel);
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
        counts = counts_of(t); // as the kind keeps them (a surface table's theta count is odd)
        const std::string label = std::string(t.name()) + " trial " + std::to_string(k + 1) + " (" + counts_text(counts) + ")";
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
                axis_interpolation_estimate(t.chosen == k ? best : table, t.kind->interpolation_ln_floor());
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
            axis_interpolation_estimate(t.chosen == k ? best : table, t.kind->interpolation_ln_floor());
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

    check_spot_lights(t, plan, best);

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

std::vector<int> counts_of(const PlannedTable &t) { return t.kind->counts(t.plan); }

void set_counts(PlannedTable &t, const std::vector<int> &c) { t.kind->set_counts(t.plan, c); }

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

void resolve_plan(ScenePlan &plan, Device &device, const Provenance &provenance,
                  const std::function<void(const std::string &, double)> &progress) {
    Provenance p = provenance;
    p.scene = plan.scene.text;
    const auto start = std::chrono::steady_clock::now();
    for (PlannedTable &t : plan.tables) resolve_table(t, plan, device, p, progress);
    plan.search_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

} // namespace scatterlut
