// The anisotropic near-light tables' runtime facet (kinds/runtime_kind.hpp): their sampler,
// NearLightHgTable (tables/src/nearlight_hg.cpp); one class for E3_hg and E4_hg, registered
// twice. Eval's near_light queries with a phase_g are answered by the near-light facet
// (kinds/nearlight_runtime.cpp), which reads these tables. Their descriptor: kinds/nearlight_kind.cpp.
#include <memory>
#include <string>

#include "kinds/runtime_kind.hpp"
#include "scatterlut/nearlight_hg.hpp"

namespace scatterlut {
namespace {

class NearLightHgRuntime final : public RuntimeKind {
public:
    explicit NearLightHgRuntime(bool finite_thickness) : finite_(finite_thickness) {}
    const char *name() const override { return finite_ ? kKindNearLightE4Hg : kKindNearLightE3Hg; }
    std::shared_ptr<const RuntimeSampler> make_sampler(Table table) const override {
        return std::make_shared<SamplerOf<NearLightHgTable>>(std::move(table));
    }
    std::vector<std::string> eval_quantities() const override { return {}; }
    void answer_eval(const std::string &, const nlohmann::json &, nlohmann::json &, const EvalTables &) const override {}

private:
    bool finite_;
};

} // namespace

const RuntimeKind &near_light_thick_hg_runtime_kind() {
    static const NearLightHgRuntime kind(false);
    return kind;
}

const RuntimeKind &near_light_slab_hg_runtime_kind() {
    static const NearLightHgRuntime kind(true);
    return kind;
}

} // namespace scatterlut
