#include "report_gpu.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdlib>
#include <string>
#include <utility>
#include <vector>

#include "embedded_kernels.hpp"
#include "gpu_pixel_passes.hpp"

namespace scatterlut {

namespace embedded {
// The generated GLSL snippets and the GPU baselines' GLSL (bench/shaders), embedded at build
// time (host/CMakeLists.txt: cmake/embed_kernels.cmake).
extern const EmbeddedFile kShaderFiles[];
extern const std::size_t kShaderFileCount;
} // namespace embedded

namespace {

// Tables of the same snippet over the same pixels and the same exact radiance form one group (the
// airlight snippet's two tables; not the surface tables of two exponents, whose queries coincide
// but whose quantities differ), in the order of first appearance.
std::vector<GpuGroup> group_tables(const std::vector<GpuTableInput> &tables,
                                   std::vector<std::vector<size_t>> *members) {
    std::vector<GpuGroup> groups;
    for (size_t t = 0; t < tables.size(); ++t) {
        const GpuSnippetMethods &m = tables[t].methods;
        if (m.snippet.empty() || m.methods.empty()) continue;
        size_t g = 0;
        for (; g < groups.size(); ++g) {
            const GpuSnippetMethods &first = tables[(*members)[g][0]].methods;
            if (first.snippet == m.snippet && first.vec4s == m.vec4s && first.inputs == m.inputs &&
                tables[(*members)[g][0]].queries->exact == tables[t].queries->exact)
                break;
        }
        if (g == groups.size()) {
            groups.emplace_back();
            members->emplace_back();
            groups[g].snippet = m.snippet;
            groups[g].queries = tables[t].queries->size();
        }
        groups[g].tables.push_back(tables[t].table);
        (*members)[g].push_back(t);
        if (groups[g].baseline.empty()) groups[g].baseline = m.baseline;
        groups[g].notes.insert(groups[g].notes.end(), m.notes.begin(), m.notes.end());
    }
    return groups;
}

} // namespace

#if SLUT_HAVE_EGL

namespace {

using gpu_harness::Gl;

// The embedded file called `name`, or null.
const char *embedded_shader(const std::string &name) {
    for (std::size_t k = 0; k < embedded::kShaderFileCount; ++k)
        if (name == embedded::kShaderFiles[k].name) return embedded::kShaderFiles[k].contents;
    return nullptr;
}

constexpr int kFrameWidth = 256;        // pixels per row of the frame
constexpr double kTargetFrameMs = 10.0; // the slowest method's frame at least (else rows are added)
constexpr int kMaxFrameRows = 4096;     // at most 2^20 pixels

// Relative errors of the first exact.size() pixels of `image` (pixel k: query k); a result that
// is not finite and ≥ 0 counts as +inf.
std::vector<double> pixel_errors(const std::vector<float> &image, const std::vector<double> &exact) {
    std::vector<double> e(exact.size());
    for (size_t k = 0; k < exact.size(); ++k) {
        const double got = image[k];
        e[k] = std::isfinite(got) && got >= 0.0 ? std::fabs(got - exact[k]) / exact[k] : HUGE_VAL;
    }
    return e;
}

// The inputs of `rows` rows of kFrameWidth pixels: pixel i draws query i mod (the queries).
std::vector<float> frame_inputs(const GpuSnippetMethods &m, int rows) {
    const size_t per_query = static_cast<size_t>(m.vec4s) * 4, n = m.inputs.size() / per_query;
    const size_t pixels = static_cast<size_t>(kFrameWidth) * static_cast<size_t>(rows);
    std::vector<float> inputs(pixels * per_query);
    for (size_t i = 0; i < pixels; ++i)
        std::copy_n(m.inputs.begin() + static_cast<long>((i % n) * per_query), per_query,
                    inputs.begin() + static_cast<long>(i * per_query));
    return inputs;
}

// Frames of `methods` (built) in rounds on a frame of `rows` rows: the rows' figures; "" or why not.
std::string time_and_read(const Gl &gl, const GpuSnippetMethods &first, const RadianceQueries &qs, int rows_count,
                          std::vector<gpu_harness::Method> &methods, const GpuOptions &opt, const std::string &baseline,
                          std::vector<GpuRow> &rows) {
    gpu_harness::Passes passes(gl, kFrameWidth, rows_count, frame_inputs(first, rows_count));
    if (!passes.complete()) return "the R32F render target is not complete";
    const std::vector<std::vector<double>> round_ms = passes.time_rounds(methods, opt.rounds, opt.frames);
    const double pixels = static_cast<double>(kFrameWidth) * rows_count;
    const double inputs_ms = gpu_harness::median_of(round_ms.back());
    size_t base = 0;
    for (size_t m = 0; m < rows.size(); ++m)
        if (rows[m].name == baseline) base = m;
    for (size_t m = 0; m < rows.size(); ++m) {
        const double ms = gpu_harness::median_of(round_ms[m]);
        rows[m].ns_per_pixel_gross = ms * 1e6 / pixels;
        rows[m].ns_per_pixel = (ms - inputs_ms) * 1e6 / pixels;
        std::vector<double> ratios;
        for (size_t r = 0; r < round_ms[m].size(); ++r) ratios.push_back(round_ms[m][r] / round_ms[base][r]);
        rows[m].ratio = gpu_harness::median_of(ratios);
        rows[m].ratio_min = *std::min_element(ratios.begin(), ratios.end());
        rows[m].ratio_max = *std::max_element(ratios.begin(), ratios.end());
        rows[m].error = error_stats(pixel_errors(passes.frame(methods[m]), qs.exact));
    }
    const GLenum gl_error = gl.glGetError();
    return gl_error == GL_NO_ERROR ? ""
                                   : "OpenGL error 0x" + gpu_harness::GpuContext::hex(static_cast<EGLint>(gl_error));
}

// Measures one group; sets why_not where it cannot.
void measure_group(const Gl &gl, const std::vector<GpuTableInput> &tables, const std::vector<size_t> &members,
                   const GpuOptions &opt, GpuGroup &group) {
    const GpuSnippetMethods &first = tables[members[0]].methods;
    const RadianceQueries &qs = *tables[members[0]].queries;
    const size_t n = qs.size();
    if (n == 0) {
        group.why_not = "no radiance queries";
        return;
    }
    // The frame: whole rows of kFrameWidth pixels, at least the queries and opt.min_pixels.
    const size_t pixels_wanted = std::max(n, opt.min_pixels);
    group.width = kFrameWidth;
    group.height = static_cast<int>(std::min<size_t>(kMaxFrameRows, (pixels_wanted + kFrameWidth - 1) / kFrameWidth));

    GLint max_2d = 0, max_3d = 0;
    gl.glGetIntegerv(GL_MAX_TEXTURE_SIZE, &max_2d);
    gl.glGetIntegerv(GL_MAX_3D_TEXTURE_SIZE, &max_3d);
    std::vector<gpu_harness::Method> methods;
    std::vector<GpuRow> rows;
    std::vector<GLuint> textures;
    for (size_t t : members)
        for (const GpuMethod &m : tables[t].methods.methods) {
            if (!group.why_not.empty()) break;
            const char *source = embedded_shader(m.source);
            if (!source) {
                group.why_not = "the GLSL file " + m.source + " is not embedded in this build";
                break;
            }
            gpu_harness::Method gm;
            gm.name = m.name;
            gm.what = m.what;
            gm.fragment = gpu_harness::fragment_source(m.before + source + "\n" + m.after, first.vec4s, m.call);
            gm.uniforms = m.uniforms;
            if (m.texture) {
                const GpuTexture &x = *m.texture;
                const GLint limit = x.depth > 0 ? max_3d : max_2d;
                if (x.width > limit || x.height > limit || x.depth > limit) {
                    group.why_not = "the " + m.name + " method's texture (" + std::to_string(x.width) + " x " +
                                    std::to_string(x.height) + (x.depth > 0 ? " x " + std::to_string(x.depth) : "") +
                                    ") exceeds this OpenGL's texture size limit " + std::to_string(limit);
                    break;
                }
                gm.texture_target = x.depth > 0 ? GL_TEXTURE_3D : GL_TEXTURE_2D;
                gm.texture = gpu_harness::make_r32f_texture(gl, x.texels, x.width, x.height, x.depth);
                textures.push_back(gm.texture);
            }
            methods.push_back(gm);
            GpuRow row;
            row.name = m.name;
            row.what = m.what;
            row.tier = m.tier;
            row.table = m.texture && !m.tier.empty() ? tables[t].table : "";
            rows.push_back(row);
        }
    gpu_harness::Method inputs_only;
    inputs_only.name = "inputs";
    inputs_only.what = "reads the inputs only";
    inputs_only.fragment = gpu_harness::fragment_source("", first.vec4s, first.inputs_read);
    inputs_only.timed_only = true;
    methods.push_back(inputs_only);

    auto release = [&] {
        for (const auto &m : methods)
            if (m.program) gl.glDeleteProgram(m.program);
        if (!textures.empty()) gl.glDeleteTextures(static_cast<GLsizei>(textures.size()), textures.data());
    };
    if (!group.why_not.empty()) {
        release();
        return;
    }
    {
        // Build every program on the first frame, and time each (median of 3 frames): where the slowest
        // is shorter than kTargetFrameMs (cheap snippets, whose frames the machine's jitter
        // would swamp), the frame grows to it, up to kMaxFrameRows rows.
        gpu_harness::Passes probe(gl, group.width, group.height, frame_inputs(first, group.height));
        std::string error = probe.complete() ? probe.build(methods) : "the R32F render target is not complete";
        if (error.empty()) {
            double slowest_ms = 0;
            for (const auto &t : probe.time_rounds(methods, 1, 3))
                slowest_ms = std::max(slowest_ms, t[0]); // median of 3
            if (slowest_ms > 0 && slowest_ms < kTargetFrameMs)
                group.height =
                    std::min(kMaxFrameRows, static_cast<int>(std::ceil(group.height * kTargetFrameMs / slowest_ms)));
        }
        if (error.empty()) error = time_and_read(gl, first, qs, group.height, methods, opt, group.baseline, rows);
        if (!error.empty()) group.why_not = error;
    }
    size_t base = 0;
    for (size_t m = 0; m < rows.size(); ++m)
        if (rows[m].name == group.baseline) base = m;
    if (!rows.empty()) group.baseline = rows[base].name;
    release();
    if (group.why_not.empty()) group.rows = std::move(rows);
}

} // namespace

GpuSection measure_gpu(const std::vector<GpuTableInput> &tables, const GpuOptions &options) {
    GpuSection s;
    s.options = options;
    std::vector<std::vector<size_t>> members;
    s.groups = group_tables(tables, &members);
    if (!options.enabled) {
        s.why_not = "the run was given --no-gpu";
        return s;
    }
    if (s.groups.empty()) {
        s.why_not = "no planned table is sampled by a GLSL snippet";
        return s;
    }
    const auto t0 = std::chrono::steady_clock::now();
    gpu_harness::GpuContext &context = gpu_harness::gpu();
    if (!context.ok) {
        s.why_not = "no OpenGL 4.3 context through EGL: " + context.why_not;
        return s;
    }
    const char *threads = std::getenv("LP_NUM_THREADS");
    s.renderer = context.renderer + " (LP_NUM_THREADS=" + (threads ? threads : "unset") + ")";
    s.measured = true;
    for (size_t g = 0; g < s.groups.size(); ++g) measure_group(context.gl, tables, members[g], options, s.groups[g]);
    s.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    return s;
}

#else // SLUT_HAVE_EGL

GpuSection measure_gpu(const std::vector<GpuTableInput> &tables, const GpuOptions &options) {
    GpuSection s;
    s.options = options;
    std::vector<std::vector<size_t>> members;
    s.groups = group_tables(tables, &members);
    s.why_not = options.enabled ? "this scatterlut was built without the EGL and OpenGL headers (EGL/egl.h, "
                                  "GL/glcorearb.h; Debian: libegl-dev libgl-dev), so it cannot draw"
                                : "the run was given --no-gpu";
    return s;
}

#endif // SLUT_HAVE_EGL

} // namespace scatterlut
