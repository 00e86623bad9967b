// scatterlut generator — `report`'s GPU section: every planned table that a GLSL snippet
// samples, drawn per tier (and the GPU baselines engines use) over the table's own radiance
// queries, one query per pixel, through a surfaceless EGL / OpenGL 4.3 context (Mesa
// llvmpipe where there is no GPU: egl_context.hpp, loaded with dlopen so that `scatterlut`
// runs without libEGL). What each kind draws: TableKind::gpu_methods (gpu_methods.hpp); the
// snippets are the generated ones, embedded at build time. Cost: ns per pixel, net of a pass
// that only reads the inputs, median of interleaved rounds, and the per-round ratio of each
// method's frame to the group's baseline frame; error: the float radiance read back against
// the exact references the CPU methods are measured against.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include "gpu_methods.hpp"
#include "kinds/table_kind.hpp"
#include "report_ladders.hpp"

namespace scatterlut {

struct GpuOptions {
    bool enabled = true;       // false: --no-gpu
    int rounds = 5;            // interleaved rounds (the report's --rounds)
    int frames = 3;            // frames per method and round (the round's figure: their median)
    size_t min_pixels = 32768; // each frame repeats the queries up to at least this many pixels
};

// One method's figures.
struct GpuRow {
    std::string name, what;
    std::string tier;                               // "fast", "accurate", "none"; "" for a baseline
    std::string table;                              // the planned table it samples ("" for a baseline without one)
    double ns_per_pixel = 0;                        // net of the inputs-only pass (median frame of rounds)
    double ns_per_pixel_gross = 0;                  // the whole frame
    double ratio = 0, ratio_min = 0, ratio_max = 0; // per-round frame / the baseline's frame
    ErrorStats error;
};

// One snippet over one query set: the tables it samples there (the airlight snippet's
// airlight_F and airlight_rational share the isotropic airlight queries).
struct GpuGroup {
    std::vector<std::string> tables; // their names (file stems), the first names the group's files
    std::string snippet;
    std::string baseline; // the rows' ratio reference
    std::vector<std::string> notes;
    size_t queries = 0;
    int width = 0, height = 0; // the frame
    std::string why_not;       // not measured (this group), else ""
    std::vector<GpuRow> rows;
};

struct GpuSection {
    bool measured = false; // a context was made; groups may still carry their own why_not
    std::string why_not;   // when !measured: why, in words
    std::string renderer;  // GL_RENDERER | GL_VERSION, and LP_NUM_THREADS
    GpuOptions options;
    double seconds = 0; // the whole measurement, wall clock
    std::vector<GpuGroup> groups;
};

// One planned table's GPU methods over its radiance queries.
struct GpuTableInput {
    std::string table;
    GpuSnippetMethods methods;
    const RadianceQueries *queries = nullptr;
};

// Groups the tables (same snippet, same pixel inputs: one group) and measures every group.
// Never throws for a missing context or driver: the section says why.
GpuSection measure_gpu(const std::vector<GpuTableInput> &tables, const GpuOptions &options);

} // namespace scatterlut
