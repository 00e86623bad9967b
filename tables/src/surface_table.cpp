#include "scatterlut/surface_table.hpp"

#include "require.hpp"

#include <cmath>
#include <stdexcept>
#include <string>
#include <utility>

extern "C" {
#include "slut_surface.h"
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

// e^{−T} G0(0, θ_s): the closed-form scale the table's ratio multiplies.
double closed_form_scale(double optical_distance, double theta_rad) {
    return std::exp(-optical_distance) * slut_surface_G0_no_extinction(theta_rad);
}

} // namespace

Table surface_G0_layout(double T_max, int T_count, int theta_count) {
    require(std::isfinite(T_max) && T_max > 0.0, "surface_G: T_max must be finite and > 0");
    require(T_count >= 2, "surface_G: the T axis needs at least 2 nodes");
    require(theta_count >= 3 && theta_count % 2 == 1,
            "surface_G: the theta_s axis needs an odd count >= 3 (a node at pi/2)");
    Table t;
    t.kind = kKindSurfaceG;
    t.quantity_version = kSurfaceGQuantityVersion;
    Axis T;
    T.name = "T";
    T.meaning = "optical distance sigma_t * D from the surface point to the light";
    T.map = slut_axis{0.0, T_max, kSurfaceG0TScale, SLUT_WARP_LOG1P, T_count};
    Axis theta;
    theta.name = "theta_s";
    theta.meaning = "angle between the surface normal and the direction to the light (rad)";
    theta.map = slut_axis{0.0, SLUT_PI, 1.0, SLUT_WARP_LINEAR, theta_count};
    t.axes = {T, theta};
    Channel c;
    c.name = "ln_G0_ratio";
    c.meaning = "ln(G0(T, theta_s) / (exp(-T) * 2 pi [cos theta_s + E(sin theta_s)]))";
    c.encoding = Encoding::Log;
    t.channels = {c};
    t.storage = Storage::F64;
    return t;
}

double surface_G0_encode(double optical_distance, double theta_rad, double g0) {
    return std::log(g0 / closed_form_scale(optical_distance, theta_rad));
}

Table surface_G0_table_by_quadrature(double T_max, int T_count, int theta_count) {
    Table t = surface_G0_layout(T_max, T_count, theta_count);
    t.values.resize(t.node_count());
    for (int j = 0; j < theta_count; ++j) {
        const double theta = slut_axis_node(&t.axes[1].map, j);
        for (int i = 0; i < T_count; ++i) {
            const double T = slut_axis_node(&t.axes[0].map, i);
            t.values[static_cast<size_t>(j) * T_count + i] = surface_G0_encode(T, theta, surface_G_exact(1, T, theta));
        }
    }
    return t;
}

SurfaceTable::SurfaceTable(Table table) : table_(std::move(table)) {
    table_.check_consistent();
    require(table_.kind == kKindSurfaceG, "surface_G table: kind is '" + table_.kind + "'");
    require(table_.quantity_version == kSurfaceGQuantityVersion,
            "surface_G table: quantity version " + std::to_string(table_.quantity_version) + ", expected " +
                std::to_string(kSurfaceGQuantityVersion));
    require(table_.axes.size() == 2 && table_.axes[0].name == "T" && table_.axes[1].name == "theta_s",
            "surface_G table: expected the axes (T, theta_s)");
    const slut_axis &T = table_.axes[0].map, &th = table_.axes[1].map;
    require(T.min == 0.0 && std::isfinite(T.max) && T.max > 0.0, "surface_G table: the T axis must span [0, T_max]");
    require(T.warp == SLUT_WARP_LOG1P && std::isfinite(T.scale) && T.scale > 0.0,
            "surface_G table: the T axis must be log1p with a finite scale > 0");
    require(th.min == 0.0 && std::fabs(th.max - SLUT_PI) < 1e-12 && th.warp == SLUT_WARP_LINEAR,
            "surface_G table: the theta_s axis must be linear on [0, pi]");
    require(table_.channels.size() == 1 && table_.channels[0].name == "ln_G0_ratio" &&
                table_.channels[0].encoding == Encoding::Log,
            "surface_G table: expected one Log channel ln_G0_ratio");
    for (size_t k = 0; k < table_.values.size(); ++k)
        require(std::isfinite(table_.values[k]) && table_.values[k] <= kLnRoundingSlack && table_.values[k] > kMinStoredLn,
                "surface_G table: stored value " + std::to_string(k) + " is not a finite ln ratio <= 0");
    cache_ = make_sampler_cache(table_);
}

double SurfaceTable::G0(double optical_distance, double theta_rad) const {
    require(optical_distance >= 0.0 && optical_distance <= T_max(),
            "surface_G table: T = " + std::to_string(optical_distance) + " outside the table's [0, " +
                std::to_string(T_max()) + "]");
    require(theta_rad >= 0.0 && theta_rad <= SLUT_PI, "surface_G table: theta_s must lie in [0, pi]");
    const double params[2] = {optical_distance, theta_rad};
    return sample(table_, cache_, params, 0) * closed_form_scale(optical_distance, theta_rad);
}

double SurfaceTable::irradiance(const SurfaceQuery &q) const {
    check_surface_query(q);
    if (q.sigma_s_per_m == 0.0 || q.intensity_W_per_sr == 0.0) return 0.0;
    const double T = (q.sigma_s_per_m + q.sigma_a_per_m) * q.distance_m;
    return q.sigma_s_per_m * q.intensity_W_per_sr / (4.0 * SLUT_PI * q.distance_m) * G0(T, q.theta_rad);
}

} // namespace scatterlut
