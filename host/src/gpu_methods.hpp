// scatterlut generator — what `report` draws on the GPU for one planned table: the generated
// GLSL snippet that samples it, in each of its tiers (docs/SHADERS.md, "Tiers"), and the
// per-pixel forms engines use instead (the GPU baselines), as pieces of a fragment shader
// over the table's own radiance queries (one query per pixel). Each kind writes its pieces
// (TableKind::gpu_methods); report_gpu.cpp puts them around the snippet's text, draws them
// through OpenGL and reads the float radiance back. Nothing here needs OpenGL: the kinds
// describe, the report draws.
#pragma once

#include <memory>
#include <string>
#include <utility>
#include <vector>

#include "scatterlut/airlight.hpp"
#include "scatterlut/nearlight.hpp"
#include "scatterlut/surface.hpp"
#include "scatterlut/table.hpp"

namespace scatterlut {

// A table as an R32F texture: 2-D (depth 0) or 3-D, texels in the texture's row order.
struct GpuTexture {
    int width = 0, height = 0, depth = 0;
    std::vector<float> texels;
};

// One way of computing the radiance per pixel.
struct GpuMethod {
    std::string name;                          // "fast", "accurate", "none" (the snippet's tiers) or a baseline's name
    std::string what;                          // one line for the report
    std::string tier;                          // "fast", "accurate", "none"; "" for a baseline (no snippet tier)
    std::string source;                        // the GLSL file it includes: a generated snippet or a baseline's file
    std::string before;                        // GLSL before the source: the tier's define, the table's sampler
    std::string after;                         // GLSL after it (the table's metadata)
    std::string call;                          // the radiance, a float expression of the pixel's inputs in0, in1, …
    std::shared_ptr<const GpuTexture> texture; // on texture unit 0; null: none
    std::vector<std::pair<std::string, float>> uniforms = {}; // float uniforms of the source
};

// A kind's methods for one table over its radiance queries.
struct GpuSnippetMethods {
    std::string snippet;       // the generated snippet, e.g. "scatterlut_airlight.glsl"; "": none
    int vec4s = 0;             // inputs per query, in vec4
    std::vector<float> inputs; // vec4s × 4 floats per query, in the queries' order
    std::string inputs_read;   // a float expression that reads every input (the inputs-only pass)
    std::vector<GpuMethod> methods;
    std::string baseline;           // the method the costs are given as ratios to ("" : the first)
    std::vector<std::string> notes; // for the report, e.g. queries a shader clamps
};

// The tier's define, e.g. "#define SLUT_TIER_FAST\n" ("" for "none").
std::string gpu_tier_define(const std::string &tier);
// A GLSL float literal of `v` (9 significant digits; ±inf as a bit pattern).
std::string glsl_float(double v);
// slut_axis_make(min, max, scale, warp, count) of one of the table's axes (common.slsl).
std::string glsl_axis(const Axis &axis);
// The table's values (channel 0) as a texture: 2 axes → 2-D (width axis 0), 3 axes → 3-D;
// 4 axes (the near-light E4 tables) → 3-D with the layers of axis 3 stacked along the height,
// texel (i0, i1 + n1·i3, i2), as the near-light snippet samples it. Null for other tables.
std::shared_ptr<const GpuTexture> gpu_table_texture(const Table &table);
// A snippet's method: `tier` ("fast", "accurate", "none") of `snippet`, sampling `texture` on
// unit 0 through a uniform `sampler` ("sampler2D" / "sampler3D") named slut_table.
GpuMethod gpu_tier_method(const std::string &tier, const std::string &what, const std::string &snippet,
                          const std::string &sampler, std::shared_ptr<const GpuTexture> texture,
                          const std::string &after, const std::string &call);

// The queries as pixel inputs (floats; an infinite length stays +inf), with `snippet`,
// vec4s, inputs and inputs_read filled; the arguments the snippets' radiance functions take
// after their table are kAirlightGpuArgs, … (GLSL, of in0, in1, …).
//   airlight   (sigma_s, sigma_a, I0, D), (sin gamma, cos gamma, s, 0)
//   near light (sigma_s, sigma_a, I0, s), (normal, eta), (eye_dir, fresnel), (light_rel, 0)
//   surface    (sigma_s, sigma_a, I0, D), (theta, 0, 0, 0)
GpuSnippetMethods airlight_gpu_inputs(const std::vector<AirlightQuery> &queries, const std::string &snippet);
GpuSnippetMethods near_light_gpu_inputs(const std::vector<NearLightQuery> &queries, const std::string &snippet);
GpuSnippetMethods surface_gpu_inputs(const std::vector<SurfaceQuery> &queries, const std::string &snippet);
// sigma_s, sigma_a, I0, D, sin gamma, cos gamma, s
inline const char *kAirlightGpuArgs = "in0.x, in0.y, in0.z, in0.w, in1.x, in1.y, in1.z";
// sigma_s, sigma_a, I0, normal, eye_dir, light_rel, s, eta, fresnel
inline const char *kNearLightGpuArgs = "in0.x, in0.y, in0.z, in1.xyz, in2.xyz, in3.xyz, in0.w, in1.w, in2.w > 0.5";

} // namespace scatterlut
