// The WebGL2 snippets (GLSL ES 3.00: scatterlut_airlight.essl, scatterlut_nearlight.essl),
// assembled from the same one source as the GLSL and HLSL ones (cmake/assemble_shaders.cmake):
//   - ShaderWebGL2.SharedBodyIsTheGlslOne: the same shared body, only the prelude differs;
//   - ShaderWebGL2.CompileAsGlslEs300: both snippets in one "#version 300 es" fragment
//     shader that declares no precision of its own, as a three.js ShaderMaterial with
//     glslVersion GLSL3 would, with and without the hardware-filter options, sampling an
//     airlight 2-D texture and a packed E4 3-D texture (the KTX2 layout, FORMAT.md §6);
//     glslangValidator checks it against the GLSL ES 3.00 rules;
//   - ShaderWebGL2.GlslangEnforcesEsRules: the same shader with the desktop snippets and no
//     precision statement is refused (an ES fragment shader has no default precision for
//     float, nor any shader for sampler3D), so the compile check above is an ES check.
#include "gpu_harness.hpp"

namespace {

using namespace gpu_harness;

std::string es_fragment(const std::string &airlight, const std::string &nearlight, bool hardware_filter) {
    std::string s = "#version 300 es\n";
    if (hardware_filter) s += "#define SLUT_AIRLIGHT_HARDWARE_FILTER\n#define SLUT_NEARLIGHT_HARDWARE_FILTER\n";
    s += airlight + nearlight;
    s += R"glsl(
uniform sampler2D airlight_table;   // R32F, NEAREST (texelFetch path) or LINEAR (hardware filter)
uniform sampler3D near_table;       // R32F, E4 packed: T x (g * q) x r
uniform vec4 airlight_meta;         // u_max, u_scale, w_min, -
uniform ivec2 airlight_counts;      // u count, w count
uniform vec3 light_pos;
uniform vec3 medium;                // sigma_s, sigma_a, I0
uniform vec3 slab_normal;
in vec3 world_pos;
in vec3 eye_pos;
out vec4 colour;

void main() {
    SlutAirlightTable a = slut_airlight_table(airlight_meta.x, airlight_meta.y, airlight_counts.x,
                                              airlight_meta.z, airlight_counts.y);
    vec3 view = world_pos - eye_pos;
    float L = slut_airlight_radiance_points(airlight_table, a, eye_pos, view, light_pos, length(view),
                                            medium.x, medium.y, medium.z);
    SlutNearLightTable e4 = slut_near_light_table_e4(
        slut_axis_make(0.5, 10.0, 1.0, SLUT_WARP_LOGLIN, 45), slut_axis_make(-0.984808, 1.0, 0.02, SLUT_WARP_LOG1P, 20),
        slut_axis_make(0.0, 5.75877, 1e-9, SLUT_WARP_LOG1P, 85), slut_axis_make(0.2, 11.5175, 0.0, SLUT_WARP_NL_QODDS, 37));
    L += slut_near_light_radiance(near_table, e4, medium.x, medium.y, medium.z, slab_normal,
                                  normalize(eye_pos - world_pos), light_pos - world_pos, 0.5, 1.0, false);
    colour = vec4(vec3(L), 1.0);
}
)glsl";
    return s;
}

TEST(ShaderWebGL2, SharedBodyIsTheGlslOne) {
    for (const char *name : {"airlight", "nearlight"}) {
        SCOPED_TRACE(name);
        const std::string es = read_text(kShaderDir + "scatterlut_" + name + ".essl");
        EXPECT_EQ(shared_body(es), shared_body(read_text(kShaderDir + "scatterlut_" + name + ".glsl")));
        EXPECT_NE(es.find("precision highp sampler3D;"), std::string::npos);
        EXPECT_NE(es.find("GLSL ES 3.00 (WebGL2) sampling snippet"), std::string::npos);
    }
}

TEST(ShaderWebGL2, CompileAsGlslEs300) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    const std::string airlight = read_text(kShaderDir + "scatterlut_airlight.essl");
    const std::string nearlight = read_text(kShaderDir + "scatterlut_nearlight.essl");
    for (bool hw : {false, true}) {
        SCOPED_TRACE(hw ? "hardware filter" : "texelFetch path");
        EXPECT_EQ(glslang(std::string("webgl2") + (hw ? "_hw" : "") + ".frag", es_fragment(airlight, nearlight, hw), ""),
                  "");
    }
}

TEST(ShaderWebGL2, GlslangEnforcesEsRules) {
    if (kGlslang.empty()) SLUT_SKIP_OR_FAIL("glslangValidator was not found at configure time (Debian: glslang-tools)");
    const std::string airlight = read_text(kShaderDir + "scatterlut_airlight.glsl");
    const std::string nearlight = read_text(kShaderDir + "scatterlut_nearlight.glsl");
    const std::string error = glslang("webgl2_desktop_snippets.frag", es_fragment(airlight, nearlight, false), "");
    EXPECT_NE(error.find("default precision"), std::string::npos) << error;
}

} // namespace
