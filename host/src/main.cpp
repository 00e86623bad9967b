// scatterlut — the command line: a thin layer over scatterlut_core.
// One options struct per subcommand: setup_<cmd> binds it, run_<cmd> does the work.
#include <chrono>
#include <csignal>
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
#include "exit_codes.hpp"
#include "inspect.hpp"
#include "validate.hpp"
#include "report.hpp"
#include "scene_commands.hpp"
#include "opencl_device.hpp"
#include "scatterlut/io.hpp"
#include "version.hpp"

namespace scatterlut {
namespace {

std::string g_command_line; // recorded in every table

std::string shell_quote(const std::string &arg) {
    if (!arg.empty() && arg.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789-_./=:,+") ==
                            std::string::npos)
        return arg;
    std::string out = "'";
    for (char c : arg) out += (c == '\'') ? std::string("'\\''") : std::string(1, c);
    return out + "'";
}

// A SIGINT, SIGTERM or SIGHUP during a write removes that write's hidden temporary file
// (the final names keep their previous complete files), then terminates as the signal would.
extern "C" void on_terminating_signal(int sig) {
    remove_temporaries_in_progress();
    std::signal(sig, SIG_DFL);
    std::raise(sig);
}

void install_signal_handlers() {
    struct sigaction action {};
    action.sa_handler = on_terminating_signal;
    sigemptyset(&action.sa_mask);
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaction(sig, &action, nullptr);
}

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

// ---------------------------------------------------------------- plan, generate: scene_commands.cpp

// ---------------------------------------------------------------- eval
struct EvalOptions {
    std::vector<std::string> tables;
};

int run_eval(const EvalOptions &opt) {
    EvalTables tables;
    for (const auto &path : opt.tables) tables.add(path, load_table(path));
    eval_stream(std::cin, std::cout, tables);
    return 0; // bad lines are answered with {"error": …}, not an exit code
}

void setup_eval(CLI::App &app, int &exit_code) {
    auto opt = std::make_shared<EvalOptions>();
    auto *cmd = app.add_subcommand("eval", "JSON lines on stdin -> one JSON line per query on stdout: exact and table");
    cmd->add_option("--table", opt->tables, "A table to sample (repeatable)")->check(CLI::ExistingFile);
    cmd->callback([opt, &exit_code] { exit_code = run_eval(*opt); });
}

// The exit code of an error that ends a command: bad input (an unreadable table, an invalid
// argument, no such device) or a failure (a checksum mismatch, a device or OpenCL error, any
// other).
int error_exit_code(const std::exception &e) {
    if (dynamic_cast<const ChecksumError *>(&e)) return kExitFailure; // a LoadError, but the file's content is wrong
    const bool bad_input = dynamic_cast<const LoadError *>(&e) || dynamic_cast<const std::invalid_argument *>(&e) ||
                           dynamic_cast<const DeviceSelectionError *>(&e);
    return bad_input ? kExitBadInput : kExitFailure;
}

// Its message: an OpenCL error names its code and the call.
std::string error_text(const std::exception &e) {
    if (const auto *cl_error = dynamic_cast<const cl::Error *>(&e))
        return "OpenCL error " + std::to_string(cl_error->err()) + " in " + cl_error->what();
    return e.what();
}

} // namespace
} // namespace scatterlut

int main(int argc, char **argv) {
    using namespace scatterlut;
    install_signal_handlers();
    for (int i = 0; i < argc; ++i) g_command_line += (i ? " " : "") + shell_quote(argv[i]);

    CLI::App app{"scatterlut: lookup tables for analytic single scattering in participating media"};
    app.set_version_flag("--version", generator_version());
    app.require_subcommand(1);
    int exit_code = 0;
    setup_devices(app, exit_code);
    setup_plan(app, exit_code);
    setup_generate(app, exit_code, g_command_line);
    setup_eval(app, exit_code);
    setup_validate(app, exit_code);
    setup_inspect(app, exit_code);
    setup_report(app, exit_code, g_command_line);
    try {
        app.parse(argc, argv);
    } catch (const CLI::ParseError &e) {
        // A first word that is no subcommand: say so plainly (CLI11 would only list it as extra).
        if (argc > 1 && argv[1][0] != '-' && app.get_subcommands().empty()) {
            std::cerr << "scatterlut: unknown subcommand '" << argv[1]
                      << "' (expected devices, plan, generate, eval, validate, inspect or report; see --help)\n";
            return kExitBadInput;
        }
        return app.exit(e) == 0 ? 0 : kExitBadInput;
    } catch (const std::exception &e) {
        std::cerr << "scatterlut: " << error_text(e) << "\n";
        return error_exit_code(e);
    }
    return exit_code;
}
