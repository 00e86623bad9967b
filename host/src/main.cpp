// scatterlut — the command line: a thin layer over scatterlut_core.
// One options struct per subcommand: setup_<cmd> binds it, run_<cmd> does the work.
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <memory>
#include <sstream>
#include <string>
#include <vector>

#include <unistd.h>

#include <CLI/CLI.hpp>

#include "eval.hpp"
#include "inspect.hpp"
#include "validate.hpp"
#include "generate_airlight.hpp"
#include "generate_nearlight.hpp"
#include "opencl_device.hpp"
#include "scatterlut/io.hpp"
#include "version.hpp"

namespace scatterlut {
namespace {

// Exit codes: 0 success, 1 failure (device, accuracy), 2 bad input (arguments, files).
constexpr int kExitFailure = 1;
constexpr int kExitBadInput = 2;

std::string g_command_line; // recorded in every table

std::string shell_quote(const std::string &arg) {
    if (!arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=:,+") ==
                            std::string::npos)
        return arg;
    std::string out = "'";
    for (char c : arg) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// Progress on a terminal only; silent when stderr is a pipe or a file.
struct Progress {
    bool enabled = isatty(STDERR_FILENO) != 0;
    std::string label;
    void operator()(double fraction) const {
        if (!enabled) return;
        std::fprintf(stderr, "\r%s %3d%%", label.c_str(), static_cast<int>(100.0 * fraction + 0.5));
        if (fraction >= 1.0) std::fprintf(stderr, "\n");
        std::fflush(stderr);
    }
};

// ---------------------------------------------------------------- devices
struct DevicesOptions {};

int run_devices(const DevicesOptions &) {
    const auto devices = list_devices();
    if (devices.empty()) {
        std::cerr << "scatterlut: no OpenCL platform or device found (install pocl-opencl-icd for the CPU)\n";
        return kExitFailure;
    }
    for (const auto &d : devices) {
        std::cout << d.platform_index << ":" << d.device_index << "  " << d.type << "  " << d.platform_name << " / "
                  << d.device_name << "\n      " << d.device_version << ", driver " << d.driver_version << ", "
                  << d.compute_units << " compute units, fp64: " << (d.fp64 ? "yes" : "NO (unusable)") << "\n";
    }
    return 0;
}

void setup_devices(CLI::App &app, int &exit_code) {
    auto opt = std::make_shared<DevicesOptions>();
    auto *cmd = app.add_subcommand("devices", "List OpenCL platforms and devices (select one with --device P:D)");
    cmd->callback([opt, &exit_code] { exit_code = run_devices(*opt); });
}

// ---------------------------------------------------------------- generate
struct GenerateOptions {
    std::string out_dir = "out";
    std::string format = "both";
    std::string storage = "f32";
    std::string device;
    AirlightPlan airlight;
};

void write_table(const Table &t, const std::string &out_dir, const std::string &stem, const std::string &format) {
    std::filesystem::create_directories(out_dir);
    if (format == "bin" || format == "both") {
        const std::string path = out_dir + "/" + stem + ".slut";
        save_binary(t, path);
        std::cout << "  wrote " << path << "\n";
    }
    if (format == "exr" || format == "both") {
        if (t.storage == Storage::F64) {
            std::cout << "  (no EXR: f64 storage is binary only)\n";
        } else {
            const std::string path = out_dir + "/" + stem + ".exr";
            save_exr(t, path);
            std::cout << "  wrote " << path << "\n";
        }
    }
}

int run_generate(const GenerateOptions &opt) {
    Device device(opt.device);
    Provenance provenance;
    provenance.generator_version = generator_version();
    provenance.command_line = g_command_line;
    provenance.device = device.info().describe();

    Storage storage = Storage::F32;
    storage_from_string(opt.storage, &storage);
    std::cout << "device: " << device.info().describe() << "\n";

    auto report = [&](const Table &table, const std::string &stem, const std::string &shape, double seconds) {
        const auto &a = table.accuracy;
        std::printf("%s: %s, %s, %.1f KiB, %.2f s (integration + accuracy measurement)\n", stem.c_str(),
                    shape.c_str(), to_string(table.storage),
                    static_cast<double>(table.node_count() * storage_bytes(table.storage)) / 1024.0, seconds);
        std::printf("  integration max rel %.2e; storage rounding max rel %.2e\n", a.integration_max_rel,
                    a.storage_max_rel);
        std::printf("  sampling: max rel %.2e, p99 %.2e, median %.2e over %llu points (%s)\n", a.sampling_max_rel,
                    a.sampling_p99_rel, a.sampling_median_rel, static_cast<unsigned long long>(a.sampling_points),
                    a.sampling_domain.c_str());
        write_table(table, opt.out_dir, stem, opt.format);
    };
    auto seconds_since = [](std::chrono::steady_clock::time_point t0) {
        return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    };

    AirlightPlan air = opt.airlight;
    air.storage = storage;
    auto start = std::chrono::steady_clock::now();
    const Table f = generate_airlight_table(device, air, provenance, Progress{isatty(STDERR_FILENO) != 0, "airlight_F"});
    report(f, "airlight_F", std::to_string(air.n_u) + " x " + std::to_string(air.n_w) + " (u x w)", seconds_since(start));

    for (bool finite : {false, true}) {
        NearLightPlan nl = default_near_light_plan(finite);
        nl.storage = storage;
        const std::string stem = finite ? "near_light_E4" : "near_light_E3";
        start = std::chrono::steady_clock::now();
        const Table e = generate_nearlight_table(device, nl, provenance, Progress{isatty(STDERR_FILENO) != 0, stem});
        std::string shape = std::to_string(nl.n_T) + " x " + std::to_string(nl.n_g) + " x " + std::to_string(nl.n_r);
        shape += finite ? " x " + std::to_string(nl.n_S) + " (T x g x r x q)" : " (T x g x r)";
        report(e, stem, shape, seconds_since(start));
    }
    return 0;
}

void setup_generate(CLI::App &app, int &exit_code) {
    auto opt = std::make_shared<GenerateOptions>();
    auto *cmd = app.add_subcommand("generate", "Generate tables on the OpenCL device and write them");
    cmd->add_option("--out", opt->out_dir, "Output directory")->capture_default_str();
    cmd->add_option("--format", opt->format, "File format")->check(CLI::IsMember({"bin", "exr", "both"}))->capture_default_str();
    cmd->add_option("--storage", opt->storage, "Stored precision (f16/f32 for EXR, f32/f64 for binary)")
        ->check(CLI::IsMember({"f16", "f32", "f64"}))
        ->capture_default_str();
    cmd->add_option("--device", opt->device, "OpenCL device: P:D index or name substring (env SCATTERLUT_DEVICE)");
    cmd->add_option("--u-max", opt->airlight.u_max, "Airlight table: largest u = sigma_t*D*sin(gamma)")
        ->check(CLI::Range(1.0, 1e4))->capture_default_str();
    cmd->add_option("--n-u", opt->airlight.n_u, "Airlight table: nodes along u")->check(CLI::Range(8, 16384))->capture_default_str();
    cmd->add_option("--n-w", opt->airlight.n_w, "Airlight table: nodes along w = pi/2 - v")->check(CLI::Range(8, 16384))->capture_default_str();
    cmd->add_option("--w-min", opt->airlight.w_min, "Airlight table: smallest w")->check(CLI::Range(1e-6, 0.1))->capture_default_str();
    cmd->callback([opt, &exit_code] { exit_code = run_generate(*opt); });
}

// ---------------------------------------------------------------- eval
struct EvalOptions {
    std::vector<std::string> tables;
};

int run_eval(const EvalOptions &opt) {
    EvalTables tables;
    for (const auto &path : opt.tables) {
        Table t = load_table(path);
        if (t.kind == kKindAirlightF) tables.airlight.emplace_back(std::move(t));
        else if (t.kind == kKindNearLightE3 || t.kind == kKindNearLightE4) tables.near_light.emplace_back(std::move(t));
        else throw LoadError(path + ": table kind '" + t.kind + "' is not one eval knows");
    }
    eval_stream(std::cin, std::cout, tables);
    return 0; // bad lines are answered with {"error": …}, not an exit code
}

void setup_eval(CLI::App &app, int &exit_code) {
    auto opt = std::make_shared<EvalOptions>();
    auto *cmd = app.add_subcommand("eval", "JSON lines on stdin -> one JSON line per query on stdout: exact and table");
    cmd->add_option("--table", opt->tables, "A table to sample (repeatable)")->check(CLI::ExistingFile);
    cmd->callback([opt, &exit_code] { exit_code = run_eval(*opt); });
}

} // namespace
} // namespace scatterlut

int main(int argc, char **argv) {
    using namespace scatterlut;
    for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + shell_quote(argv[i]);

    CLI::App app{"scatterlut: lookup tables for analytic single scattering in participating media"};
    app.set_version_flag("--version", generator_version());
    app.require_subcommand(1);
    int exit_code = 0;
    setup_devices(app, exit_code);
    setup_generate(app, exit_code);
    setup_eval(app, exit_code);
    setup_validate(app, exit_code);
    setup_inspect(app, exit_code);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        return app.exit(e) == 0 ? 0 : kExitBadInput;
    } catch (const LoadError &e) {
        std::cerr << "scatterlut: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const std::invalid_argument &e) {
        std::cerr << "scatterlut: " << e.what() << "\n";
        return kExitBadInput;
    } catch (const DeviceError &e) {
        std::cerr << "scatterlut: " << e.what() << "\n";
        return kExitFailure;
    } catch (const cl::Error &e) {
        std::cerr << "scatterlut: OpenCL error " << e.err() << " in " << e.what() << "\n";
        return kExitFailure;
    } catch (const std::exception &e) {
        std::cerr << "scatterlut: " << e.what() << "\n";
        return kExitFailure;
    }
    return exit_code;
}
