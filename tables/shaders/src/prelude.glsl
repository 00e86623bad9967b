// ------------------------------------------------------------ GLSL prelude (language glue)
// Requirements: GLSL 3.30+ / GLSL ES 3.00+ (texelFetch, uintBitsToFloat, switch), highp
// float, or Vulkan GLSL. Include it after your #version line and before code that calls
// it (paste it, or #include with GL_GOOGLE_include_directive).
// A texture argument TEX below is one sampler2D (airlight) or sampler3D (near light).

#define SLUT_TEX2D_PARAM(t) sampler2D t
#define SLUT_TEX3D_PARAM(t) sampler3D t
#define SLUT_TEX_ARG(t) t
#define SLUT_TEXEL2D(t, i, j) texelFetch(t, ivec2(i, j), 0).r
#define SLUT_TEXEL3D(t, i, j, k) texelFetch(t, ivec3(i, j, k), 0).r
#define SLUT_FILTER2D(t, x, y) textureLod(t, vec2(x, y), 0.0).r
#define SLUT_FILTER3D(t, x, y, z) textureLod(t, vec3(x, y, z), 0.0).r
#define SLUT_TEXTURE_SIZE2D(t) vec2(textureSize(t, 0)) // width, height in texels
#define SLUT_FLOAT3 vec3
// Constant arrays of kernels/ (SLUT_CONST_ARRAY* there; one line each: GLSL before 4.20 has no line
// continuation).
#define SLUT_CONST_ARRAY3(name, a0, a1, a2) const float name[3] = float[3](a0, a1, a2)
#define SLUT_CONST_ARRAY4(name, a0, a1, a2, a3) const float name[4] = float[4](a0, a1, a2, a3)
#define SLUT_CONST_ARRAY8(name, a0, a1, a2, a3, a4, a5, a6, a7) const float name[8] = float[8](a0, a1, a2, a3, a4, a5, a6, a7)

float slut_inf() { return uintBitsToFloat(0x7F800000u); }

// kernels/slut_compat.h's SLUT_SELECT(c, a, b): c ? a : b with both operands evaluated, a select
// (ANGLE writes `?:` with computed operands as a branch, which SwiftShader compiles slowly).
float slut_select(bool c, float a, float b) { return c ? a : b; }
int slut_select(bool c, int a, int b) { return c ? a : b; }
bool slut_select(bool c, bool a, bool b) { return c ? a : b; }
