// scatterlut generator — the table-kind descriptor: everything the host asks of one kind of
// table (the airlight F table, the near-light E tables, …) in one place.
//
// A kind is an abstract class with one registered instance per kind, not a struct of
// function pointers: a kind has state that several of its functions share (the near-light
// class template serves E3 and E4, parameterized by slab / thick), and the compiler checks
// that a new kind supplies every function. Each kind file lists its instances
// (<kind>_table_kinds()), kinds/registry.cpp gathers them. A kind's name, runtime sampler and eval answers are its runtime facet
// (runtime_kind.hpp: it links without OpenCL, as eval does); find_runtime_kind() is the one
// place where a kind's name (Table::kind, the file stem) is compared with a string.
//
// Each kind keeps its own plan type (AirlightPlan, NearLightPlan, …) in a std::any: the
// planner, the search and the report pass it back to the kind, which alone reads it.
//
// Adding a kind: kinds/<kind>_kind.cpp (a subclass of PlannedKind, kinds/planned_kind.hpp, which
// supplies what every kind does the same way, and <kind>_table_kinds() listing its instances)
// and kinds/<kind>_runtime.cpp (its RuntimeKindOf<Runtime>), one line in kinds/registry.cpp and
// one in kinds/runtime_registry.cpp, both files in host/CMakeLists.txt (docs/ARCHITECTURE.md
// lists the rest).
#pragma once

#include <any>
#include <cstddef>
#include <cstdint>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "gpu_methods.hpp"
#include "kinds/runtime_kind.hpp"
#include "measurement.hpp"
#include "scatterlut/spot.hpp"
#include "opencl_device.hpp"
#include "scene.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

struct PlannedTable;
struct AirlightOverrides;

// The scene's physical radiance queries for one table, with their exact radiance. What a
// query is (its type) is the kind's: `queries` holds its vector.
struct RadianceQueries {
    std::any queries;
    std::vector<double> exact; // W/(m²·sr)
    std::string description;
    size_t size() const { return exact.size(); }
};

// One way the runtime computes the same radiance (the table, closed forms, exact quadrature).
struct RuntimeMethod {
    std::string name, what;
    bool reference = false;                  // the exact quadrature: the others are measured against it
    std::function<double(size_t)> radiance;  // of query k of the RadianceQueries it was made for
};

// Spot lights (docs/SPOT.md) a table answers: the media it serves (as its radiance_queries
// draws them), its phase and the table path's radiance of a spot ray (spot_airlight_radiance).
struct SpotServing {
    Scene media;
    double phase_g = 0;
    std::function<double(const SpotQuery &)> table_radiance;
};

class TableKind {
public:
    virtual ~TableKind() = default;

    // ------------------------------------------------ identity and runtime
    // Its runtime facet: name, runtime sampler, eval answers (runtime_kind.hpp).
    virtual const RuntimeKind &runtime() const = 0;
    // Table::kind of its tables and their file stem (kKindAirlightF, …).
    const char *name() const { return runtime().name(); }

    // ------------------------------------------------ derivation: its domain from the scene
    // Called for each lit (medium, point light) pair of the scene, with `state` starting
    // empty for each kind (the kind's own accumulator); adds to t.requested_by when the pair
    // needs this kind's table.
    virtual void add_demand(const Scene &scene, const SceneMedium &medium, const SceneLight &light, std::any &state,
                            PlannedTable &t) const = 0;
    // After all pairs, when some asked: the plan (domain, starting counts) and target_rel.
    virtual void finish_plan(const Scene &scene, const std::any &state, const AirlightOverrides &overrides,
                             PlannedTable &t) const = 0;
    // Whether the kind makes one table per Henyey–Greenstein g (the planner then calls
    // add_demand with the media of one g ≠ 0 at a time, each g its own table and file stem).
    virtual bool per_phase() const { return false; }
    // Whether the kind makes one table per exponent of the scene's lit surfaces
    // (SceneSurfaces::exponents(): 1 for diffuse surfaces, each Phong exponent): the planner
    // then sets PlannedTable::exponent and calls add_demand with the media whose surfaces
    // need that exponent, each exponent its own table and file stem.
    virtual bool per_exponent() const { return false; }
    // `plan` text: why target_rel is what it is.
    virtual const char *target_reason() const = 0;

    // ------------------------------------------------ the plan's counts and settings
    // Node counts in the table's axis order.
    virtual std::vector<int> counts(const std::any &plan) const = 0;
    virtual void set_counts(std::any &plan, const std::vector<int> &counts) const = 0;
    virtual void set_storage(std::any &plan, Storage storage) const = 0;
    virtual double integration_tolerance(const std::any &plan) const = 0;
    // The resolution search's per-axis estimate skips ln values below this (−∞: none).
    virtual double interpolation_ln_floor() const = 0;

    // ------------------------------------------------ generation (the kernel and its launch)
    // A table with the plan's axes (integration tolerance `tolerance`) and no values.
    virtual Table layout(const std::any &plan, double tolerance) const = 0;
    // The stored channel at every node of `layout`, on the device; nothing measured.
    virtual std::vector<double> integrate(Device &device, const Table &layout, double tolerance) const = 0;
    // Integrated, measured and rounded to the plan's storage. progress may be empty.
    virtual Table generate(Device &device, const std::any &plan, const Provenance &provenance,
                           const std::function<void(double)> &progress) const = 0;

    // ------------------------------------------------ measurement
    // The nodes the generator measures its integration error at (`nodes` of them, from `seed`).
    virtual std::vector<NodeIndex> generator_nodes(const Table &table, int nodes, uint64_t seed) const = 0;
    // The largest relative error of the sampler's table's (decoded) values at `nodes` against
    // `reference`; +∞ if one is NaN. The one integration-error measurement of generate,
    // validate and report.
    virtual double integration_error(const RuntimeSampler &sampler, const std::vector<NodeIndex> &nodes,
                                     IntegrationReference reference) const = 0;
    // What IntegrationReference::IndependentGaussKronrod computes for this kind, in words
    // (validate's output names it).
    virtual const char *independent_reference() const { return "Boost.Math Gauss-Kronrod 61"; }
    // Interpolated values at `points` random off-node points against quadrature.
    virtual SamplingStats sampling_error(const RuntimeSampler &sampler, int points, uint64_t seed) const = 0;

    // ------------------------------------------------ report adapters
    // `count` random radiance queries over the scene's domain for this table (`plan`: its plan),
    // with their exact radiance; queries the table does not serve are left out.
    virtual RadianceQueries radiance_queries(const Scene &scene, const std::any &plan, size_t count,
                                             uint64_t seed) const = 0;
    // The runtime's methods for these queries: exact (the reference), the table, closed forms.
    virtual std::vector<RuntimeMethod> runtime_methods(const Table &table, const RadianceQueries &queries) const = 0;
    // The radiance through the table's runtime sampler, per query.
    virtual std::function<double(size_t)> table_radiance(const Table &table,
                                                         const RadianceQueries &queries) const = 0;
    // A loop of `count` table lookups at `params` (axis-count values per lookup), returning their sum.
    virtual std::function<double()> lookup_loop(const Table &table, const std::vector<double> &params,
                                                size_t count) const = 0;
    virtual const char *runtime_class() const = 0; // "AirlightTable", …
    virtual std::string methods_note() const = 0;  // the report's text under its runtime methods ("" none)
    // The spot lights this kind's table answers (the airlight tables: spot_airlight_radiance);
    // none by default. The planner and the report measure them (spot_measure.hpp).
    virtual std::optional<SpotServing> spot_serving(const Scene &, const std::any &, const Table &) const {
        return std::nullopt;
    }

    // ------------------------------------------------ the report's GPU section
    // The generated GLSL snippet that samples this table, in each tier it runs the table in,
    // and the GPU baselines engines use, over `queries` as pixels (gpu_methods.hpp); an empty
    // snippet where no snippet samples the table.
    virtual GpuSnippetMethods gpu_methods(const Table &table, const RadianceQueries &queries) const = 0;

};

// Every kind, in the order plans, output sets and reports list them.
const std::vector<const TableKind *> &table_kinds();
// The kind whose name() is `name`, or nullptr.
const TableKind *find_table_kind(const std::string &name);

} // namespace scatterlut
