/* scatterlut — the near-light integral (light outside a medium, viewer outside), written once.
 *
 * This header includes the parts, one job each (what includes this one gets them all):
 *   slut_nearlight_closed.h      the closed-form weight H(T, g, S) and small helpers
 *   slut_nearlight_approx.h      the closed forms without a table (distant light, thin medium)
 *   slut_nearlight_slab.h        the 4-D table's slab coordinate of S, value base, domain test
 *   slut_nearlight_refraction.h  Snell and Fresnel at the surface, slut_vec3
 *   slut_nearlight_frontend.h    (T, g, r, S) from a geometry, kind codes, radiance assembly
 *   slut_nearlight_lanes.h       the sweep's lane vectors (double16 on the device)
 *   slut_nearlight_march.h       E and N by quadrature (panel rule, sweep), exact radiance
 * All are compiled as OpenCL C by the near-light table kernels and as C++ by the host (exact
 * evaluation, eval, validation), the tests and the runtime library; the first five also,
 * whole, as GLSL/HLSL in float by the GPU snippets (cmake/assemble_shaders.cmake). The
 * physics and its conventions: docs/PHYSICS.md §1.2–§1.3.
 *
 * Geometry (docs/PHYSICS.md §1.2). A plane with outward unit normal n bounds the medium (below it).
 * The view ray enters at O and runs a length s inside; ω = unit vector from O towards the
 * viewer (so the ray inside is P(x) = O − x ω), μ_e = ω·n > 0. The light sits at
 * O + l ω_l, μ_l = ω_l·n, g = ω·ω_l. The light-to-point distance is h(x)² = x² + l² + 2 x l g
 * and the part of the light path inside the medium is k(x) = h(x)·x μ_e/(x μ_e + l μ_l)
 * (similar triangles: the depth of P(x) is x μ_e, the height of the light l μ_l).
 *
 *   L_near = σ_s/(4π) · I0 · ∫_0^s e^{−σ_t (x + k(x))} / h(x)² dx = σ_s/(4π) · I0 · σ_t · N(T, g, r, S)
 *   N(T, g, r, S) = ∫_0^S exp(−t − ĥ(t)·t/(t + T r)) / ĥ(t)² dt,   ĥ(t)² = t² + T² + 2 t T g
 *   T = σ_t l,  S = σ_t s (may be +∞),  r = μ_l/μ_e ≥ 0,  t = σ_t x.
 *   H(T, g, S) = ∫_0^S ĥ^{−2} dt (closed form),  E = N/H ∈ (0, 1] (ĥ^{−2}-weighted mean attenuation).
 *
 * Throughout, w = T√(1 − g²) is the distance from the light to the ray's line and
 * d(t) = t + T g the signed distance along the ray past the foot of that perpendicular, so
 * ĥ² = d² + w². The peak of 1/ĥ² sits at t* = −T g (inside the ray when g < 0), with
 * width w; 1/ĥ² has its poles at t* ± i w, at distance exactly ĥ(t) from a real t.
 */
#ifndef SLUT_NEARLIGHT_H
#define SLUT_NEARLIGHT_H

#include "slut_nearlight_closed.h"
#include "slut_nearlight_approx.h"
#include "slut_nearlight_slab.h"
#include "slut_nearlight_refraction.h"
#include "slut_nearlight_frontend.h"
#include "slut_nearlight_lanes.h"
#include "slut_nearlight_march.h"

#endif /* SLUT_NEARLIGHT_H */
