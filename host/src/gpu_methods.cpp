#include "gpu_methods.hpp"

#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <string>
#include <utility>

namespace scatterlut {

std::string gpu_tier_define(const std::string &tier) {
    if (tier == "fast") return "#define SLUT_TIER_FAST\n";
    if (tier == "accurate") return "#define SLUT_TIER_ACCURATE\n";
    return "";
}

std::string glsl_float(double v) {
    if (std::isinf(v)) return v > 0 ? "uintBitsToFloat(0x7F800000u)" : "uintBitsToFloat(0xFF800000u)";
    char buf[64];
    std::snprintf(buf, sizeof buf, "%.9g", v);
    std::string s = buf;
    if (s.find_first_of(".e") == std::string::npos) s += ".0";
    return s;
}

std::string glsl_axis(const Axis &axis) {
    const slut_axis &a = axis.map;
    return "slut_axis_make(" + glsl_float(a.min) + ", " + glsl_float(a.max) + ", " + glsl_float(a.scale) + ", " +
           std::to_string(a.warp) + ", " + std::to_string(a.count) + ")";
}

std::shared_ptr<const GpuTexture> gpu_table_texture(const Table &table) {
    const size_t axes = table.axes.size(), channels = table.channels.size();
    if (axes < 2 || axes > 4 || channels == 0 || table.values.size() != table.node_count() * channels) return nullptr;
    std::vector<int> n;
    for (const Axis &a : table.axes) n.push_back(a.map.count);
    auto t = std::make_shared<GpuTexture>();
    t->width = n[0];
    t->height = axes == 4 ? n[1] * n[3] : n[1];
    t->depth = axes >= 3 ? n[2] : 0;
    t->texels.resize(table.node_count());
    const size_t n0 = static_cast<size_t>(n[0]), n1 = static_cast<size_t>(n[1]);
    const size_t n2 = axes >= 3 ? static_cast<size_t>(n[2]) : 1, n3 = axes == 4 ? static_cast<size_t>(n[3]) : 1;
    const size_t height = static_cast<size_t>(t->height);
    for (size_t i3 = 0; i3 < n3; ++i3)
        for (size_t i2 = 0; i2 < n2; ++i2)
            for (size_t i1 = 0; i1 < n1; ++i1)
                for (size_t i0 = 0; i0 < n0; ++i0) {
                    const size_t node = i0 + n0 * (i1 + n1 * (i2 + n2 * i3)); // axis 0 fastest
                    const size_t texel = i0 + n0 * ((i1 + n1 * i3) + height * i2);
                    t->texels[texel] = static_cast<float>(table.values[node * channels]);
                }
    return t;
}

GpuMethod gpu_tier_method(const std::string &tier, const std::string &what, const std::string &snippet,
                          const std::string &sampler, std::shared_ptr<const GpuTexture> texture,
                          const std::string &after, const std::string &call) {
    GpuMethod m;
    m.name = tier;
    m.what = what;
    m.tier = tier;
    m.source = snippet;
    m.before = gpu_tier_define(tier) + "layout(binding = 0) uniform " + sampler + " slut_table;\n";
    m.after = after;
    m.call = call;
    m.texture = std::move(texture);
    return m;
}

namespace {

GpuSnippetMethods inputs_of(const std::string &snippet, int vec4s, std::string read, size_t queries) {
    GpuSnippetMethods g;
    g.snippet = snippet;
    g.vec4s = vec4s;
    g.inputs_read = std::move(read);
    g.inputs.reserve(queries * static_cast<size_t>(vec4s) * 4);
    return g;
}

void push(std::vector<float> &v, std::initializer_list<double> values) {
    for (double x : values) v.push_back(static_cast<float>(x));
}

} // namespace

GpuSnippetMethods airlight_gpu_inputs(const std::vector<AirlightQuery> &queries, const std::string &snippet) {
    GpuSnippetMethods g =
        inputs_of(snippet, 2, "in0.x + in0.y + in0.z + in0.w + in1.x + in1.y + in1.z", queries.size());
    for (const AirlightQuery &q : queries) // gamma: view direction <-> direction viewer -> light
        push(g.inputs, {q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m, std::sin(q.gamma_rad),
                        std::cos(q.gamma_rad), q.length_m, 0.0});
    return g;
}

GpuSnippetMethods near_light_gpu_inputs(const std::vector<NearLightQuery> &queries, const std::string &snippet) {
    GpuSnippetMethods g = inputs_of(snippet, 4,
                                    "in0.x + in0.y + in0.z + in0.w + in1.x + in1.y + in1.z + in1.w + in2.x + in2.y + "
                                    "in2.z + in2.w + in3.x + in3.y + in3.z",
                                    queries.size());
    for (const NearLightQuery &q : queries)
        push(g.inputs, {q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.length_m, q.normal[0], q.normal[1],
                        q.normal[2], q.eta, q.eye_dir[0], q.eye_dir[1], q.eye_dir[2], q.fresnel ? 1.0 : 0.0,
                        q.light_rel_m[0], q.light_rel_m[1], q.light_rel_m[2], 0.0});
    return g;
}

GpuSnippetMethods surface_gpu_inputs(const std::vector<SurfaceQuery> &queries, const std::string &snippet) {
    GpuSnippetMethods g = inputs_of(snippet, 2, "in0.x + in0.y + in0.z + in0.w + in1.x", queries.size());
    for (const SurfaceQuery &q : queries)
        push(g.inputs,
             {q.sigma_s_per_m, q.sigma_a_per_m, q.intensity_W_per_sr, q.distance_m, q.theta_rad, 0.0, 0.0, 0.0});
    return g;
}

} // namespace scatterlut
