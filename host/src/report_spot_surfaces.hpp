// scatterlut generator — `report`'s section on surfaces lit by spot lights (docs/SPOT.md,
// "Surfaces lit by a spot"): on the scene's own geometries, the error of the two approximations
// of scatterlut/spot_surface.hpp for the scattered terms E_ss and S_n (the point light's times
// glTF KHR_lights_punctual's falloff f(θ_P), and the thin-beam model) against the spot's exact
// terms, by spot, term and where the surface point lies (inside the inner cone, in the falloff
// band, outside the beam); where they fail. Written as Markdown (returned) and a CSV.
#pragma once

#include <string>

#include "scene.hpp"

namespace scatterlut {

// Whether some spot light lights a medium with surfaces (viewer inside, σ_s > 0).
bool scene_has_spot_surfaces(const Scene &scene);

// `points` random surface points over those (medium, spot) pairs in turn (each colour channel
// in turn; D log-uniform over the surfaces' light_distance_m; the spot angle of P uniform in
// [0, min(180°, 2 θ_o + 10°)], so inside, band and outside all occur; the normal and the
// mirror direction uniform on the sphere; every exponent of the medium's surfaces). Writes
// <out_dir>/spot_surfaces.csv and returns the Markdown section. Deterministic (fixed seed).
std::string spot_surface_section(const Scene &scene, int points, const std::string &out_dir);

} // namespace scatterlut
