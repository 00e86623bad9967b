#include "report_ladders.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <iterator>
#include <memory>
#include <random>

#include "measure_util.hpp"

extern "C" {
#include "slut_axes.h"
}

namespace scatterlut {
namespace {

// The ladders. Tolerances are relative, on the integrated quantity (G̃ or E).
constexpr double kTolerances[] = {1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13};
// Spacing factors around the planner's node counts: (n − 1)·k + 1 nodes per axis.
constexpr double kResolutionFactors[] = {0.5, 0.71, 1.0, 1.41, 2.0};
constexpr uint64_t kToleranceSeed = 11; // the same nodes on every rung
constexpr uint64_t kLookupSeed = 13;
constexpr size_t kLookups = 1 << 14;

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Keeps a computed value alive so that timed loops are not optimised away.
volatile double g_sink = 0;

// ---------------------------------------------------------------- what a planned table is
PlannedTable with_counts(PlannedTable t, const std::vector<int> &c, Storage storage) {
    set_counts(t, c);
    t.kind->set_storage(t.plan, storage);
    return t;
}

template <class Method> std::vector<double> relative_errors(const RadianceQueries &qs, Method method) {
    std::vector<double> err(qs.size());
    parallel_for(static_cast<int>(qs.size()), [&](int i) {
        const size_t k = static_cast<size_t>(i);
        err[k] = std::fabs(method(k) - qs.exact[k]) / qs.exact[k];
    });
    return err;
}

std::vector<double> random_params(const Table &t, size_t count) {
    std::mt19937_64 rng(kLookupSeed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> p(count * t.axes.size());
    for (size_t i = 0; i < count; ++i)
        for (size_t a = 0; a < t.axes.size(); ++a) p[i * t.axes.size() + a] = slut_param_from_unit(&t.axes[a].map, unit(rng));
    return p;
}

// ns per table lookup (G̃ or E) at random in-domain parameters, median of `rounds`.
double ns_per_lookup(const TableKind &kind, const Table &table, int rounds) {
    const std::vector<double> p = random_params(table, kLookups);
    const std::function<double()> lookups = kind.lookup_loop(table, p, kLookups);
    const std::function<void()> job = [&lookups] { g_sink = lookups(); };
    job(); // warm caches
    return 1e9 * interleaved_median_seconds(rounds, {job})[0] / static_cast<double>(kLookups);
}

ErrorStats radiance_errors(const TableKind &kind, const Table &table, const RadianceQueries &qs) {
    return error_stats(relative_errors(qs, kind.table_radiance(table, qs)));
}

} // namespace

ErrorStats error_stats(const std::vector<double> &err) {
    ErrorStats s;
    s.points = err.size();
    if (err.empty()) return s;
    s.median = percentile(err, 0.5);
    s.p90 = percentile(err, 0.9);
    s.p99 = percentile(err, 0.99);
    s.max = *std::max_element(err.begin(), err.end());
    return s;
}

// Runs every job `rounds` times, interleaved (job 0, 1, …, 0, 1, …), so that the machine's
// drift over minutes affects all of them alike; returns each job's median seconds.
std::vector<double> interleaved_median_seconds(int rounds, const std::vector<std::function<void()>> &jobs) {
    std::vector<std::vector<double>> t(jobs.size());
    for (int r = 0; r < rounds; ++r)
        for (size_t j = 0; j < jobs.size(); ++j) {
            const auto t0 = std::chrono::steady_clock::now();
            jobs[j]();
            t[j].push_back(seconds_since(t0));
        }
    std::vector<double> out;
    for (auto &v : t) out.push_back(percentile(v, 0.5));
    return out;
}


double planned_tolerance(const PlannedTable &t) { return t.kind->integration_tolerance(t.plan); }

// ---------------------------------------------------------------- tolerance ladder

std::vector<ToleranceRung> tolerance_ladder(Device &device, const PlannedTable &t, int rounds) {
    std::vector<double> tolerances(std::begin(kTolerances), std::end(kTolerances));
    const double planned = planned_tolerance(t);
    if (std::find(tolerances.begin(), tolerances.end(), planned) == tolerances.end()) tolerances.push_back(planned);
    std::sort(tolerances.begin(), tolerances.end(), std::greater<>());
    std::vector<ToleranceRung> out;
    std::vector<Table> tables;
    std::vector<std::function<void()>> jobs;
    for (double tol : tolerances) {
        tables.push_back(t.kind->layout(t.plan, tol));
        tables.back().values = t.kind->integrate(device, tables.back(), tol); // also the warm-up of this rung
    }
    for (size_t k = 0; k < tables.size(); ++k)
        jobs.push_back([&, k] { g_sink = t.kind->integrate(device, tables[k], tolerances[k]).back(); });
    const std::vector<double> med = interleaved_median_seconds(rounds, jobs);
    for (size_t k = 0; k < tables.size(); ++k) {
        ToleranceRung r;
        r.tolerance = tolerances[k];
        r.median_ms = 1e3 * med[k];
        r.max_node_rel = t.kind->integration_error(*t.kind->runtime().make_sampler(tables[k]),
                                                   t.kind->generator_nodes(tables[k], kToleranceNodes, kToleranceSeed),
                                                   IntegrationReference::FinerPanelRule);
        r.planned = tolerances[k] == planned;
        out.push_back(r);
    }
    return out;
}

// ---------------------------------------------------------------- resolution ladder

std::vector<ResolutionRung> resolution_ladder(Device &device, const PlannedTable &t, const RadianceQueries &qs,
                                              const Provenance &provenance, Storage planned_storage, size_t max_bytes,
                                              int rounds, const std::function<void(double)> &progress) {
    const std::vector<int> planned = counts_of(t);
    std::vector<ResolutionRung> out;
    const size_t steps = std::size(kResolutionFactors) * 2;
    size_t done = 0;
    for (double k : kResolutionFactors) {
        std::vector<int> c;
        for (int n : planned) c.push_back(std::max(4, static_cast<int>(std::lround((n - 1) * k)) + 1));
        for (Storage s : {Storage::F16, Storage::F32}) {
            ResolutionRung r;
            r.counts = c;
            r.storage = s;
            r.bytes = storage_bytes(s);
            for (int n : c) r.bytes *= static_cast<size_t>(n);
            r.planned = k == 1.0 && s == planned_storage;
            if (r.bytes > max_bytes && !r.planned) { // beyond the scene's size bound
                ++done;
                continue;
            }
            const PlannedTable rung = with_counts(t, c, s);
            const Table table = t.kind->generate(device, rung.plan, provenance, {});
            r.table_max_rel = table.accuracy.sampling_max_rel;
            r.radiance = radiance_errors(*t.kind, table, qs);
            r.ns_per_lookup = ns_per_lookup(*t.kind, table, rounds);
            out.push_back(r);
            if (progress) progress(static_cast<double>(++done) / static_cast<double>(steps));
        }
    }
    return out;
}

// ---------------------------------------------------------------- runtime methods

std::vector<MethodRow> runtime_methods(const TableKind &kind, const Table &table, const RadianceQueries &qs,
                                       int rounds) {
    const std::vector<RuntimeMethod> methods = kind.runtime_methods(table, qs);
    std::vector<std::function<void()>> jobs;
    for (auto &m : methods)
        jobs.push_back([&m, &qs] {
            double sum = 0;
            for (size_t k = 0; k < qs.size(); ++k) sum += m.radiance(k);
            g_sink = sum;
        });
    for (auto &j : jobs) j(); // warm-up
    const std::vector<double> med = interleaved_median_seconds(rounds, jobs);
    std::vector<MethodRow> out;
    for (size_t i = 0; i < methods.size(); ++i) {
        MethodRow r;
        r.name = methods[i].name;
        r.what = methods[i].what;
        r.reference = methods[i].reference;
        r.ns_per_call = 1e9 * med[i] / static_cast<double>(std::max<size_t>(1, qs.size()));
        if (!r.reference) r.error = error_stats(relative_errors(qs, methods[i].radiance));
        else r.error.points = qs.size();
        out.push_back(r);
    }
    return out;
}

} // namespace scatterlut
