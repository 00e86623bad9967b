// scatterlut runtime — airlight of a spot light: the point light of airlight.hpp restricted to a
// cone with glTF KHR_lights_punctual's falloff (docs/PHYSICS.md §1.6), seen through a
// homogeneous medium that contains viewer and light.
//
// Sign conventions: θ (the spot angle) is the angle between the spot's axis and the direction
// FROM THE LIGHT TO THE POINT; f(θ) = clamp((cos θ − cos θ_o)/(cos θ_i − cos θ_o), 0, 1)²
// (kernels/slut_spot.h). The scattering angle of the Henyey–Greenstein phase is the point
// light's (anisotropic.hpp, PHYSICS.md §1.4): between the light's propagation direction at
// the point (light → point) and the direction from the point to the viewer; g > 0 forward.
//
//   L = σ_s I0 ∫_0^s p_g(θ_scatter(x)) f(θ(x)) e^{−σ_t (x + d(x))} / d(x)² dx
//
// with x the distance along the view ray and d(x) the distance from the light to that point.
#pragma once

#include <array>
#include <cstddef>
#include <functional>
#include <vector>

#include "scatterlut/airlight.hpp"
#include "scatterlut/airlight_hg.hpp"
#include "scatterlut/anisotropic.hpp"

namespace scatterlut {

using Vec3 = std::array<double, 3>;

// A spot light: position, axis, the two cone half-angles and the on-axis intensity.
struct SpotLight {
    Vec3 position_m{};             // the apex
    Vec3 direction{0, 0, -1};      // the beam's axis (light → lit points); need not be unit, ≠ 0
    double outer_angle_rad = 0;    // θ_o ∈ [0, π]: f = 0 beyond (π: no outer edge)
    double inner_angle_rad = 0;    // θ_i ∈ [0, θ_o]: f = 1 within; θ_i = θ_o a hard cone
    double intensity_W_per_sr = 0; // I0 on the axis (radiant intensity I0·f(θ) off it)
};

// glTF's falloff f ∈ [0, 1] of `light` towards the point `point_m` (θ between the axis and the
// direction from the light to the point): what masks the light's direct illumination there
// and, for a surface or a slab lit by a spot, the factor a renderer applies to the point
// light's terms. 1 at the apex itself where the cone is the whole sphere, else 0 there.
double spot_falloff(const SpotLight &light, const Vec3 &point_m);

// One spot-airlight query: the medium, the view ray and the light.
struct SpotQuery {
    double sigma_s_per_m = 0;   // scattering coefficient σ_s, 1/m
    double sigma_a_per_m = 0;   // absorption coefficient σ_a, 1/m
    Vec3 viewer_m{};            // the ray's origin
    Vec3 view_dir{0, 0, 1};     // the ray's direction (need not be unit, ≠ 0)
    double length_m = 0;        // s ≥ 0, +inf allowed
    SpotLight light;
};

// The query from positions and directions as plain arrays (as airlight_query_from_points): the
// viewer, the view direction, the light's position and the beam's axis (directions need not be
// unit, ≠ 0), the cone half-angles (rad), the ray's length (m, +inf allowed), the medium and I0
// on the axis. Checked (check_spot_query: std::invalid_argument naming the first bad field).
SpotQuery spot_query_from_points(const double viewer_m[3], const double view_dir[3], const double light_m[3],
                                 const double spot_dir[3], double outer_angle_rad, double inner_angle_rad,
                                 double length_m, double sigma_s_per_m, double sigma_a_per_m,
                                 double intensity_W_per_sr);

// Throws std::invalid_argument naming the first bad field: NaN or infinite coordinates, a zero
// view_dir or direction, angles outside [0, π] or inner > outer, negative σ, I0 or length.
void check_spot_query(const SpotQuery &q);

// The ray cut by the cone: where f = 1 (inside the inner cone: "hard"), where 0 < f < 1 (the
// falloff band) and where f = 0 (left out). Pieces in order along [0, s]; the ray is also cut
// at its closest approach to the light, so every band piece lies on one side of it.
enum class SpotPieceKind { hard, band };
struct SpotPiece {
    double t0_m, t1_m; // along the ray from the viewer; t1 may be +inf
    SpotPieceKind kind;
    double falloff;    // hard: f over the whole piece (1, or a constant where the ray's line meets the apex)
};
struct SpotRay {
    Vec3 origin{}, dir{};      // the viewer, the unit view direction
    Vec3 light{}, axis{};      // the apex, the unit axis
    double vers_outer = 0, vers_inner = 0; // 1 − cos θ_o, 1 − cos θ_i
    double closest_t_m = 0;    // t* = d·(L − o): the closest approach to the light (may be < 0)
    double miss_distance_m = 0; // h = |o + t* d − L|: the light's distance from the ray's line
    Vec3 unit_foot{};          // (o + t* d − L)/h (0 when h = 0)
    std::vector<SpotPiece> pieces;
    bool through_lit_light = false; // the ray meets the light where the beam leaves it: +inf
};
// q checked (check_spot_query). Rays through an unlit apex, and beams that the ray never
// enters, leave no pieces.
SpotRay spot_ray_pieces(const SpotQuery &q);

// f at the point at depth t_m (SpotRay's vectors; the point ≠ the light).
double spot_falloff_at(const SpotRay &ray, double t_m);

// The point-light query of the sub-segment [t0, t1] seen from x(t0) (airlight_query_from_points
// with the shifted viewer): its radiance times e^{−σ_t t0} is the segment's airlight.
AirlightQuery spot_sub_segment_query(const SpotQuery &q, const SpotRay &ray, double t0_m, double t1_m);

// Radiance in W/(m²·sr), exact (~1e-13 relative on the hard pieces, ~1e-12 on the falloff band):
// each hard piece the point light's exact airlight of the sub-segment (airlight_radiance_exact),
// each band piece adaptive Gauss–Kronrod in the angle at the point between the ray and the
// light. θ_i = θ_o = π is the point light (airlight_radiance_exact, bit for bit). +inf when the
// ray passes through the light where the beam leaves it lit; 0 when it never enters the beam.
// Never NaN, never negative.
double spot_airlight_radiance_exact(const SpotQuery &q, double phase_g = 0.0);
Rgb spot_airlight_radiance_exact_rgb(const SpotQuery &q, const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m,
                                     double phase_g = 0.0);

// From an airlight table (isotropic, or anisotropic of the table's own g): the hard pieces from
// the table's radiance of each sub-segment; each band piece by parts, f at one end times the
// table radiance of the piece plus an 8-point Gauss–Legendre rule (in the same angle) of the
// table's radiance of the rest of the piece times df (docs/PHYSICS.md §1.6; its measured error
// against the exact airlight is there). Same units and limits as the exact function.
double spot_airlight_radiance(const AirlightTable &table, const SpotQuery &q);
double spot_airlight_radiance(const AirlightHgTable &table, const SpotQuery &q);
Rgb spot_airlight_radiance_rgb(const AirlightTable &table, const SpotQuery &q, const Rgb &sigma_s_per_m,
                               const Rgb &sigma_a_per_m);
Rgb spot_airlight_radiance_rgb(const AirlightHgTable &table, const SpotQuery &q, const Rgb &sigma_s_per_m,
                               const Rgb &sigma_a_per_m);

// The same for `count` queries: out[i] is the scalar call's result for queries[i], bit for bit
// (the same function, query by query). Every query is checked before anything is written: a bad
// one throws std::invalid_argument naming its index and field, and `out` is left as it was.
// The RGB forms take one medium for the whole batch (per channel, as the scalar RGB calls).
void spot_airlight_radiance(const AirlightTable &table, const SpotQuery *queries, size_t count, double *out);
void spot_airlight_radiance(const AirlightHgTable &table, const SpotQuery *queries, size_t count, double *out);
void spot_airlight_radiance_rgb(const AirlightTable &table, const SpotQuery *queries, size_t count,
                                const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m, Rgb *out);
void spot_airlight_radiance_rgb(const AirlightHgTable &table, const SpotQuery *queries, size_t count,
                                const Rgb &sigma_s_per_m, const Rgb &sigma_a_per_m, Rgb *out);

namespace detail {
// The table path with any point-light radiance in place of a table's (the tests pass the exact
// airlight_radiance_exact to measure the band rule's own error).
using PointLightRadiance = std::function<double(const AirlightQuery &)>;
double spot_airlight_radiance_from(const PointLightRadiance &point_radiance, const SpotQuery &q);

// The GPU snippets' rule (kernels/slut_spot_rule.h; docs/SPOT.md "On the GPU") in double: the
// lit intervals, one point-light radiance each (point_radiance: the tier's, AirlightRationalTable
// or AirlightTable or AirlightHgTable, or the exact airlight to measure the rule itself), the
// falloff band by its 4-point rule with the phase of phase_g. The tests' reference for the
// snippets' spot entry points on the same inputs. q checked (check_spot_query).
double spot_airlight_radiance_gpu_rule(const PointLightRadiance &point_radiance, const SpotQuery &q,
                                       double phase_g = 0.0);
} // namespace detail

} // namespace scatterlut
