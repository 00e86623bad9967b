// The closed form engines use for the airlight of a point light (Macklin 2010) times
// e^{-sigma_t D}: slut_airlight_no_extinction_attenuated (kernels/slut_airlight.h) in float,
// with the GPU's built-in atan. The baseline of the GPU per-pixel benches, read by both:
// bench/bench_gpu_pixel.cpp (GLSL 4.30, Mesa llvmpipe) and examples/web/bench_airlight.mjs
// (GLSL ES 3.00, Chromium's SwiftShader); GLSL common to both, no #version, no precision.
//   sigma_s/(4pi) I0 (atan((s + b)/h) - atan(b/h))/h e^{-sigma_t D},  b = -D cos gamma,
//   h = D sin gamma (gamma: between the view direction and the direction to the light),
// the angle as (s/den) atan(s h/den)/(s h/den), den = D (D - s cos gamma), while den > 0.
// Units: sigma in 1/m, I0 in W/sr, lengths in m; radiance in W/(m^2 sr).
float closed_form_attenuated(float ss, float sa, float i0, float dist, float sg, float cg, float len) {
    if (!(ss > 0.0) || !(i0 > 0.0) || !(len > 0.0)) return 0.0;
    float h = dist * max(sg, 0.0);
    float den = dist * (dist - len * cg);
    float angle_over_h;
    if (den > 0.0) {
        float x = len * h / den;
        angle_over_h = ((x == 0.0) ? 1.0 : atan(x) / x) * (len / den);
    } else {
        if (!(h > 0.0)) return uintBitsToFloat(0x7F800000u);
        angle_over_h = (den == 0.0) ? 1.5707963 / h : (3.14159265 - atan(len * h / -den)) / h;
    }
    return ss * 0.0795774715 * i0 * angle_over_h * exp(-(ss + sa) * dist);
}
