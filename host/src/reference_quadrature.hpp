// scatterlut generator — reference values by a rule independent of the kernels: Boost.Math
// adaptive 61-point Gauss–Kronrod quadrature (long double) of the physical integrals, split
// at break points placed by the integrands' scales. `validate` re-measures table nodes with
// these (IntegrationReference::IndependentGaussKronrod); the kernels' panel rules
// (kernels/slut_*.h) are not used.
#pragma once

namespace scatterlut {

// G̃(u, w) = (1/w) ∫_0^∞ e^{−u y} / (1 + (τ + y)²) dy, τ = cot w: the airlight's scaled tail
// (Sun et al. 2005, F(u, v) with w = π/2 − v), u ≥ 0, w ∈ (0, π/2]. Relative accuracy ~1e-15.
double reference_scaled_tail(double u, double w);

// The near-light E = N/H of Gath 2008 §4.2 (docs/PHYSICS.md §1.2): with ĥ² = t² + T² + 2tTg,
//   N = ∫_0^S exp(−t − ĥ(t)·t/(t + T r)) / ĥ² dt,   H = ∫_0^S ĥ^{−2} dt,
// T > 0, g ∈ [−1, 1], r ≥ 0 (or +∞), S > 0 (or +∞). Relative accuracy ~1e-14.
// phase_g ≠ 0: E_g, the Henyey–Greenstein phase ψ = 4π p_{phase_g}(θ) under N's integral, cos θ =
// −(t + T g)/ĥ (docs/PHYSICS.md §1.4), computed here from its half angles in long double.
double reference_near_light_E(double T, double g, double r, double S, double phase_g = 0.0);

} // namespace scatterlut

namespace scatterlut {

// G̃_g(u, w) = (1/w) ∫_0^∞ e^{−u y} k_g(τ + y) dy, τ = cot w, with the Henyey–Greenstein
// integrand k_g(t) = (1 − g²)√(1 + t²)/((1 − g)² + (1 + g)² t²)^{3/2} (kernels/slut_airlight_hg.h),
// break points also at the forward peak's scale (1 − g)/(1 + g). g = 0: reference_scaled_tail.
double reference_scaled_tail_hg(double u, double w, double g);

} // namespace scatterlut

namespace scatterlut {

// G_n(T, θ) of Sun et al. 2005's surface terms (docs/PHYSICS.md §1.5; n = 1 the diffuse G0, n > 1
// the Phong lobe of exponent n) by Boost.Math adaptive Gauss–Kronrod on the physical integral,
// sharing no rule with the kernels:
//   G_n = ∫_0^π 2 e^{−T} w2 G̃(T sin γ, w2) · K_n(θ, γ) dγ,   w2 = π/2 − γ/2,
//   K_n = 2 ∫_0^π max(cos θ cos γ + sin θ sin γ cos φ, 0)^n dφ,
// G̃ by reference_scaled_tail (the airlight along the infinite ray from the surface point at
// angle γ from the light) and K_n by quadrature in the azimuth φ (not the kernels' recurrence),
// with break points of its own. Relative accuracy ~1e-11 (Boost.Math exp_sinh along each ray, Gauss–Kronrod 31 over γ and φ).
double reference_surface_G(int n, double T, double theta);

} // namespace scatterlut
