// scatterlut generator — random physical queries over a scene's domain: the geometries a
// renderer of that scene asks the runtime for. The report measures every runtime method
// (exact quadrature, table, closed forms) on them, so its errors are errors on radiance in
// the scene, not on a table's internal quantity.
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include "scatterlut/airlight.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/spot.hpp"
#include "scatterlut/surface.hpp"
#include "scene.hpp"

namespace scatterlut {

// Airlight: for every medium the viewer is inside and every point light lighting it, in
// equal shares: D log-uniform over the light's distance range (uniform if it starts at 0),
// view directions uniform over the sphere (cos γ uniform in [−1, 1]), and the view ray's
// length s infinite for a quarter of the queries, else log-uniform in [10⁻³ D, 10 D].
std::vector<AirlightQuery> sample_airlight_queries(const Scene &scene, size_t count, uint64_t seed);

// Near light seen from outside: for every medium seen from outside and every point light
// lighting it, in equal shares, thick (length +inf) where the medium is thick and slabs
// where it lists a thickness. Surface normal +z; the eye direction uniform in solid angle
// within view.max_view_angle_deg of the normal, the light direction within
// view.max_light_angle_deg at a uniform azimuth; the light distance l log-uniform over its
// range; a slab of thickness d (uniform over the range) is crossed along s = d/μ_e.
// `finite`: slabs only (true) or thick media only (false).
std::vector<NearLightQuery> sample_near_light_queries(const Scene &scene, bool finite, size_t count, uint64_t seed);

// Lit surfaces of Phong exponent n (1: diffuse): for every medium whose surfaces need n and
// every point light lighting it, in equal shares, each colour channel in turn: D log-uniform
// over the surfaces' light_distance_m, θ uniform in [0, π] (θ_s for n = 1, θ_r for n > 1).
std::vector<SurfaceQuery> sample_surface_queries(const Scene &scene, int exponent, size_t count, uint64_t seed);

// Spot lights (docs/SPOT.md) seen three ways: for every medium the viewer is inside and every
// spot lighting it, in equal shares, the viewer at D (log-uniform over the light's distance
// range) from the light,
//   inside  within the outer cone (uniform in solid angle), looking anywhere (uniform sphere);
//   beside  outside it, looking at a point of the beam (on the axis at 0.1–3 D, moved off it
//           within the cone's radius there);
//   along   on the axis line, in front of the light or behind it, looking along ±axis within
//           the outer angle (at most 60°);
// s as for sample_airlight_queries. Lights of other types are left out; a spot with no outer
// edge (θ_o = π) has no "beside": those draws look from inside.
enum class SpotView { inside, beside, along };
const char *spot_view_name(SpotView view);
std::vector<SpotQuery> sample_spot_queries(const Scene &scene, SpotView view, size_t count, uint64_t seed);

// One sentence for reports: what the samplers above draw.
std::string describe_airlight_queries();
std::string describe_near_light_queries(bool finite);
std::string describe_spot_queries();

} // namespace scatterlut
