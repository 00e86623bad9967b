#include "scatterlut/surface_table.hpp"

#include "require.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <stdexcept>
#include <string>
#include <utility>

extern "C" {
#include "slut_surface_table.h"
#include "slut_surface_frontend.h" /* slut_surface_scattered_scale */
}

namespace scatterlut {
namespace {

using detail::require; // require.hpp

void check_exponent(int exponent) {
    require(exponent >= 1 && exponent <= kSurfaceMaxExponent,
            "surface_G: the exponent must be an integer in [1, " + std::to_string(kSurfaceMaxExponent) + "], not " +
                std::to_string(exponent));
}

// The θ axis's and the channel's names: θ_s against the normal (n = 1), θ_r against the mirror direction.
const char *theta_axis_name(int exponent) { return exponent == 1 ? "theta_s" : "theta_r"; }
const char *channel_name(int exponent) { return exponent == 1 ? "ln_G0_ratio" : "ln_Gn_ratio"; }

} // namespace

double surface_G_T_scale(int exponent) {
    check_exponent(exponent);
    return exponent == 1 ? kSurfaceG0TScale : kSurfaceGnTScale;
}

double surface_G_theta_scale(int exponent) {
    check_exponent(exponent);
    return exponent == 1 ? 1.0 : 1.0 / std::sqrt(static_cast<double>(exponent) + 1.0);
}

Table surface_G_layout(int exponent, double T_max, int T_count, int theta_count) {
    check_exponent(exponent);
    require(std::isfinite(T_max) && T_max > 0.0 && T_max <= kSurfaceGTMaxLimit,
            "surface_G: T_max must be finite, > 0 and <= " + std::to_string(kSurfaceGTMaxLimit));
    require(T_count >= 2, "surface_G: the T axis needs at least 2 nodes");
    if (exponent == 1)
        require(theta_count >= 3 && theta_count % 2 == 1,
                "surface_G: the theta_s axis needs an odd count >= 3 (a node at pi/2)");
    else
        require(theta_count >= 3, "surface_G: the theta_r axis needs at least 3 nodes");
    Table t;
    t.kind = kKindSurfaceG;
    t.quantity_version = kSurfaceGQuantityVersion;
    Axis T;
    T.name = "T";
    T.meaning = "optical distance sigma_t * D from the surface point to the light";
    T.map = slut_axis{0.0, T_max, surface_G_T_scale(exponent), SLUT_WARP_LOG1P, T_count};
    Axis theta;
    theta.name = theta_axis_name(exponent);
    Channel c;
    c.name = channel_name(exponent);
    c.encoding = Encoding::Log;
    if (exponent == 1) {
        theta.meaning = "angle between the surface normal and the direction to the light (rad)";
        theta.map = slut_axis{0.0, SLUT_PI, surface_G_theta_scale(1), SLUT_WARP_LINEAR, theta_count};
        c.meaning = "ln(G0(T, theta_s) / (exp(-T) * 2 pi [cos theta_s + E(sin theta_s)]))";
    } else {
        theta.meaning = "angle between the mirror direction and the direction to the light (rad)";
        theta.map = slut_axis{0.0, SLUT_PI, surface_G_theta_scale(exponent), SLUT_WARP_LOG1P, theta_count};
        c.meaning = "ln(G_n(T, theta_r) / (exp(-T) * N_n(theta_r))), N_n = pi sqrt(2 pi/m) exp(-x) I0(x) "
                    "theta_r (pi - theta_r)/sin theta_r, m = n + 1, x = m theta_r^2/4";
    }
    t.axes = {T, theta};
    t.channels = {c};
    t.storage = Storage::F64;
    t.extra[kSurfaceExponentKey] = std::to_string(exponent);
    return t;
}

double surface_G_encode(int exponent, double optical_distance, double theta_rad, double G) {
    return std::log(G / slut_surface_G_scale(exponent, optical_distance, theta_rad));
}

Table surface_G_table_by_quadrature(int exponent, double T_max, int T_count, int theta_count) {
    Table t = surface_G_layout(exponent, T_max, T_count, theta_count);
    t.values.resize(t.node_count());
    for (int j = 0; j < theta_count; ++j) {
        const double theta = slut_axis_node(&t.axes[1].map, j);
        for (int i = 0; i < T_count; ++i) {
            const double T = slut_axis_node(&t.axes[0].map, i);
            t.values[static_cast<size_t>(j) * T_count + i] =
                surface_G_encode(exponent, T, theta, surface_G_exact(exponent, T, theta));
        }
    }
    return t;
}

int table_surface_exponent(const Table &table) {
    const auto it = table.extra.find(kSurfaceExponentKey);
    require(it != table.extra.end(),
            "surface_G table: records no \"" + std::string(kSurfaceExponentKey) + "\" (the Phong exponent)");
    const std::string &text = it->second;
    char *end = nullptr;
    errno = 0;
    const long n = std::strtol(text.c_str(), &end, 10);
    require(!text.empty() && text[0] >= '0' && text[0] <= '9' && end != text.c_str() && *end == '\0' && errno == 0 && n >= 1 && n <= kSurfaceMaxExponent,
            "surface_G table: \"" + std::string(kSurfaceExponentKey) + "\" = '" + text + "' is not an integer in [1, " +
                std::to_string(kSurfaceMaxExponent) + "]");
    return static_cast<int>(n);
}

Table surface_G0_layout(double T_max, int T_count, int theta_count) {
    return surface_G_layout(1, T_max, T_count, theta_count);
}

double surface_G0_encode(double optical_distance, double theta_rad, double g0) {
    return surface_G_encode(1, optical_distance, theta_rad, g0);
}

Table surface_G0_table_by_quadrature(double T_max, int T_count, int theta_count) {
    return surface_G_table_by_quadrature(1, T_max, T_count, theta_count);
}

SurfaceTable::SurfaceTable(Table table) : table_(std::move(table)) {
    table_.check_consistent();
    require(table_.kind == kKindSurfaceG, "surface_G table: kind is '" + table_.kind + "'");
    require(table_.quantity_version == kSurfaceGQuantityVersion,
            "surface_G table: quantity version " + std::to_string(table_.quantity_version) + ", expected " +
                std::to_string(kSurfaceGQuantityVersion));
    exponent_ = table_surface_exponent(table_);
    const std::string theta_name = theta_axis_name(exponent_);
    require(table_.axes.size() == 2 && table_.axes[0].name == "T" && table_.axes[1].name == theta_name,
            "surface_G table: expected the axes (T, " + theta_name + ") for exponent " + std::to_string(exponent_));
    const slut_axis &T = table_.axes[0].map, &th = table_.axes[1].map;
    require(T.min == 0.0 && std::isfinite(T.max) && T.max > 0.0 && T.max <= kSurfaceGTMaxLimit,
            "surface_G table: the T axis must span [0, T_max], T_max <= " + std::to_string(kSurfaceGTMaxLimit));
    require(T.warp == SLUT_WARP_LOG1P && std::isfinite(T.scale) && T.scale > 0.0,
            "surface_G table: the T axis must be log1p with a finite scale > 0");
    require(th.min == 0.0 && std::fabs(th.max - SLUT_PI) < 1e-12, "surface_G table: the " + theta_name +
                                                                      " axis must span [0, pi]");
    if (exponent_ == 1)
        require(th.warp == SLUT_WARP_LINEAR, "surface_G table: the theta_s axis of exponent 1 must be linear");
    else
        require(th.warp == SLUT_WARP_LOG1P && std::isfinite(th.scale) && th.scale > 0.0,
                "surface_G table: the theta_r axis of exponent > 1 must be log1p with a finite scale > 0");
    const std::string channel = channel_name(exponent_);
    require(table_.channels.size() == 1 && table_.channels[0].name == channel &&
                table_.channels[0].encoding == Encoding::Log,
            "surface_G table: expected one Log channel " + channel + " for exponent " + std::to_string(exponent_));
    // The ratio is at most 1 (n = 1) or e^{kSurfaceGnMaxLnRatio} (n > 1): extinction only removes light.
    const double ln_max = (exponent_ == 1 ? 0.0 : kSurfaceGnMaxLnRatio) + kLnRoundingSlack;
    for (size_t k = 0; k < table_.values.size(); ++k)
        require(std::isfinite(table_.values[k]) && table_.values[k] <= ln_max && table_.values[k] > kMinStoredLn,
                "surface_G table: stored value " + std::to_string(k) + " = " + std::to_string(table_.values[k]) +
                    " is not a finite ln ratio in (" + std::to_string(kMinStoredLn) + ", " + std::to_string(ln_max) +
                    "]");
    cache_ = make_sampler_cache(table_);
}

double SurfaceTable::G(double optical_distance, double theta_rad) const {
    require(optical_distance >= 0.0 && optical_distance <= T_max(),
            "surface_G table: T = " + std::to_string(optical_distance) + " outside the table's [0, " +
                std::to_string(T_max()) + "]");
    require(theta_rad >= 0.0 && theta_rad <= SLUT_PI,
            std::string("surface_G table: ") + theta_axis_name(exponent_) + " must lie in [0, pi]");
    const double params[2] = {optical_distance, theta_rad};
    return sample(table_, cache_, params, 0) * slut_surface_G_scale(exponent_, optical_distance, theta_rad);
}

double SurfaceTable::G0(double optical_distance, double theta_rad) const {
    require(exponent_ == 1, "surface_G table: G0 needs the diffuse table (exponent 1), this one has exponent " +
                                std::to_string(exponent_));
    return G(optical_distance, theta_rad);
}

double SurfaceTable::irradiance(const SurfaceQuery &q) const {
    require(exponent_ == 1, "surface_G table: E_ss needs the diffuse table (exponent 1), this one has exponent " +
                                std::to_string(exponent_));
    return specular(q);
}

double SurfaceTable::specular(const SurfaceQuery &q) const {
    check_surface_query(q);
    if (q.sigma_s_per_m == 0.0 || q.intensity_W_per_sr == 0.0) return 0.0;
    const double T = (q.sigma_s_per_m + q.sigma_a_per_m) * q.distance_m;
    return slut_surface_scattered_scale(q.sigma_s_per_m, q.intensity_W_per_sr, q.distance_m) *
           G(T, std::fmin(q.theta_rad, SLUT_PI));
}

} // namespace scatterlut
