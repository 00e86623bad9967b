// The GPU snippets' spot rule in double (scatterlut/spot.hpp,
// detail::spot_airlight_radiance_gpu_rule; kernels/slut_spot_rule.h, docs/SPOT.md "On the GPU"):
// the same shared functions the snippets compile in float, with a point-light radiance of the
// caller's in place of the tier's. The shader tests' reference of the same rule on the same
// inputs, and (with the exact point-light airlight) the measure of the rule's own error.
#include "scatterlut/spot.hpp"

#include "spot_band.hpp"

#include <cmath>

extern "C" {
#include "slut_spot_rule.h"
}

namespace scatterlut::detail {

double spot_airlight_radiance_gpu_rule(const PointLightRadiance &point_radiance, const SpotQuery &q, double phase_g) {
    check_phase_g(phase_g);
    check_spot_query(q);
    using spot_detail::vec;
    const slut_spot_ray ray = slut_spot_ray_of(vec(q.viewer_m), vec(q.view_dir), vec(q.light.position_m),
                                               vec(q.light.direction), q.light.outer_angle_rad,
                                               q.light.inner_angle_rad, q.length_m);
    // The interval that holds the light, as the snippets pass it to the tier.
    const slut_spot_interval iv = slut_spot_interval_of(ray);
    AirlightQuery a;
    a.sigma_s_per_m = q.sigma_s_per_m;
    a.sigma_a_per_m = q.sigma_a_per_m;
    a.intensity_W_per_sr = q.light.intensity_W_per_sr;
    a.distance_m = iv.distance;
    a.gamma_rad = std::atan2(iv.sin_gamma, iv.cos_gamma);
    a.length_m = iv.sub_length >= SLUT_INFINITE_ABOVE ? HUGE_VAL : iv.sub_length;
    const double sum = slut_spot_interval_radiance(ray, iv, point_radiance(a), q.sigma_s_per_m,
                                                   q.sigma_s_per_m + q.sigma_a_per_m, q.light.intensity_W_per_sr, phase_g);
    return sum;
}

} // namespace scatterlut::detail
