// scatterlut generator — what every table kind does the same way, written once: the base of
// the kinds' descriptors (airlight_kind.cpp, nearlight_kind.cpp, surface_kind.cpp).
//
// A kind has its own plan type (Plan: AirlightPlan, … kept in PlannedTable::plan's std::any,
// with members `storage` and `integration_tolerance`), its runtime class (Runtime:
// AirlightTable, NearLightHgTable, …: the sampler its RuntimeKindOf<Runtime> facet makes) and
// its report's radiance query (Query: AirlightQuery, …). PlannedKind reads the plan, forwards
// layout, integration, generation and the measurements to the kind's generator, and builds the
// report's table radiance and lookup loop. The kind (Kind, the class deriving from
// PlannedKind<Kind, …>) names what is its own as static members, found at compile time: a
// function, or a constexpr pointer to the generator's function where it fits as it is:
//
//   Table layout_of(const Plan &)                    the table's axes, no values
//   std::vector<double> integrate_nodes(Device &, const Table &layout, double tolerance)
//   Table generate_table(Device &, const Plan &, const Provenance &, const std::function<void(double)> &progress)
//   double measure_integration(const Runtime &, const std::vector<NodeIndex> &, IntegrationReference)
//   SamplingStats measure_sampling(const Runtime &, int points, uint64_t seed)
//   double lookup(const Runtime &, const double *params, size_t axes) one lookup (axes values)
//
// and, where the default below does not fit, hides
//
//   std::vector<NodeIndex> measurement_nodes(const Table &, int nodes, uint64_t seed)  (random_table_nodes)
//   double query_radiance(const Runtime &, const Query &)  the table's answer to one query (Runtime::radiance)
//
// and overrides the TableKind functions that are its own: runtime facet, demand and plan,
// counts, radiance queries (with served_queries), runtime methods and the report's texts.
#pragma once

#include <any>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

#include "kinds/table_kind.hpp"
#include "measure_util.hpp"

namespace scatterlut {

// Whether a runtime class serves a Henyey–Greenstein kind: it records the phase's g (phase_g()).
template <class Runtime, class = void> struct RecordsPhase : std::false_type {};
template <class Runtime>
struct RecordsPhase<Runtime, std::void_t<decltype(std::declval<const Runtime &>().phase_g())>> : std::true_type {};

template <class Kind, class Plan, class Runtime, class Query> class PlannedKind : public TableKind {
public:
    // What RadianceQueries::queries holds for this kind.
    using Queries = std::vector<Query>;
    // A Henyey–Greenstein kind (airlight_Fg, near_light_E3_hg, …: one table per g, per_phase()).
    static constexpr bool kAnisotropic = RecordsPhase<Runtime>::value;

    bool per_phase() const override { return kAnisotropic; }
    void set_storage(std::any &plan, Storage storage) const override { plan_of(plan).storage = storage; }
    double integration_tolerance(const std::any &plan) const override { return plan_of(plan).integration_tolerance; }
    double interpolation_ln_floor() const override { return -HUGE_VAL; }

    Table layout(const std::any &plan, double tolerance) const override {
        Plan p = plan_of(plan);
        p.integration_tolerance = tolerance;
        return Kind::layout_of(p);
    }
    std::vector<double> integrate(Device &device, const Table &layout, double tolerance) const override {
        return Kind::integrate_nodes(device, layout, tolerance);
    }
    Table generate(Device &device, const std::any &plan, const Provenance &provenance,
                   const std::function<void(double)> &progress) const override {
        return Kind::generate_table(device, plan_of(plan), provenance, progress);
    }

    std::vector<NodeIndex> generator_nodes(const Table &table, int nodes, uint64_t seed) const override {
        return Kind::measurement_nodes(table, nodes, seed);
    }
    double integration_error(const RuntimeSampler &sampler, const std::vector<NodeIndex> &nodes,
                             IntegrationReference reference) const override {
        return Kind::measure_integration(runtime_of<Runtime>(sampler), nodes, reference);
    }
    SamplingStats sampling_error(const RuntimeSampler &sampler, int points, uint64_t seed) const override {
        return Kind::measure_sampling(runtime_of<Runtime>(sampler), points, seed);
    }

    std::function<double(size_t)> table_radiance(const Table &table, const RadianceQueries &qs) const override {
        auto runtime = std::make_shared<Runtime>(table);
        const Queries *q = &queries_of(qs);
        return [runtime, q](size_t k) { return Kind::query_radiance(*runtime, (*q)[k]); };
    }
    std::function<double()> lookup_loop(const Table &table, const std::vector<double> &params,
                                        size_t count) const override {
        auto runtime = std::make_shared<Runtime>(table);
        const std::vector<double> *p = &params;
        const size_t axes = table.axes.size();
        return [runtime, p, count, axes] {
            const double *at = p->data();
            double sum = 0;
            for (size_t i = 0; i < count; ++i) sum += Kind::lookup(*runtime, at + axes * i, axes);
            return sum;
        };
    }

    // The defaults of the kind's static functions (above).
    static std::vector<NodeIndex> measurement_nodes(const Table &table, int nodes, uint64_t seed) {
        return random_table_nodes(table, nodes, seed);
    }
    static double query_radiance(const Runtime &runtime, const Query &q) { return runtime.radiance(q); }

protected:
    static const Plan &plan_of(const std::any &plan) { return std::any_cast<const Plan &>(plan); }
    static Plan &plan_of(std::any &plan) { return std::any_cast<Plan &>(plan); }
    static const Queries &queries_of(const RadianceQueries &qs) { return std::any_cast<const Queries &>(qs.queries); }

    // The report's queries for a table: those of `all` whose exact radiance exact(q) is finite
    // and > 0 and that the table serves (serves(q)), with that radiance. Both run in parallel.
    template <class Exact, class Serves>
    static RadianceQueries served_queries(const Queries &all, Exact exact, Serves serves, std::string description) {
        std::vector<double> value(all.size());
        std::vector<char> kept(all.size());
        parallel_for(static_cast<int>(all.size()), [&](int i) {
            const size_t k = static_cast<size_t>(i);
            value[k] = exact(all[k]);
            kept[k] = std::isfinite(value[k]) && value[k] > 0 && serves(all[k]);
        });
        Queries served;
        RadianceQueries s;
        for (size_t k = 0; k < all.size(); ++k)
            if (kept[k]) {
                served.push_back(all[k]);
                s.exact.push_back(value[k]);
            }
        s.queries = std::move(served);
        s.description = std::move(description);
        return s;
    }
};

} // namespace scatterlut
