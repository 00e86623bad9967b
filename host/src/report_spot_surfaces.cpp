#include "report_spot_surfaces.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <random>
#include <string>
#include <vector>

#include "report_writers.hpp" // write_text
#include "text_format.hpp"
#include "scatterlut/spot_surface.hpp"
#include "scatterlut/surface.hpp"

namespace scatterlut {
namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegree = kPi / 180.0;
constexpr uint64_t kSeed = 32; // issue #32: the points are the same on every run

bool lights_spot_surfaces(const SceneMedium &m, const SceneLight &l) {
    return l.spot && l.type == LightType::Point && m.viewer_inside && m.has_surfaces && m.sigma_s_per_m > 0.0 &&
           Scene::lights_medium(l, m);
}

// One surface term at one point: the spot's exact value, the point light's, the falloff and the
// direct term it sits beside (W/m²).
struct Sample {
    std::string medium, light;
    int channel = 0;
    int exponent = 1; // 1: E_ss (the diffuse table), n > 1: S_n
    double outer_deg = 0, inner_deg = 0, theta_P_deg = 0, distance_m = 0, optical_depth = 0;
    double falloff = 0;
    double exact = 0, point = 0; // the scattered term: the spot's, the point light's (both exact)
    double thin = 0;             // the thin-beam model's: min(point, e^{−T} σ_s I0/(4π D) G^spot_n(0))
    double direct = 0;           // the direct term beside it, already times f
    // The approximation of model m (0: falloff, 1: thin beam).
    double approx(int m) const { return m == 0 ? falloff * point : thin; }
    double ratio(int m) const { return approx(m) / exact; }                             // scattered term
    double total_ratio(int m) const { return (direct + approx(m)) / (direct + exact); } // with the direct term
    double scaled_error(int m) const { return std::fabs(approx(m) - exact) / point; }   // on the point light's scale
};
const char *model_name(int m) { return m == 0 ? "falloff" : "thin beam"; }

enum Where { kInside, kBand, kOutside };
const char *where_name(int w) { return w == kInside ? "inside the inner cone" : w == kBand ? "falloff band" : "outside the beam"; }
int where_of(const Sample &s) { return s.falloff >= 1.0 ? kInside : (s.falloff > 0.0 ? kBand : kOutside); }

using V = std::array<double, 3>;
double dot(const V &a, const V &b) { return a[0] * b[0] + a[1] * b[1] + a[2] * b[2]; }
double angle(const V &a, const V &b) { // both unit
    const V c{a[1] * b[2] - a[2] * b[1], a[2] * b[0] - a[0] * b[2], a[0] * b[1] - a[1] * b[0]};
    return std::atan2(std::sqrt(dot(c, c)), dot(a, b));
}

V random_unit(std::mt19937_64 &rng) {
    std::uniform_real_distribution<double> U(-1.0, 1.0);
    for (;;) {
        const V v{U(rng), U(rng), U(rng)};
        const double r2 = dot(v, v);
        if (r2 > 1e-4 && r2 <= 1.0) {
            const double r = std::sqrt(r2);
            return {v[0] / r, v[1] / r, v[2] / r};
        }
    }
}

std::vector<Sample> draw_samples(const Scene &scene, int points) {
    std::vector<std::pair<const SceneMedium *, const SceneLight *>> pairs;
    for (const SceneMedium &m : scene.media)
        for (const SceneLight &l : scene.lights)
            if (lights_spot_surfaces(m, l)) pairs.emplace_back(&m, &l);
    std::vector<Sample> out;
    if (pairs.empty()) return out;
    std::mt19937_64 rng(kSeed);
    std::uniform_real_distribution<double> U(0.0, 1.0);
    for (int k = 0; k < points; ++k) {
        const SceneMedium &m = *pairs[static_cast<size_t>(k) % pairs.size()].first;
        const SceneLight &l = *pairs[static_cast<size_t>(k) % pairs.size()].second;
        const int channel = static_cast<int>((static_cast<size_t>(k) / pairs.size()) % 3);
        const Range &d = m.surfaces.light_distance_m;
        const double D = d.min * std::pow(d.max / d.min, U(rng));
        const double theta_P = std::min(kPi, (2.0 * l.outer_angle_deg + 10.0) * kDegree) * U(rng);
        const V normal = random_unit(rng), mirror = random_unit(rng);
        // The light at the origin, its axis +z (G depends on the geometry only through angles).
        SpotSurfacePoint q;
        q.sigma_s_per_m = m.sigma_s_rgb_per_m[static_cast<size_t>(channel)];
        q.sigma_a_per_m = m.sigma_a_rgb_per_m[static_cast<size_t>(channel)];
        q.point_m = {D * std::sin(theta_P), 0.0, D * std::cos(theta_P)};
        q.light.position_m = {0, 0, 0};
        q.light.direction = {0, 0, 1};
        q.light.outer_angle_rad = l.outer_angle_deg * kDegree;
        q.light.inner_angle_rad = l.inner_angle_deg * kDegree;
        q.light.intensity_W_per_sr = l.intensity_W_per_sr;
        const V to_light{-std::sin(theta_P), 0.0, -std::cos(theta_P)};
        const double T = (q.sigma_s_per_m + q.sigma_a_per_m) * D, f = spot_falloff_at_point(q.light, q.point_m.data());
        const double normal_irradiance = l.intensity_W_per_sr * std::exp(-T) / (D * D); // I0 e^{−T}/D²
        const double cos_s = dot(normal, to_light), cos_r = dot(mirror, to_light);
        for (int n : m.surfaces.exponents()) {
            Sample s;
            s.medium = m.name;
            s.light = l.name;
            s.channel = channel;
            s.exponent = n;
            s.outer_deg = l.outer_angle_deg;
            s.inner_deg = l.inner_angle_deg;
            s.theta_P_deg = theta_P / kDegree;
            s.distance_m = D;
            s.optical_depth = T;
            s.falloff = f;
            SurfaceQuery p;
            p.sigma_s_per_m = q.sigma_s_per_m;
            p.sigma_a_per_m = q.sigma_a_per_m;
            p.intensity_W_per_sr = l.intensity_W_per_sr;
            p.distance_m = D;
            if (n == 1) {
                q.lobe_axis = normal;
                p.theta_rad = angle(normal, to_light);
                s.exact = spot_surface_irradiance_exact(q);
                s.point = surface_irradiance_exact(p);
                s.direct = f * normal_irradiance * std::max(cos_s, 0.0);
            } else {
                q.lobe_axis = mirror;
                p.theta_rad = angle(mirror, to_light);
                s.exact = spot_surface_specular_exact(q, n);
                s.point = surface_specular_exact(p, n);
                s.direct = cos_s > 0.0 && cos_r > 0.0 ? f * normal_irradiance * std::pow(cos_r, n) : 0.0;
            }
            const double scale = q.sigma_s_per_m * l.intensity_W_per_sr / (4.0 * kPi * D); // W/m² per unit of G
            s.thin = std::min(s.point, std::exp(-T) * scale * spot_surface_G_thin(n, q));
            if (s.exact > 0.0) out.push_back(s);
        }
    }
    return out;
}

double quantile(std::vector<double> v, double q) {
    if (v.empty()) return NAN;
    std::sort(v.begin(), v.end());
    const size_t i = std::min(v.size() - 1, static_cast<size_t>(q * static_cast<double>(v.size() - 1) + 0.5));
    return v[i];
}

std::string ratio_text(double r) {
    if (!std::isfinite(r)) return "-";
    if (r == 0.0) return "0";
    return r >= 0.1 ? fmt("%.3g", r) : fmt("%.2g", r);
}

std::string term_name(int n) { return n == 1 ? "E_ss (diffuse)" : "S_" + std::to_string(n) + " (Phong)"; }

std::string csv_of(const std::vector<Sample> &samples) {
    std::string s = "medium,light,channel,term,outer_deg,inner_deg,theta_P_deg,D_m,sigma_t_D,falloff,exact_W_m2,"
                    "point_light_W_m2,falloff_W_m2,falloff_over_exact,thin_beam_W_m2,thin_beam_over_exact,direct_W_m2,"
                    "total_falloff_over_exact,total_thin_beam_over_exact\n";
    for (const Sample &x : samples)
        s += x.medium + "," + x.light + "," + std::to_string(x.channel) + "," + (x.exponent == 1 ? "E_ss" : "S_" + std::to_string(x.exponent)) +
             "," + fmt("%.6g", x.outer_deg) + "," + fmt("%.6g", x.inner_deg) + "," + fmt("%.6g", x.theta_P_deg) + "," +
             fmt("%.6g", x.distance_m) + "," + fmt("%.6g", x.optical_depth) + "," + fmt("%.6g", x.falloff) + "," +
             fmt("%.9g", x.exact) + "," + fmt("%.9g", x.point) + "," + fmt("%.9g", x.approx(0)) + "," +
             fmt("%.6g", x.ratio(0)) + "," + fmt("%.9g", x.approx(1)) + "," + fmt("%.6g", x.ratio(1)) + "," +
             fmt("%.9g", x.direct) + "," + fmt("%.6g", x.total_ratio(0)) + "," + fmt("%.6g", x.total_ratio(1)) + "\n";
    return s;
}

} // namespace

bool scene_has_spot_surfaces(const Scene &scene) {
    for (const SceneMedium &m : scene.media)
        for (const SceneLight &l : scene.lights)
            if (lights_spot_surfaces(m, l)) return true;
    return false;
}

std::string spot_surface_section(const Scene &scene, int points, const std::string &out_dir) {
    const std::vector<Sample> samples = draw_samples(scene, points);
    write_text(out_dir + "/spot_surfaces.csv", csv_of(samples));
    std::string md = "\n## Surfaces lit by spot lights\n\n";
    md += "Engines light a surface under a spot with the point light's surface terms (Sun et al. 2005; the surface_G "
          "tables above) and glTF KHR_lights_punctual's falloff f(theta_P) of the direction from the lamp to the "
          "point: the direct terms times f (exact), the scattered terms E_ss and S_n times a factor, an "
          "approximation (the point light's scattered light comes from the whole medium around the lamp, the spot's "
          "only from its beam): 'falloff' f itself, or 'thin beam' min(1, e^(-sigma_t D) G_spot(0) / G), the spot's "
          "integral without extinction by a fixed rule (scatterlut/spot_surface.hpp). Here both against the spot's exact scattered terms (scatterlut/spot_surface.hpp: "
          "the integral over the beam's volume, ~1e-8) on " + std::to_string(points) +
          " random surface points of this scene (every medium with surfaces x every spot lighting it, each colour "
          "channel in turn; D log-uniform over the surfaces' light_distance_m; the point's angle from the spot's "
          "axis uniform in [0, min(180, 2 theta_o + 10)] degrees; normal and mirror direction uniform on the sphere; "
          "the point light's terms exact, so that the tables' own error, measured above, stays out). Ratio = "
          "approximation / exact; 'with direct' adds the exact direct term (f E_d, or f P_d) to both. All points: "
          "`spot_surfaces.csv`.\n\n";
    if (samples.empty()) return md + "No point received scattered light (no spot lights a medium with surfaces).\n";
    md += "| term | spot (outer / inner) | where the point lies | points | sigma_t D | model | ratio: median | min | "
          "max | with direct: median | max | max error / point light's |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|\n";
    std::vector<std::pair<int, std::string>> groups; // (exponent, light) in order of appearance, sorted by exponent
    for (const Sample &s : samples)
        if (std::find(groups.begin(), groups.end(), std::make_pair(s.exponent, s.light)) == groups.end())
            groups.emplace_back(s.exponent, s.light);
    std::stable_sort(groups.begin(), groups.end(), [](const auto &a, const auto &b) { return a.first < b.first; });
    std::string verdict;
    for (const auto &[n, light] : groups) {
        for (int w = kInside; w <= kOutside; ++w) {
            std::vector<const Sample *> in;
            for (const Sample &s : samples)
                if (s.exponent == n && s.light == light && where_of(s) == w) in.push_back(&s);
            if (in.empty()) continue;
            const std::string cone = fmt("%g", in[0]->outer_deg) + " / " + fmt("%g", in[0]->inner_deg) + " deg";
            std::vector<double> T, glow;
            for (const Sample *s : in) {
                T.push_back(s->optical_depth);
                glow.push_back(s->exact / s->point);
            }
            const std::string who = term_name(n) + ", " + light + " (" + cone + ")";
            for (int model = 0; model < 2; ++model) {
                std::vector<double> ratio, total, scaled;
                for (const Sample *s : in) {
                    ratio.push_back(s->ratio(model));
                    total.push_back(s->total_ratio(model));
                    scaled.push_back(s->scaled_error(model));
                }
                md += "| " + term_name(n) + " | " + light + " (" + cone + ") | " + where_name(w) + " | " +
                      std::to_string(in.size()) + " | " + fmt("%.3g", quantile(T, 0.0)) + " - " +
                      fmt("%.3g", quantile(T, 1.0)) + " | " + model_name(model) + " | " +
                      ratio_text(quantile(ratio, 0.5)) + " | " + ratio_text(quantile(ratio, 0.0)) + " | " +
                      ratio_text(quantile(ratio, 1.0)) + " | " + ratio_text(quantile(total, 0.5)) + " | " +
                      ratio_text(quantile(total, 1.0)) + " | " + ratio_text(quantile(scaled, 1.0)) + " |\n";
                if (w == kInside)
                    verdict += "- " + who + ", inside the inner cone, " + model_name(model) + ": " +
                               ratio_text(quantile(ratio, 0.5)) + "x the spot's scattered term (median; " +
                               ratio_text(quantile(ratio, 0.0)) + "x to " + ratio_text(quantile(ratio, 1.0)) +
                               "x); with the direct term the surface is " + ratio_text(quantile(total, 0.5)) +
                               "x as bright as it should be (median, up to " + ratio_text(quantile(total, 1.0)) + "x).\n";
                if (w == kOutside && model == 0)
                    verdict += "- " + who + ", outside the beam, falloff: 0, while the glow the beam scatters onto the "
                               "surface (its only light there) is " + ratio_text(quantile(glow, 0.5)) +
                               " of the point light's term (median; up to " + ratio_text(quantile(glow, 1.0)) + ").\n";
                if (w == kOutside && model == 1)
                    verdict += "- " + who + ", outside the beam, thin beam: " + ratio_text(quantile(ratio, 0.5)) +
                               "x the glow (median; " + ratio_text(quantile(ratio, 0.0)) + "x to " +
                               ratio_text(quantile(ratio, 1.0)) + "x).\n";
            }
        }
    }
    md += "\n**Where it fails.** Terms within 10 % of the exact scattered term, and with the direct term added:";
    for (int model = 0; model < 2; ++model) {
        size_t within = 0, within_total = 0;
        for (const Sample &s : samples) {
            within += std::fabs(s.ratio(model) - 1.0) <= 0.1;
            within_total += std::fabs(s.total_ratio(model) - 1.0) <= 0.1;
        }
        md += std::string(model == 0 ? " " : "; ") + model_name(model) + " " + std::to_string(within) + " and " +
              std::to_string(within_total) + " of " + std::to_string(samples.size());
    }
    md += ".\n\n" + verdict +
          "\nThe falloff factor holds only for beams nearly as wide as a point light; the thin-beam model while "
          "sigma_t D theta_o is small (docs/SPOT.md gives both regimes and their measured errors). Ratios far from 1 "
          "where the exact term is tiny matter little: the last column puts each error on the scale of the point "
          "light's term.\n";
    return md;
}

} // namespace scatterlut
