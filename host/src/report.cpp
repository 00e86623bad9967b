#include "report.hpp"

#include "cli_checks.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <functional>
#include <iterator>
#include <iostream>
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
#include "svg_plot.hpp"
#include "text_format.hpp"
#include "version.hpp"
#include "scatterlut/io.hpp"

namespace scatterlut {
namespace {

// The ladders. Tolerances are relative, on the integrated quantity (G̃ or E).
constexpr double kTolerances[] = {1e-3, 1e-5, 1e-7, 1e-9, 1e-11, 1e-13};
// Spacing factors around the planner's node counts: (n − 1)·k + 1 nodes per axis.
constexpr double kResolutionFactors[] = {0.5, 0.71, 1.0, 1.41, 2.0};
constexpr int kToleranceNodes = 400;    // nodes compared with the finer reference per rung
constexpr uint64_t kToleranceSeed = 11; // the same nodes on every rung
constexpr uint64_t kQuerySeed = 12;
constexpr uint64_t kLookupSeed = 13;
constexpr size_t kLookups = 1 << 14;


struct ErrorStats {
    double median = 0, p90 = 0, p99 = 0, max = 0;
    size_t points = 0;
};

ErrorStats error_stats(const std::vector<double> &err) {
    ErrorStats s;
    s.points = err.size();
    if (err.empty()) return s;
    s.median = percentile(err, 0.5);
    s.p90 = percentile(err, 0.9);
    s.p99 = percentile(err, 0.99);
    s.max = *std::max_element(err.begin(), err.end());
    return s;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
    return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Runs every job `rounds` times, interleaved (job 0, 1, …, 0, 1, …), so that the machine's
// drift over minutes affects all of them alike; returns each job's median seconds.
std::vector<double> interleaved_median_seconds(int rounds, const std::vector<std::function<void()>> &jobs) {
    std::vector<std::vector<double>> t(jobs.size());
    for (int r = 0; r < rounds; ++r)
        for (size_t j = 0; j < jobs.size(); ++j) {
            const auto t0 = std::chrono::steady_clock::now();
            jobs[j]();
            t[j].push_back(seconds_since(t0));
        }
    std::vector<double> out;
    for (auto &v : t) out.push_back(percentile(v, 0.5));
    return out;
}

// Keeps a computed value alive so that timed loops are not optimised away.
volatile double g_sink = 0;

// ---------------------------------------------------------------- what a planned table is
PlannedTable with_counts(PlannedTable t, const std::vector<int> &c, Storage storage) {
    set_counts(t, c);
    t.kind->set_storage(t.plan, storage);
    return t;
}

double planned_tolerance(const PlannedTable &t) { return t.kind->integration_tolerance(t.plan); }

template <class Method> std::vector<double> relative_errors(const RadianceQueries &qs, Method method) {
    std::vector<double> err(qs.size());
    parallel_for(static_cast<int>(qs.size()), [&](int i) {
        const size_t k = static_cast<size_t>(i);
        err[k] = std::fabs(method(k) - qs.exact[k]) / qs.exact[k];
    });
    return err;
}

// ---------------------------------------------------------------- tolerance ladder
struct ToleranceRung {
    double tolerance = 0;
    double median_ms = 0;
    double max_node_rel = 0;
    bool planned = false;
};

std::vector<ToleranceRung> tolerance_ladder(Device &device, const PlannedTable &t, int rounds) {
    std::vector<double> tolerances(std::begin(kTolerances), std::end(kTolerances));
    const double planned = planned_tolerance(t);
    if (std::find(tolerances.begin(), tolerances.end(), planned) == tolerances.end()) tolerances.push_back(planned);
    std::sort(tolerances.begin(), tolerances.end(), std::greater<>());
    std::vector<ToleranceRung> out;
    std::vector<Table> tables;
    std::vector<std::function<void()>> jobs;
    for (double tol : tolerances) {
        tables.push_back(t.kind->layout(t.plan, tol));
        tables.back().values = t.kind->integrate(device, tables.back(), tol); // also the warm-up of this rung
    }
    for (size_t k = 0; k < tables.size(); ++k)
        jobs.push_back([&, k] { g_sink = t.kind->integrate(device, tables[k], tolerances[k]).back(); });
    const std::vector<double> med = interleaved_median_seconds(rounds, jobs);
    for (size_t k = 0; k < tables.size(); ++k) {
        ToleranceRung r;
        r.tolerance = tolerances[k];
        r.median_ms = 1e3 * med[k];
        r.max_node_rel = t.kind->integration_error(*t.kind->make_sampler(tables[k]),
                                                   t.kind->generator_nodes(tables[k], kToleranceNodes, kToleranceSeed),
                                                   IntegrationReference::FinerPanelRule);
        r.planned = tolerances[k] == planned;
        out.push_back(r);
    }
    return out;
}

// ---------------------------------------------------------------- resolution ladder
struct ResolutionRung {
    std::vector<int> counts;
    Storage storage = Storage::F32;
    size_t bytes = 0;
    double table_max_rel = 0; // the generator's own measurement, on G̃ or E
    ErrorStats radiance;      // over the scene's queries
    double ns_per_lookup = 0;
    bool planned = false;
};

std::vector<double> random_params(const Table &t, size_t count) {
    std::mt19937_64 rng(kLookupSeed);
    std::uniform_real_distribution<double> unit(0.0, 1.0);
    std::vector<double> p(count * t.axes.size());
    for (size_t i = 0; i < count; ++i)
        for (size_t a = 0; a < t.axes.size(); ++a) p[i * t.axes.size() + a] = slut_param_from_unit(&t.axes[a].map, unit(rng));
    return p;
}

// ns per table lookup (G̃ or E) at random in-domain parameters, median of `rounds`.
double ns_per_lookup(const TableKind &kind, const Table &table, int rounds) {
    const std::vector<double> p = random_params(table, kLookups);
    const std::function<double()> lookups = kind.lookup_loop(table, p, kLookups);
    const std::function<void()> job = [&lookups] { g_sink = lookups(); };
    job(); // warm caches
    return 1e9 * interleaved_median_seconds(rounds, {job})[0] / static_cast<double>(kLookups);
}

ErrorStats radiance_errors(const TableKind &kind, const Table &table, const RadianceQueries &qs) {
    return error_stats(relative_errors(qs, kind.table_radiance(table, qs)));
}

std::vector<ResolutionRung> resolution_ladder(Device &device, const PlannedTable &t, const RadianceQueries &qs,
                                              const Provenance &provenance, Storage planned_storage, size_t max_bytes,
                                              int rounds, const std::function<void(double)> &progress) {
    const std::vector<int> planned = counts_of(t);
    std::vector<ResolutionRung> out;
    const size_t steps = std::size(kResolutionFactors) * 2;
    size_t done = 0;
    for (double k : kResolutionFactors) {
        std::vector<int> c;
        for (int n : planned) c.push_back(std::max(4, static_cast<int>(std::lround((n - 1) * k)) + 1));
        for (Storage s : {Storage::F16, Storage::F32}) {
            ResolutionRung r;
            r.counts = c;
            r.storage = s;
            r.bytes = storage_bytes(s);
            for (int n : c) r.bytes *= static_cast<size_t>(n);
            r.planned = k == 1.0 && s == planned_storage;
            if (r.bytes > max_bytes && !r.planned) { // beyond the scene's size bound
                ++done;
                continue;
            }
            const PlannedTable rung = with_counts(t, c, s);
            const Table table = t.kind->generate(device, rung.plan, provenance, {});
            r.table_max_rel = table.accuracy.sampling_max_rel;
            r.radiance = radiance_errors(*t.kind, table, qs);
            r.ns_per_lookup = ns_per_lookup(*t.kind, table, rounds);
            out.push_back(r);
            if (progress) progress(static_cast<double>(++done) / static_cast<double>(steps));
        }
    }
    return out;
}

// ---------------------------------------------------------------- runtime methods
struct MethodRow {
    std::string name;
    std::string what;
    double ns_per_call = 0;
    ErrorStats error;
    bool reference = false; // the exact quadrature: the errors are measured against it
};

std::vector<MethodRow> runtime_methods(const TableKind &kind, const Table &table, const RadianceQueries &qs,
                                       int rounds) {
    const std::vector<RuntimeMethod> methods = kind.runtime_methods(table, qs);
    std::vector<std::function<void()>> jobs;
    for (auto &m : methods)
        jobs.push_back([&m, &qs] {
            double sum = 0;
            for (size_t k = 0; k < qs.size(); ++k) sum += m.radiance(k);
            g_sink = sum;
        });
    for (auto &j : jobs) j(); // warm-up
    const std::vector<double> med = interleaved_median_seconds(rounds, jobs);
    std::vector<MethodRow> out;
    for (size_t i = 0; i < methods.size(); ++i) {
        MethodRow r;
        r.name = methods[i].name;
        r.what = methods[i].what;
        r.reference = methods[i].reference;
        r.ns_per_call = 1e9 * med[i] / static_cast<double>(std::max<size_t>(1, qs.size()));
        if (!r.reference) r.error = error_stats(relative_errors(qs, methods[i].radiance));
        else r.error.points = qs.size();
        out.push_back(r);
    }
    return out;
}

// ---------------------------------------------------------------- output
void write_text(const std::string &path, const std::string &text) {
    write_file_atomic(path, std::vector<uint8_t>(text.begin(), text.end()));
}

std::string tolerance_csv(const std::vector<ToleranceRung> &rungs) {
    std::string s = "tolerance,generation_ms_median,max_node_rel_error,planned\n";
    for (const auto &r : rungs)
        s += fmt("%.3g", r.tolerance) + "," + fmt("%.6g", r.median_ms) + "," + fmt("%.6g", r.max_node_rel) + "," +
             (r.planned ? "1" : "0") + "\n";
    return s;
}

std::string resolution_csv(const std::vector<ResolutionRung> &rungs) {
    std::string s = "counts,storage,bytes,table_max_rel,radiance_max_rel,radiance_p99_rel,radiance_median_rel,"
                    "queries,ns_per_lookup,planned\n";
    for (const auto &r : rungs)
        s += counts_text(r.counts) + "," + to_string(r.storage) + "," + std::to_string(r.bytes) + "," +
             fmt("%.6g", r.table_max_rel) + "," + fmt("%.6g", r.radiance.max) + "," + fmt("%.6g", r.radiance.p99) + "," +
             fmt("%.6g", r.radiance.median) + "," + std::to_string(r.radiance.points) + "," +
             fmt("%.4g", r.ns_per_lookup) + "," + (r.planned ? "1" : "0") + "\n";
    return s;
}

std::string methods_csv(const std::vector<MethodRow> &rows) {
    std::string s = "method,ns_per_call,median_rel,p90_rel,p99_rel,max_rel,queries\n";
    for (const auto &r : rows) {
        auto e = [&](double v) { return r.reference ? std::string("reference") : fmt("%.6g", v); };
        s += r.name + "," + fmt("%.5g", r.ns_per_call) + "," + e(r.error.median) + "," + e(r.error.p90) + "," +
             e(r.error.p99) + "," + e(r.error.max) + "," + std::to_string(r.error.points) + "\n";
    }
    return s;
}

Plot tolerance_plot(const std::string &kind, const std::vector<ToleranceRung> &rungs) {
    Plot p;
    p.title = kind + ": integration tolerance ladder";
    p.x_label = "generation time, in-process, median of interleaved rounds (ms)";
    p.y_label = "max relative error at sampled nodes";
    p.log_x = p.log_y = true;
    PlotSeries s;
    s.label = "tolerance rungs";
    for (const auto &r : rungs) {
        s.points.push_back({r.median_ms, r.max_node_rel});
        s.point_labels.push_back("tol " + fmt("%.0e", r.tolerance));
        if (r.planned) p.markers.push_back({{r.median_ms, r.max_node_rel}, "planned"});
    }
    p.series.push_back(s);
    return p;
}

Plot resolution_plot(const std::string &kind, const std::vector<ResolutionRung> &rungs, double accepted) {
    Plot p;
    p.title = kind + ": resolution ladder (radiance over the scene's domain)";
    p.x_label = "table size (bytes)";
    p.y_label = "relative error of the sampled radiance";
    p.log_x = p.log_y = true;
    std::vector<PlotPoint> all;
    for (Storage st : {Storage::F32, Storage::F16}) {
        PlotSeries mx, p99;
        mx.label = std::string(to_string(st)) + " max";
        p99.label = std::string(to_string(st)) + " p99";
        p99.dashed = true;
        for (const auto &r : rungs) {
            if (r.storage != st) continue;
            mx.points.push_back({static_cast<double>(r.bytes), r.radiance.max});
            mx.point_labels.push_back(counts_text(r.counts));
            p99.points.push_back({static_cast<double>(r.bytes), r.radiance.p99});
            all.push_back({static_cast<double>(r.bytes), r.radiance.max});
            if (r.planned) p.markers.push_back({{static_cast<double>(r.bytes), r.radiance.max}, "planned"});
        }
        p.series.push_back(mx);
        p.series.push_back(p99);
    }
    PlotSeries front;
    front.label = "Pareto front (max)";
    front.points = pareto_front(all);
    front.dashed = true;
    p.series.push_back(front);
    p.hlines.push_back({accepted, "accepted error " + fmt("%.3g", accepted)});
    return p;
}

Plot methods_plot(const std::string &kind, const std::vector<MethodRow> &rows, double accepted) {
    Plot p;
    p.title = kind + ": runtime methods for the same radiance";
    p.x_label = "time per radiance call (ns)";
    p.y_label = "relative error vs exact (median, p99, max)";
    p.log_x = p.log_y = true;
    for (const auto &r : rows) {
        if (r.reference) {
            p.vlines.push_back({r.ns_per_call, "exact (the reference) " + fmt("%.3g", r.ns_per_call) + " ns"});
            continue;
        }
        PlotSeries s;
        s.label = r.name;
        s.points = {{r.ns_per_call, r.error.median}, {r.ns_per_call, r.error.p99}, {r.ns_per_call, r.error.max}};
        s.point_labels = {"median", "p99", "max"};
        if (r.name == "table") p.markers.push_back({{r.ns_per_call, r.error.max}, "planned table"});
        p.series.push_back(s);
    }
    p.hlines.push_back({accepted, "accepted error " + fmt("%.3g", accepted)});
    return p;
}

// ---------------------------------------------------------------- the command
struct ReportOptions {
    std::string scene_file; // "" = the embedded default scene
    std::string out_dir;
    std::string device;
    int rounds = 5;
    int queries = 4000;
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

        const PlanTrial &chosen = *t.chosen_trial();
        md += "\n## " + kind + "\n\n";
        for (const auto &r : t.requested_by) md += "- asked for by medium '" + r.medium + "' with light '" + r.light + "': " + r.need + "\n";
        md += "- planned: " + counts_text(chosen.counts) + ", " + to_string(storage) + ", " +
              fmt("%.1f", static_cast<double>(chosen.bytes) / 1024.0) + " KiB, integration tolerance " +
              fmt("%.0e", planned_tolerance(t)) + "; " + t.verdict + "\n";
        md += "- radiance queries: " + std::to_string(qs.size()) + " (" + qs.description + ")\n";

        md += "\n### Integration tolerance\n\n![tolerance ladder](" + kind + "_tolerance.svg)\n\n";
        md += "At the planned resolution. Error: maximum over " + std::to_string(kToleranceNodes) +
              " random nodes against the finer independent panel rule the generator measures with.\n\n";
        md += "| tolerance | generation (ms) | max node error | |\n|---:|---:|---:|---|\n";
        for (const auto &r : tol)
            md += "| " + fmt("%.0e", r.tolerance) + " | " + fmt("%.3g", r.median_ms) + " | " + fmt("%.2e", r.max_node_rel) +
                  " | " + (r.planned ? "planned" : "") + " |\n";

        md += "\n### Resolution and storage\n\n![resolution ladder](" + kind + "_resolution.svg)\n\n";
        md += "Radiance through the runtime (`" + std::string(t.kind->runtime_class()) +
              "::radiance`) against exact quadrature on the queries above; 'table max' is the generator's own "
              "measurement on the tabulated quantity over the whole table.\n\n";
        md += "| nodes | storage | KiB | table max | radiance max | radiance p99 | ns/lookup | |\n"
              "|---|---|---:|---:|---:|---:|---:|---|\n";
        for (const auto &r : res)
            md += "| " + counts_text(r.counts) + " | " + to_string(r.storage) + " | " +
                  fmt("%.1f", static_cast<double>(r.bytes) / 1024.0) + " | " + fmt("%.2e", r.table_max_rel) + " | " +
                  fmt("%.2e", r.radiance.max) + " | " + fmt("%.2e", r.radiance.p99) + " | " + fmt("%.3g", r.ns_per_lookup) +
                  " | " + (r.planned ? "planned" : "") + " |\n";

        md += "\n### Runtime methods\n\n![runtime methods](" + kind + "_methods.svg)\n\n";
        md += "Error: relative to exact quadrature, over the radiance queries above.";
        md += t.kind->methods_note();
        md += "\n\n| method | what | ns/call | median | p90 | p99 | max |\n|---|---|---:|---:|---:|---:|---:|\n";
        for (const auto &r : methods) {
            auto e = [&](double v) { return r.reference ? std::string("reference") : fmt("%.2e", v); };
            md += "| " + r.name + " | " + r.what + " | " + fmt("%.4g", r.ns_per_call) + " | " + e(r.error.median) + " | " +
                  e(r.error.p90) + " | " + e(r.error.p99) + " | " + e(r.error.max) + " |\n";
        }
    }
    write_text(opt.out_dir + "/report.md", md);
    std::cout << "wrote " << opt.out_dir << "/report.md\n";
    return 0;
}

} // namespace

void setup_report(CLI::App &app, int &exit_code, const std::string &command_line) {
    auto opt = std::make_shared<ReportOptions>();
    auto *cmd = app.add_subcommand("report", "What accuracy costs in time: tolerance and resolution ladders and runtime "
                                             "methods for every table a scene calls for (Markdown, CSV, SVG)");
    cmd->add_option("--scene", opt->scene_file, "Scene file (TOML); default: the embedded default scene")
        ->check(CLI::ExistingFile);
    cmd->add_option("--out", opt->out_dir, "Directory for report.md and the CSV and SVG files")
        ->required()
        ->check(non_empty_text("an output directory"));
    cmd->add_option("--device", opt->device, "OpenCL device: P:D index or name substring (env SCATTERLUT_DEVICE)");
    cmd->add_option("--rounds", opt->rounds, "Interleaved timing rounds per measurement (median reported)")
        ->check(integer_number())
        ->check(CLI::Range(1, 100))
        ->capture_default_str();
    cmd->add_option("--queries", opt->queries, "Random radiance queries over the scene's domain per table")
        ->check(integer_number())
        ->check(CLI::Range(100, 1000000))
        ->capture_default_str();
    cmd->callback([opt, &exit_code, &command_line] { exit_code = run_report(*opt, command_line); });
}

} // namespace scatterlut
