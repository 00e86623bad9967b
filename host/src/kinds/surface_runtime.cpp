// The surface terms' runtime facet (kinds/runtime_kind.hpp): the eval quantities "surface"
// (E_ss, the scattered irradiance of a surface in the medium) and "surface_specular" (S_n, the
// Phong-lobe-weighted incident airlight) of Sun et al. 2005 (docs/PHYSICS.md §1.5), exact by
// quadrature (scatterlut/surface.hpp). A loaded surface_G table (scatterlut/surface_table.hpp)
// answers "table" for the exponent it records — "surface" from an exponent-1 table,
// "surface_specular" of exponent n from an exponent-n table — where the query's T = σ_t D lies
// in its domain ("table": null otherwise).
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "eval.hpp"
#include "kinds/runtime_kind.hpp"
#include "scatterlut/surface.hpp"
#include "scatterlut/surface_table.hpp"

extern "C" {
#include "slut_surface_frontend.h" // slut_surface_direct_normal (Sun et al. 2005's direct terms)
}

namespace scatterlut {
namespace {

SurfaceQuery surface_query(const nlohmann::json &q, const char *theta_field) {
    SurfaceQuery s;
    s.sigma_s_per_m = eval_number_field(q, "sigma_s");
    s.sigma_a_per_m = eval_number_field(q, "sigma_a");
    s.intensity_W_per_sr = eval_number_field(q, "intensity");
    s.distance_m = eval_number_field(q, "distance");
    s.theta_rad = eval_number_field(q, theta_field);
    if (!(s.theta_rad >= 0.0 && s.theta_rad <= 3.14159265358979323846 + 1e-15))
        throw std::invalid_argument(std::string("field \"") + theta_field + "\" must lie in [0, pi] (rad)");
    return s;
}

// "exponent": an integer in [1, kSurfaceMaxExponent] (a JSON integer, or a number with no
// fractional part).
int surface_exponent(const nlohmann::json &q) {
    const std::string range = "[1, " + std::to_string(kSurfaceMaxExponent) + "]";
    if (!q.contains("exponent")) throw std::invalid_argument("missing field \"exponent\" (Phong exponent n, an integer in " + range + ")");
    const auto &v = q.at("exponent");
    if (!v.is_number()) throw std::invalid_argument("field \"exponent\" must be an integer in " + range);
    const double n = v.get<double>();
    if (!(n >= 1.0 && n <= kSurfaceMaxExponent && n == std::floor(n)))
        throw std::invalid_argument("field \"exponent\" must be an integer in " + range);
    return static_cast<int>(n);
}

// The first loaded surface_G table of exponent n whose T domain holds T, or nullptr.
const SurfaceTable *table_serving(const EvalTables &tables, int exponent, double optical_distance) {
    return first_runtime<SurfaceTable>(tables.samplers, [exponent, optical_distance](const SurfaceTable &t) {
        return t.exponent() == exponent && optical_distance <= t.T_max();
    });
}

// "surface": E_ss exact, from the diffuse table, without extinction, and the direct irradiance.
void answer_surface(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const SurfaceQuery s = surface_query(q, "theta_s");
    eval_put(out, "exact", surface_irradiance_exact(s)); // validates the query
    const double T = (s.sigma_s_per_m + s.sigma_a_per_m) * s.distance_m;
    if (const SurfaceTable *table = table_serving(tables, 1, T)) eval_put(out, "table", table->irradiance(s));
    else out["table"] = nullptr;
    eval_put(out, "no_extinction", surface_irradiance_no_extinction(s));
    eval_put(out, "direct",
             slut_surface_direct_normal(s.intensity_W_per_sr, T, s.distance_m) * std::fmax(std::cos(s.theta_rad), 0.0));
}

// "surface_specular": S_n exact, from the exponent-n table, and the direct lobe.
void answer_surface_specular(const nlohmann::json &q, nlohmann::json &out, const EvalTables &tables) {
    const SurfaceQuery s = surface_query(q, "theta_r");
    const int n = surface_exponent(q);
    eval_put(out, "exact", surface_specular_exact(s, n)); // validates the query
    const double T = (s.sigma_s_per_m + s.sigma_a_per_m) * s.distance_m;
    if (const SurfaceTable *table = table_serving(tables, n, T)) eval_put(out, "table", table->specular(s));
    else out["table"] = nullptr;
    eval_put(out, "direct", slut_surface_direct_normal(s.intensity_W_per_sr, T, s.distance_m) *
                                std::pow(std::fmax(std::cos(s.theta_rad), 0.0), n));
}

} // namespace

const RuntimeKind &surface_runtime_kind() {
    static const RuntimeKindOf<SurfaceTable> kind(
        kKindSurfaceG, {{"surface", answer_surface}, {"surface_specular", answer_surface_specular}});
    return kind;
}

} // namespace scatterlut
