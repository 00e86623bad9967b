// Sun et al. 2005's two-fetch airlight on a plain F table, as NVIDIA's SDK 10 Rain sample
// samples it. The baseline of the GPU per-pixel benches, read by both
// bench/bench_gpu_pixel.cpp (GLSL 4.30, Mesa llvmpipe) and examples/web/bench_airlight.mjs
// (GLSL ES 3.00, Chromium's SwiftShader); GLSL common to both, no #version, no precision.
//   L = A0 [F(A1, pi/4 + atan((s - D cos g)/(D sin g))/2) - F(A1, g/2)],
//   A0 = sigma_s I0 e^{-sigma_t D cos g}/(2 pi D sin g),  A1 = sigma_t D sin g,
// g the angle between the view direction and the direction to the light; F(u, v) =
// int_0^v e^{-u tan xi} dxi from a plain table: u in [0, f_u_max], v in [0, pi/2], linear
// axes, bilinear (the texture filters linearly), clamped; texture unit of f_table set by
// the caller. Units: sigma in 1/m, I0 in W/sr, lengths in m; radiance in W/(m^2 sr).
uniform sampler2D f_table;
uniform float f_u_max;
float sun_F(float u, float v) {
    vec2 unit = clamp(vec2(u / f_u_max, v / 1.5707963), 0.0, 1.0);
    vec2 size = vec2(textureSize(f_table, 0));
    return textureLod(f_table, (unit * (size - 1.0) + 0.5) / size, 0.0).r;
}
float sun2005(float ss, float sa, float i0, float dist, float sg, float cg, float len) {
    float st = ss + sa;
    float a1 = st * dist * sg;
    float a0 = ss * i0 * exp(-st * dist * cg) / (6.2831853 * dist * sg);
    float v_far = 0.7853982 + 0.5 * atan((len - dist * cg) / (dist * sg));
    float v_near = 0.5 * atan(sg, cg);
    return a0 * (sun_F(a1, v_far) - sun_F(a1, v_near));
}
