// scatterlut generator — a scene file (TOML, docs/SCENES.md): the media, the lights, the
// view ranges that matter, the output and the accepted error. Parsing checks every key
// and value; a bad scene throws SceneError naming file, line, column and key.
#pragma once

#include <algorithm>
#include <array>
#include <stdexcept>
#include <string>
#include <vector>

namespace scatterlut {

// "FILE:LINE:COL: key 'a.b.c': expected …". Derives from std::invalid_argument: bad
// input (exit 2 in the command line).
class SceneError : public std::invalid_argument {
public:
    using std::invalid_argument::invalid_argument;
};

// What a scene may ask for: the ranges a table can serve (checked when the scene is read,
// each refusal naming file:line:column and the key; docs/SCENES.md).
inline constexpr double kSceneMinLength_m = 1e-6, kSceneMaxLength_m = 1e6; // distances, thicknesses
inline constexpr double kSceneMaxSigma_per_m = 1e6;  // sigma_s, sigma_a
inline constexpr double kSceneMaxIntensity = 1e30;   // W/sr, W/m^2
// |phase_g| of a medium's Henyey–Greenstein phase: beyond 0.99 the forward peak (width
// (1 − g)/(1 + g) in tan ξ) is narrower than 0.005 and the tables' axes would need
// thousands of nodes to resolve it.
inline constexpr double kSceneMaxPhaseG = 0.99;
inline constexpr double kSceneMinRelativeError = 1e-9;
inline constexpr double kSceneMinTableMiB = 0.01;
// sigma_t times a light's largest distance or a slab's largest thickness: beyond it the
// light is attenuated by e^{-1e4}, far below double precision's smallest number.
inline constexpr double kSceneMaxOpticalDepth = 1e4;
// The largest Phong exponent a scene's surfaces may name: the lobe of exponent n has the
// angular width 1/sqrt(n) (0.03 rad at 1000), which a table's theta axis resolves with a few
// hundred nodes; narrower lobes would need thousands (the runtime's exact quadrature takes
// any n up to kSurfaceMaxExponent, scatterlut/surface.hpp).
inline constexpr int kSceneMaxPhongExponent = 1000;

struct Range {
    double min = 0, max = 0;
};

// Lit surfaces inside a medium the viewer is in (Sun et al. 2005's surface terms,
// docs/PHYSICS.md §1.5): a street, walls. Each exponent gets its own table of G_n(T, θ):
// exponent 1 the diffuse G0 (Lambertian surfaces), n > 1 a Phong lobe of exponent n.
struct SceneSurfaces {
    bool diffuse = false;               // Lambertian surfaces (the diffuse table, exponent 1)
    std::vector<int> phong_exponents;   // distinct, ascending, each in [1, kSceneMaxPhongExponent]
    Range light_distance_m;             // distance from a lit surface point to a point light, m
    int line = 0;                       // where the surfaces table starts (for messages)
    // The exponents whose tables these surfaces need, ascending (1 for diffuse surfaces).
    std::vector<int> exponents() const {
        std::vector<int> e = phong_exponents;
        if (diffuse && (e.empty() || e.front() != 1)) e.insert(e.begin(), 1);
        return e;
    }
};

struct SceneMedium {
    std::string name;
    // Scattering and absorption coefficients, 1/m. A grey medium (one number in the file):
    // the value, and every channel of the *_rgb arrays holds it. A coloured one ([r, g, b]):
    // the largest channel here (what a table's domain must reach), the channels below.
    double sigma_s_per_m = 0; // scattering coefficient, 1/m
    double sigma_a_per_m = 0; // absorption coefficient, 1/m
    double phase_g = 0.0;     // Henyey–Greenstein asymmetry, |g| <= kSceneMaxPhaseG; 0 isotropic, > 0 forward
    std::array<double, 3> sigma_s_rgb_per_m{}; // per channel (r, g, b), 1/m
    std::array<double, 3> sigma_a_rgb_per_m{};
    bool coloured = false; // sigma_s or sigma_a given as [r, g, b] with channels that differ
    bool viewer_inside = false; // true: a volume the viewer is in (fog); false: an object seen from outside
    // Media seen from outside: a thick object (the view ray does not leave it) and/or slabs
    // whose path length inside along the view ray lies in `thickness_m`.
    bool thick = false;
    bool has_thickness = false;
    Range thickness_m;
    double relative_error = 0; // accepted relative error on its radiance (default: the scene's)
    // Lit surfaces inside it (viewer_inside media only); has_surfaces false: none (the key absent).
    bool has_surfaces = false;
    SceneSurfaces surfaces;
    int line = 0; // where the [[medium]] table starts (for messages)
    // Extinction, 1/m: the largest channel's (a grey medium's σ_s + σ_a, bit for bit), the
    // smallest channel's, and channel c's.
    double sigma_t_per_m() const {
        if (!coloured) return sigma_s_per_m + sigma_a_per_m;
        return std::max({sigma_t_channel_per_m(0), sigma_t_channel_per_m(1), sigma_t_channel_per_m(2)});
    }
    double sigma_t_min_per_m() const {
        if (!coloured) return sigma_s_per_m + sigma_a_per_m;
        return std::min({sigma_t_channel_per_m(0), sigma_t_channel_per_m(1), sigma_t_channel_per_m(2)});
    }
    double sigma_t_channel_per_m(int c) const { return sigma_s_rgb_per_m[c] + sigma_a_rgb_per_m[c]; }
    bool isotropic() const { return phase_g == 0.0; }
};

enum class LightType { Point, Directional };

struct SceneLight {
    std::string name;
    LightType type = LightType::Point;
    double intensity_W_per_sr = 0;  // point lights
    Range distance_m;               // point lights: viewer–light (viewer inside) or surface point–light (outside)
    double irradiance_W_per_m2 = 0; // directional lights (informative; radiance scales with it)
    std::vector<std::string> media; // the media it lights; empty in the file = all media
    // Spot lights (type = "spot"): a point light (type Point: the planner serves it with the
    // airlight tables exactly as a point light, the same demand) with glTF's cone
    // (docs/SPOT.md): the axis, light → lit points, and the half-angles in degrees.
    bool spot = false;
    std::array<double, 3> spot_direction{0, 0, -1};
    double outer_angle_deg = 180, inner_angle_deg = 180;
    int line = 0;
};

struct SceneView {
    // Media seen from outside: the largest angle between the view ray (towards the viewer)
    // and the outward surface normal, and between the direction to the light and the normal.
    double max_view_angle_deg = 80.0;
    double max_light_angle_deg = 90.0;
};

struct SceneOutput {
    std::string directory = "out";
    std::string format = "both"; // bin | exr | both
    std::string storage = "f32"; // f16 | f32 | f64
};

struct Scene {
    std::string source; // the file name (or "<default scene>")
    std::string text;   // the TOML text, recorded in every table's provenance
    std::string name;
    double relative_error = 0.01; // accepted relative error on radiance
    double max_table_MiB = 64.0;  // bound on each table's size
    SceneView view;
    SceneOutput output;
    std::vector<SceneMedium> media;
    std::vector<SceneLight> lights;

    // Whether `light` lights `medium` (a light without a media list lights all media).
    static bool lights_medium(const SceneLight &light, const SceneMedium &medium);
};

// Parses and checks `text`; `source` names it in messages. Throws SceneError.
Scene parse_scene(const std::string &text, const std::string &source);
// Reads the file and parses it (an unreadable file is a SceneError too).
Scene load_scene_file(const std::string &path);
// The scene compiled into the binary (host/scenes/default.toml): every table kind.
Scene default_scene();

} // namespace scatterlut
