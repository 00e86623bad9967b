#include "scene_commands.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <optional>
#include <cstring>
#include <stdexcept>

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <nlohmann/json.hpp>

#include "cli_checks.hpp"
#include "opencl_device.hpp"
#include "output_set.hpp"
#include "plan.hpp"
#include "scene.hpp"
#include "text_format.hpp"
#include "scatterlut/io.hpp"
#include "version.hpp"

namespace scatterlut {
namespace {

// Progress on a terminal only; silent when stderr is a pipe or a file.
struct Progress {
    bool enabled = isatty(STDERR_FILENO) != 0;
    void operator()(const std::string &label, double fraction) const {
        if (!enabled) return;
        std::fprintf(stderr, "\r%-60s %3d%%", label.c_str(), static_cast<int>(100.0 * fraction + 0.5));
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    }
};

// What plan and generate share: the scene, the device, the storage and the airlight
// overrides (the historical generate flags).
struct SceneOptions {
    std::string scene_file; // "" = the embedded default scene
    std::string device;
    std::string format, storage; // "" = the scene's [output]
    std::optional<double> u_max, w_min;
    std::optional<int> n_u, n_w;
};

void add_scene_options(CLI::App *cmd, SceneOptions &o) {
    cmd->add_option("--scene", o.scene_file, "Scene file (TOML, docs/SCENES.md); default: the embedded default scene")
        ->check(CLI::ExistingFile);
    cmd->add_option("--device", o.device, "OpenCL device: P:D index or name substring (env SCATTERLUT_DEVICE)");
    cmd->add_option("--format", o.format,
                    "File format, overrides the scene's output.format: bin (.slut), exr, ktx2, both (bin and exr), "
                    "all (bin, exr and ktx2)")
        ->check(CLI::IsMember({"bin", "exr", "ktx2", "both", "all"}));
    cmd->add_option("--storage", o.storage, "Stored precision, overrides output.storage (f16/f32 for EXR, f32/f64 binary)")
        ->check(CLI::IsMember({"f16", "f32", "f64"}));
    cmd->add_option("--u-max", o.u_max, "Airlight table: largest u = sigma_t*D*sin(gamma) (default: from the scene)")
        ->check(finite_number())
        ->check(CLI::Range(1.0, 1e4));
    add_integer_option(cmd, "--n-u", o.n_u, "Airlight table: nodes along u (fixes the resolution instead of searching)",
                       8, 16384);
    add_integer_option(cmd, "--n-w", o.n_w, "Airlight table: nodes along w = pi/2 - v (fixes the resolution)", 8,
                       16384);
    cmd->add_option("--w-min", o.w_min, "Airlight table: smallest w")
        ->check(finite_number())
        ->check(CLI::Range(1e-6, 0.1));
}

Scene load(const SceneOptions &o) { return o.scene_file.empty() ? default_scene() : load_scene_file(o.scene_file); }

ScenePlan make_plan(const SceneOptions &o, Scene scene) {
    if (!o.format.empty()) scene.output.format = o.format;
    if (!o.storage.empty()) scene.output.storage = o.storage;
    if (scene.output.format == "exr" && scene.output.storage == "f64")
        throw std::invalid_argument("--storage f64 needs a binary format (--format bin or both): EXR holds no f64");
    if (scene.output.format == "ktx2" && scene.output.storage == "f64")
        throw std::invalid_argument("--storage f64 needs a binary format (--format bin, both or all): KTX2 output "
                                    "holds no f64");
    Storage storage = Storage::F32;
    storage_from_string(scene.output.storage, &storage);
    return derive_plan(scene, storage, AirlightOverrides{o.u_max, o.w_min, o.n_u, o.n_w});
}

std::string axis_domain(const Axis &a) {
    char buf[160];
    std::snprintf(buf, sizeof buf, "%s in [%.4g, %.4g] (%s, %d nodes)", a.name.c_str(), a.map.min, a.map.max,
                  warp_name(a.map.warp), a.map.count);
    return buf;
}


void print_text(const ScenePlan &plan) {
    const Scene &s = plan.scene;
    std::printf("scene: %s%s(%s), accepted relative error on radiance %.3g, %s\n", s.name.c_str(),
                s.name.empty() ? "" : " ", s.source.c_str(), s.relative_error, to_string(plan.storage));
    size_t total = 0;
    for (const PlannedTable &t : plan.tables) {
        const PlanTrial &c = *t.chosen_trial();
        total += c.bytes;
        std::printf("\n%s: %s, %.1f KiB\n", t.name(), counts_text(c.counts, " x ").c_str(),
                    static_cast<double>(c.bytes) / 1024.0);
        if (t.kind->per_phase()) std::printf("  phase_g = %.15g (Henyey-Greenstein)\n", t.phase_g);
        if (t.kind->per_exponent())
            std::printf("  exponent = %d (%s)\n", t.exponent, t.exponent == 1 ? "diffuse surfaces" : "Phong lobe");
        for (const auto &r : t.requested_by)
            std::printf("  asked for by medium '%s' with light '%s': %s\n", r.medium.c_str(), r.light.c_str(),
                        r.need.c_str());
        for (const auto &a : t.table.axes) std::printf("  axis %s\n", axis_domain(a).c_str());
        for (const auto &n : t.domain_notes) std::printf("  (%s)\n", n.c_str());
        std::printf("  target on the table's quantity: %.3g (%s, the strictest of the media asking)\n", t.target_rel,
                    t.kind->target_reason());
        for (size_t i = 0; i < t.trials.size(); ++i) {
            const PlanTrial &tr = t.trials[i];
            std::printf("  %s trial %zu: %-20s max %.3g, p99 %.3g, integration %.2g, %.2f s\n",
                        static_cast<int>(i) == t.chosen ? "*" : " ", i + 1, counts_text(tr.counts, " x ").c_str(),
                        tr.sampling_max_rel, tr.sampling_p99_rel, tr.integration_max_rel, tr.seconds);
        }
        std::printf("  predicted error (measured, max over %llu random points): %.3g\n",
                    static_cast<unsigned long long>(t.table.accuracy.sampling_points), c.sampling_max_rel);
        std::printf("  %s\n", t.verdict.c_str());
    }
    if (plan.tables.empty()) std::printf("\nno tables\n");
    for (const std::string &n : plan.notes) std::printf("note: %s\n", n.c_str());
    std::printf("\ntotal: %zu table(s), %.1f KiB; the search took %.2f s (generate repeats it, then writes)\n",
                plan.tables.size(), static_cast<double>(total) / 1024.0, plan.search_seconds);
}

nlohmann::json to_json(const ScenePlan &plan) {
    using nlohmann::json;
    json j;
    j["scene"] = {{"name", plan.scene.name}, {"source", plan.scene.source}, {"relative_error", plan.scene.relative_error},
                  {"max_table_MiB", plan.scene.max_table_MiB}};
    j["output"] = {{"directory", plan.scene.output.directory}, {"format", plan.scene.output.format},
                   {"storage", to_string(plan.storage)}};
    j["tables"] = json::array();
    for (const PlannedTable &t : plan.tables) {
        const PlanTrial &c = *t.chosen_trial();
        json e;
        e["kind"] = t.kind->name();
        e["file_stem"] = t.name();
        e["phase_g"] = t.phase_g; // Henyey–Greenstein g of the table (0: isotropic)
        if (t.kind->per_exponent()) e["exponent"] = t.exponent; // surfaces: 1 diffuse, n > 1 Phong
        json req = json::array();
        for (const auto &r : t.requested_by) req.push_back({{"medium", r.medium}, {"light", r.light}, {"need", r.need}});
        e["requested_by"] = req;
        json axes = json::array();
        for (const auto &a : t.table.axes)
            axes.push_back({{"name", a.name}, {"min", a.map.min}, {"max", a.map.max}, {"warp", warp_name(a.map.warp)},
                            {"count", a.map.count}});
        e["axes"] = axes;
        e["domain_notes"] = t.domain_notes;
        e["bytes"] = c.bytes;
        e["target_rel"] = t.target_rel;
        e["predicted_max_rel"] = c.sampling_max_rel;
        e["predicted_p99_rel"] = c.sampling_p99_rel;
        e["integration_max_rel"] = c.integration_max_rel;
        e["reached"] = t.reached;
        e["fixed_resolution"] = t.fixed_resolution;
        e["verdict"] = t.verdict;
        if (t.spot_max_rel >= 0) e["spot_max_rel"] = t.spot_max_rel; // the spot lights' check (spot_measure.hpp)
        e["seconds"] = c.seconds; // the chosen trial alone
        double search = 0;
        for (const PlanTrial &tr : t.trials) search += tr.seconds;
        e["estimated_seconds"] = search; // what generate spends on this table (it repeats the search)
        json trials = json::array();
        for (const PlanTrial &tr : t.trials)
            trials.push_back({{"counts", tr.counts}, {"bytes", tr.bytes}, {"sampling_max_rel", tr.sampling_max_rel},
                              {"sampling_p99_rel", tr.sampling_p99_rel}, {"integration_max_rel", tr.integration_max_rel},
                              {"storage_max_rel", tr.storage_max_rel}, {"seconds", tr.seconds}});
        e["trials"] = trials;
        j["tables"].push_back(e);
    }
    j["notes"] = plan.notes;
    j["search_seconds"] = plan.search_seconds;
    return j;
}

// The resolution search of every table on the device selected by `selector`.
void resolve_with(ScenePlan &plan, Device &device, const std::string &command_line) {
    std::cerr << "device: " << device.info().describe() << "\n";
    Provenance provenance;
    provenance.generator_version = generator_version();
    provenance.command_line = command_line;
    provenance.device = device.info().describe();
    const Progress progress;
    // Off a terminal no progress is shown, and none is asked for (one kernel launch, not slices).
    std::function<void(const std::string &, double)> on_progress;
    if (progress.enabled) on_progress = [&](const std::string &label, double f) { progress(label, f); };
    resolve_plan(plan, device, provenance, on_progress);
}

void resolve_on_device(ScenePlan &plan, const std::string &selector, const std::string &command_line) {
    if (plan.tables.empty()) return; // nothing to generate: no device needed
    Device device(selector);
    resolve_with(plan, device, command_line);
}

// ---------------------------------------------------------------- plan
struct PlanOptions {
    SceneOptions scene;
    bool json = false;
};

int run_plan(const PlanOptions &opt) {
    ScenePlan plan = make_plan(opt.scene, load(opt.scene)); // a bad scene throws here, before any work
    resolve_on_device(plan, opt.scene.device, "");
    if (opt.json) std::cout << to_json(plan).dump(2) << "\n";
    else print_text(plan);
    return 0;
}

// ---------------------------------------------------------------- generate
struct GenerateOptions {
    SceneOptions scene;
    std::string out_dir; // "" = the scene's output.directory
    bool fail_on_miss = false; // exit 1 when a table misses the scene's target (files still written)
};

// The output directory, created if missing; a path through a file, or one that cannot be
// created, is a usage error naming the option and the component in the way.
void prepare_output_directory(const std::string &out_dir) {
    namespace fs = std::filesystem;
    std::error_code ec;
    // Every leading part as the user wrote it ("a/b" of "a/b/c"), then the whole path.
    for (size_t end = out_dir.find('/', 1);; end = out_dir.find('/', end + 1)) {
        const std::string prefix = out_dir.substr(0, end);
        const fs::file_status st = fs::status(prefix, ec);
        if (fs::exists(st) && !fs::is_directory(st))
            throw std::invalid_argument("--out '" + out_dir + "': '" + prefix +
                                        "' exists and is not a directory (expected an output directory)");
        if (end == std::string::npos) break;
    }
    fs::create_directories(out_dir, ec);
    if (ec) throw std::invalid_argument("--out '" + out_dir + "': cannot create the output directory: " + ec.message());
}

// An exclusive, non-blocking flock on the output directory itself for the whole run: a
// second generate into the same directory is refused at once. No lock file: the directory
// holds only the run's files, and the kernel releases the lock when this process ends,
// however it ends.
class OutputLock {
public:
    explicit OutputLock(const std::string &out_dir) {
        fd_ = ::open(out_dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
        if (fd_ < 0)
            throw std::invalid_argument("--out '" + out_dir + "': cannot open the output directory: " +
                                        std::strerror(errno));
        if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
            const int err = errno;
            ::close(fd_);
            if (err == EWOULDBLOCK)
                throw std::runtime_error("another scatterlut run is writing '" + out_dir +
                                         "' (it holds the directory's lock); nothing written");
            throw std::runtime_error(out_dir + ": cannot lock the output directory: " + std::strerror(err));
        }
    }
    ~OutputLock() { ::close(fd_); }
    OutputLock(const OutputLock &) = delete;
    OutputLock &operator=(const OutputLock &) = delete;

private:
    int fd_ = -1;
};

// The files of one run: every table encoded in memory, then each written to a hidden
// temporary, the manifest last, and only then all renamed into place (AtomicFileSet).
void write_output_set(const ScenePlan &plan, const std::string &out_dir, const std::string &command_line) {
    const std::string &format = plan.scene.output.format;
    struct File {
        std::string name, kind, format;
        std::vector<uint8_t> bytes;
    };
    std::vector<File> files;
    for (const PlannedTable &t : plan.tables) {
        if (format == "bin" || format == "both" || format == "all")
            files.push_back({std::string(t.name()) + ".slut", t.kind->name(), "bin", encode_binary(t.table)});
        if (format == "exr" || format == "both" || format == "all") {
            if (t.table.storage == Storage::F64) std::cout << t.name() << ": no EXR (f64 storage is binary only)\n";
            else files.push_back({std::string(t.name()) + ".exr", t.kind->name(), "exr", encode_exr(t.table)});
        }
        if (format == "ktx2" || format == "all") {
            if (t.table.storage == Storage::F64) std::cout << t.name() << ": no KTX2 (f64 storage is binary only)\n";
            else files.push_back({std::string(t.name()) + ".ktx2", t.kind->name(), "ktx2", encode_ktx2(t.table)});
        }
    }
    nlohmann::json manifest;
    manifest["manifest"] = kManifestMagic;
    manifest["manifest_version"] = 1;
    manifest["generator_version"] = generator_version();
    manifest["command_line"] = command_line;
    manifest["scene"] = {{"source", plan.scene.source}, {"text", plan.scene.text}};
    manifest["storage"] = to_string(plan.storage);
    nlohmann::json list = nlohmann::json::array();
    for (const File &f : files)
        list.push_back({{"name", f.name}, {"kind", f.kind}, {"format", f.format}, {"bytes", f.bytes.size()},
                        {"fnv1a64", hex64(fnv1a64(f.bytes.data(), f.bytes.size()))}});
    manifest["files"] = list;
    const std::string text = manifest.dump(2, ' ', false, nlohmann::json::error_handler_t::replace) + "\n";

    AtomicFileSet set;
    for (const File &f : files) set.add(out_dir + "/" + f.name, f.bytes);
    set.add(out_dir + "/" + kManifestName, std::vector<uint8_t>(text.begin(), text.end()));
    set.commit();
    for (const File &f : files) std::cout << "  wrote " << out_dir << "/" << f.name << "\n";
    std::cout << "  wrote " << out_dir << "/" << kManifestName << " (" << files.size() << " file(s) of this run)\n";
}

int run_generate(const GenerateOptions &opt, const std::string &command_line) {
    ScenePlan plan = make_plan(opt.scene, load(opt.scene));
    const std::string out_dir = opt.out_dir.empty() ? plan.scene.output.directory : opt.out_dir;
    if (plan.tables.empty()) { // nothing to generate: nothing written, not even the directory
        print_text(plan);
        return 0;
    }
    Device device(opt.scene.device); // a --device naming no device is refused before anything is created
    prepare_output_directory(out_dir);
    const OutputLock lock(out_dir); // held until every file of this run is in place
    resolve_with(plan, device, command_line);
    print_text(plan);
    // Only now, with every table generated and measured, is anything written: all files of
    // the run to temporaries, then renamed together (an error or a signal before leaves the
    // previous set whole).
    write_output_set(plan, out_dir, command_line);
    int missed = 0;
    for (const PlannedTable &t : plan.tables) {
        if (!t.reached) {
            std::cerr << "scatterlut: " << (opt.fail_on_miss ? "error: " : "warning: ") << t.name() << ": " << t.verdict
                      << "\n";
            ++missed;
        }
    }
    // The tables are written either way: each declares the error it measured.
    return (opt.fail_on_miss && missed > 0) ? 1 : 0;
}

} // namespace

void setup_plan(CLI::App &app, int &exit_code) {
    auto opt = std::make_shared<PlanOptions>();
    auto *cmd = app.add_subcommand(
        "plan", "Which tables a scene calls for and why, their domains, resolutions (searched on the device), "
                "sizes, predicted errors and time; writes nothing");
    add_scene_options(cmd, opt->scene);
    cmd->add_flag("--json", opt->json, "One JSON object on stdout (\"tables\": one entry per table)");
    cmd->callback([opt, &exit_code] { exit_code = run_plan(*opt); });
}

void setup_generate(CLI::App &app, int &exit_code, const std::string &command_line) {
    auto opt = std::make_shared<GenerateOptions>();
    auto *cmd = app.add_subcommand("generate", "Carry out a scene's plan: generate its tables on the OpenCL device and write them");
    add_scene_options(cmd, opt->scene);
    cmd->add_option("--out", opt->out_dir, "Output directory (default: the scene's output.directory)")
        ->check(non_empty_text("an output directory"));
    cmd->add_flag("--fail-on-miss", opt->fail_on_miss,
                  "Exit 1 if a table misses the scene's accuracy target (for CI; the tables are still written, "
                  "each with its measured error)");
    cmd->callback([opt, &exit_code, &command_line] { exit_code = run_generate(*opt, command_line); });
}

} // namespace scatterlut
