// The airlight tables' runtime facets (kinds/runtime_kind.hpp). airlight_F: its sampler,
// AirlightTable (tables/src/airlight.cpp), and the eval quantities F and airlight.
// airlight_Fg: its sampler, AirlightHgTable (tables/src/airlight_hg.cpp), and no eval quantity
// of its own: eval answers "airlight" queries with "phase_g" ≠ 0 from a loaded table of that g
// (eval.cpp). Their descriptor: kinds/airlight_kind.cpp.
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "eval.hpp"
#include "kinds/runtime_kind.hpp"
#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/spot.hpp"

extern "C" {
#include "slut_airlight.h"
}

namespace scatterlut {
namespace {

// The loaded airlight_F table, or nullptr.
const AirlightTable *airlight_table(const EvalTables &tables) {
    return first_runtime<AirlightTable>(tables.samplers, [](const AirlightTable &) { return true; });
}

// "F": F(u, v) and its tail by quadrature and from the table.
void answer_F(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const double u = eval_number_field(q, "u"), v = eval_number_field(q, "v");
    if (!(u >= 0.0) || !std::isfinite(u)) throw std::invalid_argument("u must be finite and >= 0");
    if (!(v >= 0.0) || !(v <= 1.5707963267948968)) throw std::invalid_argument("v must lie in [0, pi/2]");
    eval_put(out, "exact", slut_F_quadrature(u, v));
    eval_put(out, "tail", slut_tail_quadrature(u, v));
    if (const AirlightTable *table = airlight_table(tables)) {
        eval_put(out, "table", table->F(u, v));
        eval_put(out, "table_tail", table->tail(u, v));
    } else {
        out["table"] = nullptr;
        out["table_tail"] = nullptr;
    }
}

// "airlight": the radiance of a view ray, exact and from the table.
void answer_airlight(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const AirlightQuery a = eval_airlight_query(q);
    const double exact = airlight_radiance_exact(a); // validates the query
    eval_put(out, "exact", exact);
    const bool through_light = a.gamma_rad == 0.0 && a.length_m >= a.distance_m;
    if (through_light) out["note"] = "diverges: the view ray passes through the light";
    if (const AirlightTable *table = airlight_table(tables)) eval_put(out, "table", table->radiance(a));
    else out["table"] = nullptr;
}

// A "spot_airlight" line's query: σ, I0, the ray (viewer, view_dir, length) and the spot
// (light_pos, spot_dir, outer_angle, inner_angle defaulting to outer_angle; angles in rad).
SpotQuery eval_spot_query(const nlohmann::json &q) {
    SpotQuery s;
    s.sigma_s_per_m = eval_number_field(q, "sigma_s");
    s.sigma_a_per_m = eval_number_field(q, "sigma_a");
    s.light.intensity_W_per_sr = eval_number_field(q, "intensity");
    eval_vector_field(q, "viewer", s.viewer_m.data());
    eval_vector_field(q, "view_dir", s.view_dir.data());
    s.length_m = eval_number_field(q, "length");
    eval_vector_field(q, "light_pos", s.light.position_m.data());
    eval_vector_field(q, "spot_dir", s.light.direction.data());
    s.light.outer_angle_rad = eval_number_field(q, "outer_angle");
    s.light.inner_angle_rad = q.contains("inner_angle") ? eval_number_field(q, "inner_angle") : s.light.outer_angle_rad;
    return s;
}

} // namespace

void answer_spot_airlight(const nlohmann::json &q, double phase_g, nlohmann::json &out, const EvalTables &tables) {
    const SpotQuery s = eval_spot_query(q);
    const double exact = spot_airlight_radiance_exact(s, phase_g); // validates the query
    eval_put(out, "exact", exact);
    if (exact == HUGE_VAL) out["note"] = "diverges: the view ray passes through the light where the beam is lit";
    // The airlight tables cover every u and w (asymptotic forms beyond their axes): any table of the query's g.
    if (phase_g == 0.0) {
        if (const AirlightTable *table = airlight_table(tables)) eval_put(out, "table", spot_airlight_radiance(*table, s));
        else out["table"] = nullptr;
        return;
    }
    const AirlightHgTable *table =
        first_runtime<AirlightHgTable>(tables.samplers, [&](const AirlightHgTable &t) { return t.serves(phase_g); });
    if (table) eval_put(out, "table", spot_airlight_radiance(*table, s));
    else out["table"] = nullptr;
}

const RuntimeKind &airlight_runtime_kind(bool anisotropic) {
    static const RuntimeKindOf<AirlightTable> isotropic_kind(kKindAirlightF,
                                                             {{"F", answer_F},
                                                              {"airlight", answer_airlight},
                                                              {"spot_airlight", [](const nlohmann::json &q, nlohmann::json &out,
                                                                                   const EvalTables &tables) {
                                                                   answer_spot_airlight(q, 0.0, out, tables);
                                                               }}});
    static const RuntimeKindOf<AirlightHgTable> anisotropic_kind(kKindAirlightFg);
    if (anisotropic) return anisotropic_kind;
    return isotropic_kind;
}

} // namespace scatterlut
