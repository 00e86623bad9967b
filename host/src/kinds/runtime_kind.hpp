// scatterlut generator — the runtime facet of a table kind: its name, its runtime sampler and
// the eval queries it answers. It depends on the runtime library alone (no OpenCL, no
// generator), so that eval links without the device (the eval fuzzer builds it so); the
// kind's descriptor (table_kind.hpp) holds the rest and points to its facet.
//
// The facets are listed once, in kinds/runtime_registry.cpp; find_runtime_kind() is the one
// place where a kind's name (Table::kind, the file stem) is compared with a string.
#pragma once

#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include <nlohmann/json.hpp>

#include "scatterlut/table.hpp"

namespace scatterlut {

struct EvalTables;

// A kind's runtime sampler over a loaded table, opaque to all but its kind.
struct RuntimeSampler {
    virtual ~RuntimeSampler() = default;
    virtual const Table &table() const = 0;
};

// The sampler of the runtime class R (AirlightTable, NearLightTable, …), which checks the
// table in its constructor (std::invalid_argument) and keeps it.
template <class R> struct SamplerOf final : RuntimeSampler {
    explicit SamplerOf(Table t) : runtime(std::move(t)) {}
    const Table &table() const override { return runtime.table(); }
    R runtime;
};

// The runtime class R of a sampler made as a SamplerOf<R> (std::bad_cast for another).
template <class R> const R &runtime_of(const RuntimeSampler &sampler) {
    return dynamic_cast<const SamplerOf<R> &>(sampler).runtime;
}

// The first loaded table whose sampler is a SamplerOf<R> and that `accepts`, or nullptr.
template <class R, class Accept>
const R *first_runtime(const std::vector<std::shared_ptr<const RuntimeSampler>> &samplers, Accept accepts) {
    for (const auto &s : samplers)
        if (const auto *r = dynamic_cast<const SamplerOf<R> *>(s.get()))
            if (accepts(r->runtime)) return &r->runtime;
    return nullptr;
}

class RuntimeKind {
public:
    virtual ~RuntimeKind() = default;
    // Table::kind of its tables and their file stem (kKindAirlightF, …).
    virtual const char *name() const = 0;
    // The runtime sampler of a table of this kind; throws std::invalid_argument when the
    // table is not one (version, axes, channels).
    virtual std::shared_ptr<const RuntimeSampler> make_sampler(Table table) const = 0;
    // The "quantity" values of eval queries this kind answers.
    virtual std::vector<std::string> eval_quantities() const = 0;
    // Answers one query of one of its quantities into `out`, using the loaded tables it can.
    virtual void answer_eval(const std::string &quantity, const nlohmann::json &query, nlohmann::json &out,
                             const EvalTables &tables) const = 0;
};

// One eval quantity a kind answers: its "quantity" value and the function that answers a
// query of it into `out`, using the loaded tables it can.
struct EvalAnswer {
    const char *quantity;
    void (*answer)(const nlohmann::json &query, nlohmann::json &out, const EvalTables &tables);
};

// The runtime facet of a kind whose sampler is the runtime class R (AirlightTable, …): its
// name, its sampler and the eval quantities it answers (none for some kinds).
template <class R> class RuntimeKindOf final : public RuntimeKind {
public:
    explicit RuntimeKindOf(const char *name, std::vector<EvalAnswer> answers = {})
        : name_(name), answers_(std::move(answers)) {}
    const char *name() const override { return name_; }
    std::shared_ptr<const RuntimeSampler> make_sampler(Table table) const override {
        return std::make_shared<SamplerOf<R>>(std::move(table));
    }
    std::vector<std::string> eval_quantities() const override {
        std::vector<std::string> q;
        for (const EvalAnswer &a : answers_) q.emplace_back(a.quantity);
        return q;
    }
    void answer_eval(const std::string &quantity, const nlohmann::json &query, nlohmann::json &out,
                     const EvalTables &tables) const override {
        for (const EvalAnswer &a : answers_)
            if (quantity == a.quantity) return a.answer(query, out, tables);
        throw std::logic_error(std::string("the kind ") + name_ + " answers no eval quantity '" + quantity + "'");
    }

private:
    const char *name_; // Table::kind of its tables (kKindAirlightF, …)
    std::vector<EvalAnswer> answers_;
};

// Each kind's runtime facets, defined in kinds/<kind>_runtime.cpp and listed in
// kinds/runtime_registry.cpp. anisotropic: the Henyey–Greenstein kind (airlight_Fg,
// near_light_E3_hg, …); finite_thickness: the slab kind E4 (else E3).
const RuntimeKind &airlight_runtime_kind(bool anisotropic);
const RuntimeKind &near_light_runtime_kind(bool finite_thickness, bool anisotropic);
const RuntimeKind &surface_runtime_kind();
const RuntimeKind &airlight_rational_runtime_kind(); // the GPU tiers' airlight table

// Every kind's runtime facet, in the registry's order.
const std::vector<const RuntimeKind *> &runtime_kinds();
// The facet whose name() is `name`, or nullptr.
const RuntimeKind *find_runtime_kind(const std::string &name);

} // namespace scatterlut
