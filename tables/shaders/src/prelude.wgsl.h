// ------------------------------------------------------------ WGSL prelude (translator input)
// Not WGSL itself: the C-preprocessor glue through which tables/shaders/wgsl/slut_wgsl.py reads
// a snippet (the GLSL subset) and writes WGSL. The macros map the snippets' texture access to
// placeholders the translator knows; the rest of the snippet is the GLSL branch's.
//   texture parameter  texture_2d<f32> / texture_3d<f32>; in the fast tier (SLUT_TIER_FAST: the
//                      hardware-filtered fetches) followed by its sampler, named <texture>_sampler
//   texel fetch        textureLoad(t, vec2<i32>(i, j), 0).r / vec3<i32>(i, j, k)
//   filtered fetch     textureSampleLevel(t, t_sampler, vec2<f32>(x, y), 0.0).r (level 0)
//   texture size       vec2<f32>(textureDimensions(t, 0))
// +inf comes from a private variable's bits (bitcast<f32>): a constant +inf is a WGSL error.

#ifdef SLUT_TIER_FAST
#define SLUT_TEX2D_PARAM(t) slut_wgsl_texture_2d t, slut_wgsl_sampler t##_sampler
#define SLUT_TEX3D_PARAM(t) slut_wgsl_texture_3d t, slut_wgsl_sampler t##_sampler
#define SLUT_TEX_ARG(t) t, t##_sampler
#else
#define SLUT_TEX2D_PARAM(t) slut_wgsl_texture_2d t
#define SLUT_TEX3D_PARAM(t) slut_wgsl_texture_3d t
#define SLUT_TEX_ARG(t) t
#endif
#define SLUT_TEXEL2D(t, i, j) slut_wgsl_texel2d(t, i, j)
#define SLUT_TEXEL3D(t, i, j, k) slut_wgsl_texel3d(t, i, j, k)
#define SLUT_FILTER2D(t, x, y) slut_wgsl_filter2d(t, t##_sampler, x, y)
#define SLUT_FILTER3D(t, x, y, z) slut_wgsl_filter3d(t, t##_sampler, x, y, z)
#define SLUT_TEXTURE_SIZE2D(t) slut_wgsl_texture_size2d(t)
#define SLUT_FLOAT3 vec3
// kernels/slut_compat.h's SLUT_SELECT: the ternary, which the translator writes as select().
#define SLUT_SELECT(c, a, b) ((c) ? (a) : (b))
// Constant arrays of kernels/ (SLUT_CONST_ARRAY* there): WGSL const arrays.
#define SLUT_CONST_ARRAY3(name, a0, a1, a2) const float name[3] = {a0, a1, a2}
#define SLUT_CONST_ARRAY4(name, a0, a1, a2, a3) const float name[4] = {a0, a1, a2, a3}
#define SLUT_CONST_ARRAY8(name, a0, a1, a2, a3, a4, a5, a6, a7) const float name[8] = {a0, a1, a2, a3, a4, a5, a6, a7}

uint slut_wgsl_inf_bits = 0x7F800000u;
float slut_inf() { return slut_wgsl_bitcast_f32(slut_wgsl_inf_bits); }
