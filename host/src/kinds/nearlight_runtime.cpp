// The near-light E tables' runtime facet (kinds/runtime_kind.hpp): their sampler,
// NearLightTable (tables/src/nearlight.cpp), and the eval quantities N and near_light; and the
// anisotropic kinds' (E3_hg, E4_hg): their sampler NearLightHgTable (tables/src/nearlight_hg.cpp)
// and no eval quantity of their own (eval.cpp's answer_near_light_phase reads them for
// near_light queries with a phase_g). Their descriptor: kinds/nearlight_kind.cpp.
#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "eval.hpp"
#include "kinds/runtime_kind.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/nearlight_hg.hpp"

extern "C" {
#include "slut_nearlight.h"
}

namespace scatterlut {
namespace {

// The first near-light table (E3 or E4) covering (T, g, r, S), or null.
const NearLightTable *covering(const EvalTables &tables, double T, double g, double r, double S) {
    return first_runtime<NearLightTable>(tables.samplers,
                                         [&](const NearLightTable &t) { return t.covers(T, g, r, S); });
}

bool any_near_light(const EvalTables &tables) {
    return first_runtime<NearLightTable>(tables.samplers, [](const NearLightTable &) { return true; }) != nullptr;
}

// "N": N = E·H at (T, g, r, S), exact and from the table covering it.
void answer_N(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const double T = eval_number_field(q, "T"), g = eval_number_field(q, "g"), r = eval_number_field(q, "r"),
                 S = eval_number_field(q, "S");
    if (!(T > 0.0) || !std::isfinite(T)) throw std::invalid_argument("T must be finite and > 0");
    if (!(g >= -1.0 && g <= 1.0)) throw std::invalid_argument("g must lie in [-1, 1]");
    if (!(r >= 0.0)) throw std::invalid_argument("r must be >= 0");
    if (!(S >= 0.0)) throw std::invalid_argument("S must be >= 0 (or \"inf\")");
    const double H = slut_nl_H(T, g, S), E = slut_nl_E(T, g, r, S);
    eval_put(out, "exact", (H > 0.0 && std::isfinite(H)) ? E * H : H);
    eval_put(out, "E", E);
    eval_put(out, "H", H);
    const NearLightTable *t = covering(tables, T, g, r, S);
    if (t) eval_put(out, "table", t->E(T, g, r, S) * H);
    else out["table"] = nullptr;
    eval_put(out, "approx", slut_nl_N_thin(T, g, r, S));
}

// "near_light": the radiance of a view ray into the medium, exact, from the table, and the
// thin-medium and distant-light closed forms.
void answer_near_light(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const NearLightQuery n = eval_near_light_query(q);
    eval_put(out, "exact", near_light_radiance_exact(n)); // validates the query
    const NearLightParams p = near_light_params(n);
    const NearLightTable *t = p.light_below ? nullptr : covering(tables, p.T, p.g, p.r, p.S);
    if (t) eval_put(out, "table", t->radiance(n));
    else if (p.light_below && any_near_light(tables)) out["table"] = 0.0;
    else out["table"] = nullptr;
    eval_put(out, "approx", near_light_radiance_thin(n));
    eval_put(out, "distant", near_light_radiance_distant(n));
}

} // namespace

const RuntimeKind &near_light_runtime_kind(bool finite_thickness, bool anisotropic) {
    static const std::vector<EvalAnswer> answers = {{"N", answer_N}, {"near_light", answer_near_light}};
    static const RuntimeKindOf<NearLightTable> thick(kKindNearLightE3, answers), slab(kKindNearLightE4, answers);
    static const RuntimeKindOf<NearLightHgTable> thick_hg(kKindNearLightE3Hg), slab_hg(kKindNearLightE4Hg);
    if (anisotropic) return finite_thickness ? slab_hg : thick_hg;
    return finite_thickness ? slab : thick;
}

} // namespace scatterlut
