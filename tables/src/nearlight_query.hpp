// The near-light query's front-end (internal; not installed): (T, g, r, S) of a query and the
// exit's Fresnel factor by the shared math (kernels/slut_nearlight_frontend.h,
// slut_nearlight_refraction.h), the functions the near-light snippet calls too. Defined in
// nearlight.cpp; the isotropic and the Henyey–Greenstein samplers and exact forms all take
// their geometry from here.
#pragma once

#include "scatterlut/nearlight.hpp"

extern "C" {
#include "slut_nearlight.h"
}

namespace scatterlut::detail {

// slut_nl_params_seen of the query (the eye ray refracted where eta ≠ 1); throws
// std::invalid_argument if the viewer is below the surface. The query's other fields are
// not checked (check_near_light_query).
slut_nl_params near_light_params_unchecked(const NearLightQuery &q);

// The Fresnel factor of the exit (slut_exit_transmittance): 1 without refraction or without `fresnel`.
double near_light_exit_transmittance(const NearLightQuery &q);

} // namespace scatterlut::detail
