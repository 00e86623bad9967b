// ------------------------------------------------------------ HLSL prelude (language glue)
// Requirements: Shader Model 4.0+ (DXC, FXC or glslang), full 32-bit float (no
// min16float). #include it before code that calls it.
// A texture argument TEX below is two arguments: a Texture2D<float> (airlight) or
// Texture3D<float> (near light) and its SamplerState (used only by the hardware-filter
// options, but always passed).

#define SLUT_TEX2D_PARAM(t) Texture2D<float> t, SamplerState t##_sampler
#define SLUT_TEX3D_PARAM(t) Texture3D<float> t, SamplerState t##_sampler
#define SLUT_TEX_ARG(t) t, t##_sampler
#define SLUT_TEXEL2D(t, i, j) t.Load(int3(i, j, 0))
#define SLUT_TEXEL3D(t, i, j, k) t.Load(int4(i, j, k, 0))
#define SLUT_FILTER2D(t, x, y) t.SampleLevel(t##_sampler, float2(x, y), 0.0)
#define SLUT_FILTER3D(t, x, y, z) t.SampleLevel(t##_sampler, float3(x, y, z), 0.0)
#define SLUT_TEXTURE_SIZE2D(t) slut_texture_size2d(t) // width, height in texels
#define SLUT_FLOAT3 float3
// Constant arrays of kernels/ (SLUT_CONST_ARRAY* there).
#define SLUT_CONST_ARRAY3(name, a0, a1, a2) static const float name[3] = {a0, a1, a2}
#define SLUT_CONST_ARRAY4(name, a0, a1, a2, a3) static const float name[4] = {a0, a1, a2, a3}
#define SLUT_CONST_ARRAY8(name, a0, a1, a2, a3, a4, a5, a6, a7) static const float name[8] = {a0, a1, a2, a3, a4, a5, a6, a7}

float slut_inf() { return asfloat(0x7F800000u); }
float2 slut_texture_size2d(Texture2D<float> t) {
    uint width, height;
    t.GetDimensions(width, height);
    return float2(float(width), float(height));
}

// kernels/slut_compat.h's SLUT_SELECT(c, a, b): c ? a : b with both operands evaluated, a select
// (ANGLE writes `?:` with computed operands as a branch, which SwiftShader compiles slowly).
float slut_select(bool c, float a, float b) { return c ? a : b; }
int slut_select(bool c, int a, int b) { return c ? a : b; }
bool slut_select(bool c, bool a, bool b) { return c ? a : b; }
