#include "report.hpp"

#include "cli_checks.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iterator>
#include <deque>
#include <iostream>
#include <map>
#include <memory>
#include <random>
#include <string>
#include <vector>

#include <unistd.h>

#include "measure_util.hpp"
#include "opencl_device.hpp"
#include "plan.hpp"
#include "scene.hpp"
#include "scene_queries.hpp"
#include "report_gpu.hpp"
#include "report_ladders.hpp"
#include "report_spot.hpp"
#include "report_spot_surfaces.hpp"
#include "report_writers.hpp"
#include "svg_plot.hpp"
#include "text_format.hpp"
#include "version.hpp"
#include "scatterlut/io.hpp"

namespace scatterlut {
namespace {

// ---------------------------------------------------------------- the command
struct ReportOptions {
    std::string scene_file; // "" = the embedded default scene
    std::string out_dir;
    std::string device;
    int rounds = 5;
    int queries = 4000;
    bool no_gpu = false;
    int gpu_pixels = 32768;
};

void progress_line(const std::string &label, double f) {
    if (!isatty(STDERR_FILENO)) return;
    std::fprintf(stderr, "\r%-60s %3d%%", label.c_str(), static_cast<int>(100.0 * f + 0.5));
    if (f >= 1.0) std::fprintf(stderr, "\n");
    std::fflush(stderr);
}

int run_report(const ReportOptions &opt, const std::string &command_line) {
    const Scene scene = opt.scene_file.empty() ? default_scene() : load_scene_file(opt.scene_file);
    Storage storage = Storage::F32;
    storage_from_string(scene.output.storage, &storage);
    ScenePlan plan = derive_plan(scene, storage);
    std::filesystem::create_directories(opt.out_dir);

    std::string md = "# scatterlut report: " + (scene.name.empty() ? scene.source : scene.name) + "\n\n";
    md += "Produced by `" + command_line + "` (scatterlut " + generator_version() + ").\n";
    md += "Scene: `" + scene.source + "`; accepted relative error on radiance " + fmt("%.3g", scene.relative_error) +
          ". Every figure below comes from this run; times are medians of " + std::to_string(opt.rounds) +
          " interleaved rounds on a machine that may be shared, so compare rows of one run, not runs.\n\n";
    for (const std::string &n : plan.notes) md += "- note: " + n + "\n";
    if (plan.tables.empty()) {
        md += "\nThe scene calls for no table: nothing to measure.\n";
        write_text(opt.out_dir + "/report.md", md);
        std::cout << "no tables: wrote " << opt.out_dir << "/report.md\n";
        return 0;
    }

    Device device(opt.device);
    std::cerr << "device: " << device.info().describe() << "\n";
    Provenance provenance;
    provenance.generator_version = generator_version();
    provenance.command_line = command_line;
    provenance.device = device.info().describe();
    provenance.scene = scene.text;
    md += "Device: " + device.info().describe() + ".\n";
    resolve_plan(plan, device, provenance, progress_line);
    const size_t max_bytes = static_cast<size_t>(scene.max_table_MiB * 1024.0 * 1024.0);
    std::deque<RadianceQueries> all_queries;                   // kept for the GPU section
    std::map<std::string, std::vector<MethodRow>> all_methods; // table name → its CPU methods
    std::vector<GpuTableInput> gpu_inputs;

    for (const PlannedTable &t : plan.tables) {
        const std::string kind = t.name();
        std::cout << kind << ":\n";
        const RadianceQueries qs = t.kind->radiance_queries(scene, t.plan, static_cast<size_t>(opt.queries), kQuerySeed);
        const double accepted = scene.relative_error;

        const auto tol = tolerance_ladder(device, t, opt.rounds);
        std::cout << "  tolerance ladder: " << tol.size() << " rungs\n";
        const auto res = resolution_ladder(device, t, qs, provenance, storage, max_bytes, opt.rounds,
                                           [&](double f) { progress_line(kind + " resolution ladder", f); });
        std::cout << "  resolution ladder: " << res.size() << " tables\n";
        const auto methods = runtime_methods(*t.kind, t.table, qs, opt.rounds);
        std::cout << "  runtime methods: " << methods.size() << " on " << qs.size() << " queries\n";

        write_text(opt.out_dir + "/" + kind + "_tolerance.csv", tolerance_csv(tol));
        write_text(opt.out_dir + "/" + kind + "_resolution.csv", resolution_csv(res));
        write_text(opt.out_dir + "/" + kind + "_methods.csv", methods_csv(methods));
        write_text(opt.out_dir + "/" + kind + "_tolerance.svg", render_svg(tolerance_plot(kind, tol)));
        write_text(opt.out_dir + "/" + kind + "_resolution.svg", render_svg(resolution_plot(kind, res, accepted)));
        write_text(opt.out_dir + "/" + kind + "_methods.svg", render_svg(methods_plot(kind, methods, accepted)));

        md += markdown_section(t, storage, qs, tol, res, methods);
        const std::string spot = spot_report_section(t, scene, static_cast<size_t>(opt.queries) / 4, opt.rounds,
                                                     opt.out_dir);
        if (!spot.empty()) std::cout << "  spot lights: measured inside, beside and along the beams\n";
        md += spot;
        all_methods[kind] = methods;
        all_queries.push_back(qs);
        gpu_inputs.push_back({kind, t.kind->gpu_methods(t.table, all_queries.back()), &all_queries.back()});
    }

    GpuOptions gpu_options;
    gpu_options.enabled = !opt.no_gpu;
    gpu_options.rounds = opt.rounds;
    gpu_options.min_pixels = static_cast<size_t>(opt.gpu_pixels);
    const GpuSection gpu = measure_gpu(gpu_inputs, gpu_options);
    std::vector<std::vector<MethodRow>> gpu_cpu_rows;
    for (const GpuGroup &g : gpu.groups) {
        gpu_cpu_rows.push_back(group_cpu_methods(g, all_methods));
        if (!g.why_not.empty() || g.rows.empty()) continue;
        write_text(opt.out_dir + "/" + gpu_stem(g) + ".csv", gpu_csv(g, gpu_cpu_rows.back()));
        write_text(opt.out_dir + "/" + gpu_stem(g) + ".svg",
                   render_svg(gpu_plot(g, gpu_cpu_rows.back(), scene.relative_error)));
    }
    std::cout << "GPU: " << (gpu.measured ? gpu.renderer : gpu.why_not) << "\n";
    for (const GpuGroup &g : gpu.groups)
        if (gpu.measured)
            std::cout << "  " << g.snippet << ": "
                      << (g.why_not.empty()
                              ? std::to_string(g.rows.size()) + " methods on " + std::to_string(g.queries) + " queries"
                              : g.why_not)
                      << "\n";
    md += gpu_markdown(gpu, gpu_cpu_rows, scene.relative_error);
    if (scene_has_spot_surfaces(scene)) {
        // Surfaces lit by spot lights (docs/SPOT.md): the falloff factor against the exact terms.
        const int points = std::clamp(opt.queries / 20, 20, 2000);
        std::cout << "spot-lit surfaces: " << points << " points\n";
        md += spot_surface_section(scene, points, opt.out_dir);
    }
    write_text(opt.out_dir + "/report.md", md);
    std::cout << "wrote " << opt.out_dir << "/report.md\n";
    return 0;
}

} // namespace

void setup_report(CLI::App &app, int &exit_code, const std::string &command_line) {
    auto opt = std::make_shared<ReportOptions>();
    auto *cmd = app.add_subcommand("report", "What accuracy costs in time: tolerance and resolution ladders, runtime "
                                             "methods and the GPU snippets' tiers for every table a scene calls for "
                                             "(Markdown, CSV, SVG)");
    cmd->add_option("--scene", opt->scene_file, "Scene file (TOML); default: the embedded default scene")
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", opt->out_dir, "Directory for report.md and the CSV and SVG files")
        ->required()
        ->check(non_empty_text("an output directory"));
    cmd->add_option("--device", opt->device, "OpenCL device: P:D index or name substring (env SCATTERLUT_DEVICE)");
    add_integer_option(cmd, "--rounds", opt->rounds, "Interleaved timing rounds per measurement (median reported)", 1,
                       100)
        ->capture_default_str();
    add_integer_option(cmd, "--queries", opt->queries,
                       "Random radiance queries over the scene's domain per table (and 1/20 as many spot-lit surface "
                       "points, 20 to 2000, where spot lights light surfaces)",
                       100, 1000000)
        ->capture_default_str();
    cmd->add_flag("--no-gpu", opt->no_gpu,
                  "Skip the GPU section's measurement (the snippets' tiers drawn through EGL/OpenGL; the section "
                  "then says it was not measured)");
    add_integer_option(cmd, "--gpu-pixels", opt->gpu_pixels,
                       "GPU section: pixels per frame at least (each table's queries repeated to fill them; more "
                       "where the slowest method's frame is under 10 ms)",
                       1, 1048576)
        ->capture_default_str();
    cmd->callback([opt, &exit_code, &command_line] { exit_code = run_report(*opt, command_line); });
}

} // namespace scatterlut
