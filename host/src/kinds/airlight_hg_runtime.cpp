// The anisotropic airlight table's runtime facet (kinds/runtime_kind.hpp): its sampler,
// AirlightHgTable (tables/src/airlight_hg.cpp). It lists no eval quantity of its own: eval
// answers "airlight" queries with "phase_g" ≠ 0 from a loaded table of that g (eval.cpp).
// Its descriptor: kinds/airlight_hg_kind.cpp.
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "eval.hpp"
#include "kinds/runtime_kind.hpp"
#include "scatterlut/airlight_hg.hpp"

namespace scatterlut {
namespace {

class AirlightHgRuntime final : public RuntimeKind {
public:
    const char *name() const override { return kKindAirlightFg; }
    std::shared_ptr<const RuntimeSampler> make_sampler(Table table) const override {
        return std::make_shared<SamplerOf<AirlightHgTable>>(std::move(table));
    }
    std::vector<std::string> eval_quantities() const override { return {}; }
    void answer_eval(const std::string &quantity, const nlohmann::json &, nlohmann::json &,
                     const EvalTables &) const override {
        throw std::logic_error("the anisotropic airlight kind answers no eval quantity ('" + quantity + "')");
    }
};

} // namespace

const RuntimeKind &airlight_hg_runtime_kind() {
    static const AirlightHgRuntime kind;
    return kind;
}

} // namespace scatterlut
