#include "scene_queries.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <utility>

namespace scatterlut {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;

using Rng = std::mt19937_64;

double uniform(Rng &rng, double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(rng); }

// Log-uniform over [lo, hi] for lo > 0; uniform when the range starts at 0.
double spread(Rng &rng, const Range &r) {
    if (!(r.min > 0.0) || !(r.max > r.min)) return uniform(rng, r.min, r.max);
    return std::exp(uniform(rng, std::log(r.min), std::log(r.max)));
}

// (medium, light) pairs with a point light lighting the medium, filtered by `want`.
template <class Want>
std::vector<std::pair<const SceneMedium *, const SceneLight *>> pairs(const Scene &scene, Want want) {
    std::vector<std::pair<const SceneMedium *, const SceneLight *>> out;
    for (const SceneMedium &m : scene.media) {
        if (!want(m) || !(m.sigma_s_per_m > 0.0)) continue;
        for (const SceneLight &l : scene.lights)
            if (l.type == LightType::Point && Scene::lights_medium(l, m)) out.emplace_back(&m, &l);
    }
    return out;
}

// `count` queries over the lit pairs in turn, the k-th from pair k mod their number, drawn
// by draw(rng, medium, light, k) from one generator seeded with `seed`.
template <class Query, class Draw>
std::vector<Query> queries_over(const std::vector<std::pair<const SceneMedium *, const SceneLight *>> &lit,
                                size_t count, uint64_t seed, Draw draw) {
    std::vector<Query> out;
    if (lit.empty()) return out;
    Rng rng(seed);
    out.reserve(count);
    for (size_t k = 0; k < count; ++k) {
        const auto &[m, l] = lit[k % lit.size()];
        out.push_back(draw(rng, *m, *l, k));
    }
    return out;
}

} // namespace

std::vector<AirlightQuery> sample_airlight_queries(const Scene &scene, size_t count, uint64_t seed) {
    const auto lit = pairs(scene, [](const SceneMedium &m) { return m.viewer_inside; });
    const auto draw = [](Rng &rng, const SceneMedium &m, const SceneLight &l, size_t k) {
        AirlightQuery q;
        q.sigma_s_per_m = m.sigma_s_per_m;
        q.sigma_a_per_m = m.sigma_a_per_m;
        q.intensity_W_per_sr = l.intensity_W_per_sr;
        q.distance_m = spread(rng, l.distance_m);
        q.gamma_rad = std::acos(uniform(rng, -1.0, 1.0)); // γ: view direction ↔ direction viewer→light
        q.length_m = (k % 4 == 3) ? std::numeric_limits<double>::infinity()
                                  : q.distance_m * std::exp(uniform(rng, std::log(1e-3), std::log(10.0)));
        return q;
    };
    return queries_over<AirlightQuery>(lit, count, seed, draw);
}

std::vector<NearLightQuery> sample_near_light_queries(const Scene &scene, bool finite, size_t count, uint64_t seed) {
    const auto lit = pairs(scene, [finite](const SceneMedium &m) {
        return !m.viewer_inside && (finite ? m.has_thickness : m.thick);
    });
    const double cos_view_max = std::cos(scene.view.max_view_angle_deg * kDegree);
    const double cos_light_max = std::cos(scene.view.max_light_angle_deg * kDegree);
    const auto draw = [&](Rng &rng, const SceneMedium &m, const SceneLight &l, size_t) {
        NearLightQuery q;
        q.sigma_s_per_m = m.sigma_s_per_m;
        q.sigma_a_per_m = m.sigma_a_per_m;
        q.intensity_W_per_sr = l.intensity_W_per_sr;
        // Uniform in solid angle within the cones: cos θ uniform.
        const double mu_e = uniform(rng, cos_view_max, 1.0);
        const double mu_l = uniform(rng, std::max(0.0, cos_light_max), 1.0);
        const double phi = uniform(rng, 0.0, 2.0 * kPi);
        const double sin_e = std::sqrt(std::max(0.0, 1.0 - mu_e * mu_e));
        const double sin_l = std::sqrt(std::max(0.0, 1.0 - mu_l * mu_l));
        const double eye[3] = {sin_e, 0.0, mu_e};
        const double distance = spread(rng, l.distance_m);
        for (int i = 0; i < 3; ++i) {
            q.normal[i] = i == 2 ? 1.0 : 0.0;
            q.eye_dir[i] = eye[i];
        }
        q.light_rel_m[0] = distance * sin_l * std::cos(phi);
        q.light_rel_m[1] = distance * sin_l * std::sin(phi);
        q.light_rel_m[2] = distance * mu_l;
        q.length_m = finite ? uniform(rng, m.thickness_m.min, m.thickness_m.max) / mu_e
                            : std::numeric_limits<double>::infinity();
        return q;
    };
    return queries_over<NearLightQuery>(lit, count, seed, draw);
}

std::vector<SurfaceQuery> sample_surface_queries(const Scene &scene, int exponent, size_t count, uint64_t seed) {
    const auto lit = pairs(scene, [exponent](const SceneMedium &m) {
        if (!m.has_surfaces) return false;
        const std::vector<int> e = m.surfaces.exponents();
        return std::find(e.begin(), e.end(), exponent) != e.end();
    });
    const size_t n_pairs = lit.size();
    const auto draw = [n_pairs](Rng &rng, const SceneMedium &m, const SceneLight &l, size_t k) {
        const size_t c = (k / n_pairs) % 3; // the colour channel
        const Range &d = m.surfaces.light_distance_m;
        SurfaceQuery q;
        q.sigma_s_per_m = m.sigma_s_rgb_per_m[c];
        q.sigma_a_per_m = m.sigma_a_rgb_per_m[c];
        q.intensity_W_per_sr = l.intensity_W_per_sr;
        q.distance_m = d.min * std::pow(d.max / d.min, uniform(rng, 0.0, 1.0));
        q.theta_rad = kPi * uniform(rng, 0.0, 1.0);
        return q;
    };
    return queries_over<SurfaceQuery>(lit, count, seed, draw);
}

const char *spot_view_name(SpotView view) {
    switch (view) {
    case SpotView::inside: return "inside";
    case SpotView::beside: return "beside";
    case SpotView::along: return "along";
    }
    return "?";
}

namespace {

// A unit vector at angle θ (cos θ = cos_theta) from the unit axis n, at azimuth φ.
Vec3 around(const Vec3 &n, double cos_theta, double phi) {
    // An orthonormal pair e1, e2 ⟂ n (the axis component with the smallest |n_i| left out).
    const Vec3 helper = std::fabs(n[0]) < 0.6 ? Vec3{1, 0, 0} : Vec3{0, 1, 0};
    Vec3 e1{n[1] * helper[2] - n[2] * helper[1], n[2] * helper[0] - n[0] * helper[2],
            n[0] * helper[1] - n[1] * helper[0]};
    const double l1 = std::sqrt(e1[0] * e1[0] + e1[1] * e1[1] + e1[2] * e1[2]);
    for (double &c : e1) c /= l1;
    const Vec3 e2{n[1] * e1[2] - n[2] * e1[1], n[2] * e1[0] - n[0] * e1[2], n[0] * e1[1] - n[1] * e1[0]};
    const double sin_theta = std::sqrt(std::max(0.0, 1.0 - cos_theta * cos_theta));
    Vec3 out{};
    for (int i = 0; i < 3; ++i)
        out[i] = cos_theta * n[i] + sin_theta * (std::cos(phi) * e1[i] + std::sin(phi) * e2[i]);
    return out;
}

Vec3 unit(const Vec3 &v) {
    const double l = std::sqrt(v[0] * v[0] + v[1] * v[1] + v[2] * v[2]);
    return {v[0] / l, v[1] / l, v[2] / l};
}

} // namespace

std::vector<SpotQuery> sample_spot_queries(const Scene &scene, SpotView view, size_t count, uint64_t seed) {
    auto lit = pairs(scene, [](const SceneMedium &m) { return m.viewer_inside; });
    lit.erase(std::remove_if(lit.begin(), lit.end(), [](const auto &p) { return !p.second->spot; }), lit.end());
    const auto draw = [view](Rng &rng, const SceneMedium &m, const SceneLight &l, size_t) {
        SpotQuery q;
        q.sigma_s_per_m = m.sigma_s_per_m;
        q.sigma_a_per_m = m.sigma_a_per_m;
        q.light.position_m = {0, 0, 0};
        q.light.direction = unit(l.spot_direction);
        q.light.outer_angle_rad = l.outer_angle_deg * kDegree;
        q.light.inner_angle_rad = l.inner_angle_deg * kDegree;
        q.light.intensity_W_per_sr = l.intensity_W_per_sr;
        const Vec3 &n = q.light.direction;
        const double D = spread(rng, l.distance_m);
        const double cos_outer = std::cos(q.light.outer_angle_rad);
        const double phi = uniform(rng, 0.0, 2.0 * kPi);
        SpotView v = view;
        if (v == SpotView::beside && !(cos_outer > -1.0)) v = SpotView::inside; // no outside
        if (v == SpotView::inside) {
            const Vec3 w = around(n, uniform(rng, cos_outer, 1.0), phi);
            q.viewer_m = {D * w[0], D * w[1], D * w[2]};
            q.view_dir = around({0, 0, 1}, uniform(rng, -1.0, 1.0), uniform(rng, 0.0, 2.0 * kPi));
        } else if (v == SpotView::beside) {
            const Vec3 w = around(n, uniform(rng, -1.0, cos_outer), phi);
            q.viewer_m = {D * w[0], D * w[1], D * w[2]};
            // A point of the beam: on the axis at r, moved off it within the cone's radius.
            const double r = D * std::exp(uniform(rng, std::log(0.1), std::log(3.0)));
            const double radius = r * std::tan(std::min(q.light.outer_angle_rad, 1.4)) * std::sqrt(uniform(rng, 0.0, 1.0));
            const Vec3 off = around(n, 0.0, uniform(rng, 0.0, 2.0 * kPi));
            Vec3 target{};
            for (int i = 0; i < 3; ++i) target[i] = r * n[i] + radius * off[i] - q.viewer_m[i];
            q.view_dir = unit(target);
        } else { // along the axis line, in front of the light or behind it
            const double side = uniform(rng, 0.0, 1.0) < 0.5 ? 1.0 : -1.0;
            q.viewer_m = {side * D * n[0], side * D * n[1], side * D * n[2]};
            const double spread_rad = std::min(q.light.outer_angle_rad, kPi / 3);
            const Vec3 dir = around(n, uniform(rng, std::cos(spread_rad), 1.0), phi);
            const double look = uniform(rng, 0.0, 1.0) < 0.5 ? 1.0 : -1.0; // along the axis or against it
            q.view_dir = {look * dir[0], look * dir[1], look * dir[2]};
        }
        q.length_m = uniform(rng, 0.0, 1.0) < 0.25 ? std::numeric_limits<double>::infinity()
                                                   : D * std::exp(uniform(rng, std::log(1e-3), std::log(10.0)));
        return q;
    };
    return queries_over<SpotQuery>(lit, count, seed, draw);
}

std::string describe_airlight_queries() {
    return "viewer-inside media x point lights: D log-uniform over the light's distance range, cos(gamma) uniform in "
           "[-1, 1], s = inf for 1/4 of the queries, else log-uniform in [1e-3 D, 10 D]";
}

std::string describe_spot_queries() {
    return "viewer-inside media x spot lights: D log-uniform over the light's distance range; inside: the viewer "
           "within the outer cone, any view direction; beside: outside it, looking at a point of the beam; along: "
           "on the axis line in front of or behind the light, looking along or against the axis within the outer "
           "angle (at most 60 deg); s = inf for 1/4 of the rays, else log-uniform in [1e-3 D, 10 D]";
}

std::string describe_near_light_queries(bool finite) {
    return std::string("media seen from outside x point lights: ") + (finite ? "slabs" : "thick media") +
           "; eye and light directions uniform in solid angle within the scene's view and light cones, light "
           "distance log-uniform over its range" +
           (finite ? ", path inside s = thickness / mu_e with the thickness uniform over its range" : "");
}

} // namespace scatterlut
