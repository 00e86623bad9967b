#include "validate.hpp"

#include "cli_checks.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <limits>
#include <memory>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "exit_codes.hpp"
#include "kinds/table_kind.hpp"
#include "output_set.hpp"
#include "scatterlut/io.hpp"

namespace scatterlut {
namespace {

// The generator measures with seeds 1 (nodes) and 2 (sampling); validation uses other
// random samples so that it does not merely repeat the generator's own measurement.
constexpr uint64_t kNodeSeed = 0x76616c69646e6f64ull;   // "validnod"
constexpr uint64_t kSampleSeed = 0x76616c6964736d70ull; // "validsmp"

// Node check: the stored (rounded) value differs from the exact one by the integration
// error plus the storage rounding. The exact value comes from a rule independent of the
// generator's: Boost.Math adaptive 61-point Gauss–Kronrod of the physical integral
// (IntegrationReference::IndependentGaussKronrod, reference_quadrature.hpp), not the
// kernels' panel rules. The declared integration_max_rel is a maximum over the
// generator's 400 random nodes; our sample (all corners + other random nodes) can hit a
// node somewhat worse, hence the factor (1 + kNodeMargin). The absolute floor 1e-12
// covers the reference quadrature's own error (~1e-14) for f64 tables whose declared
// errors are at round-off level.
constexpr double kNodeMargin = 1.0;
constexpr double kNodeFloor = 1e-12;
// Sampling check: the declared sampling_max_rel is the maximum over the generator's
// 20000 random points; a different (and smaller) random sample finds a slightly different
// maximum, usually lower but occasionally higher where the worst region is narrow.
// Allow 1.5 × declared + 1e-6 (the 1e-6 keeps near-exact f64 tables from failing on noise).
constexpr double kSamplingFactor = 1.5;
constexpr double kSamplingFloor = 1e-6;

struct ValidateOptions {
    std::vector<std::string> files;
    bool json = false;
    int nodes = 400;
    int points = 4000;
};

struct Check {
    std::string name;
    double measured = 0;
    double limit = 0;
    uint64_t count = 0;
    bool pass = false;
    std::string reference; // what the measured value was checked against
};

struct FileReport {
    std::string path;
    int status = 0; // 0 pass, 1 fail, 2 unreadable/unsupported
    std::string message;
    Table table; // empty when unreadable
    bool loaded = false; // table holds the file's table (false: unreadable or a checksum failure)
    std::vector<Check> checks;
};

std::string axes_text(const Table &t) {
    std::string s;
    for (const auto &a : t.axes) {
        if (!s.empty()) s += " x ";
        s += a.name + "[" + std::to_string(a.map.count) + "]";
    }
    return s;
}

// The nodes to check: every corner of the grid, then random nodes up to `nodes`.
std::vector<NodeIndex> pick_nodes(const Table &t, int nodes) {
    const size_t n_axes = t.axes.size();
    std::vector<NodeIndex> picks;
    for (size_t c = 0; c < (size_t{1} << n_axes); ++c) {
        NodeIndex p{};
        for (size_t a = 0; a < n_axes; ++a) p[a] = (c >> a & 1u) ? static_cast<size_t>(t.axes[a].map.count - 1) : 0;
        picks.push_back(p);
    }
    std::mt19937_64 rng(kNodeSeed);
    while (picks.size() < static_cast<size_t>(nodes)) {
        NodeIndex p{};
        for (size_t a = 0; a < n_axes; ++a)
            p[a] = std::uniform_int_distribution<size_t>(0, static_cast<size_t>(t.axes[a].map.count - 1))(rng);
        picks.push_back(p);
    }
    return picks;
}

FileReport validate_file(const std::string &path, const ValidateOptions &opt) {
    FileReport r;
    r.path = path;
    try {
        r.table = load_table(path);
        r.loaded = true;
    } catch (const ChecksumError &e) {
        r.status = kExitFailure; // read, but corrupt: a checksum failure, not an unreadable file
        r.message = std::string("checksum failure: ") + e.what();
        return r;
    } catch (const LoadError &e) {
        r.status = kExitBadInput;
        r.message = std::string("unreadable or unsupported: ") + e.what();
        return r;
    }
    Table &t = r.table;
    const TableKind *kind = find_table_kind(t.kind);
    if (!kind) {
        r.status = kExitBadInput;
        r.message = "unreadable or unsupported: table kind '" + t.kind + "' is not one validate knows";
        return r;
    }
    // The runtime classes check kind, quantity version, axes and channel.
    std::shared_ptr<const RuntimeSampler> sampler;
    try {
        sampler = kind->runtime().make_sampler(t);
    } catch (const std::invalid_argument &e) {
        r.status = kExitBadInput;
        r.message = std::string("unreadable or unsupported: ") + e.what();
        return r;
    }
    const Accuracy &a = t.accuracy;
    if (!(a.integration_max_rel >= 0) || !(a.storage_max_rel >= 0) || !(a.sampling_max_rel >= 0)) {
        r.status = kExitFailure;
        r.message = "inconsistent: the file does not declare its integration, storage and sampling accuracy";
        return r;
    }

    Check nodes;
    nodes.name = "nodes";
    const auto picks = pick_nodes(t, opt.nodes);
    nodes.count = picks.size();
    nodes.reference = kind->independent_reference();
    nodes.measured = kind->integration_error(*sampler, picks, IntegrationReference::IndependentGaussKronrod);
    nodes.limit = std::max(a.integration_max_rel, a.storage_max_rel) * (1 + kNodeMargin) + a.storage_max_rel + kNodeFloor;
    nodes.pass = nodes.measured <= nodes.limit;
    r.checks.push_back(nodes);

    Check sampling;
    sampling.name = "sampling";
    const SamplingStats s = kind->sampling_error(*sampler, opt.points, kSampleSeed);
    sampling.count = s.points;
    sampling.measured = s.max_rel;
    sampling.limit = kSamplingFactor * a.sampling_max_rel + kSamplingFloor;
    sampling.pass = s.max_rel <= sampling.limit; // false for NaN
    r.checks.push_back(sampling);

    r.status = (nodes.pass && sampling.pass) ? 0 : kExitFailure;
    if (r.status) r.message = "accuracy worse than declared";
    return r;
}

const char *status_name(int status) { return status == 0 ? "PASS" : status == 1 ? "FAIL" : "UNREADABLE"; }

nlohmann::json finite_or_null(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

void print_json(const FileReport &r) {
    nlohmann::json j;
    j["file"] = r.path;
    j["status"] = status_name(r.status);
    j["pass"] = r.status == 0;
    if (!r.message.empty()) j["message"] = r.message;
    if (r.loaded && r.status != kExitBadInput) {
        const Table &t = r.table;
        j["kind"] = t.kind;
        j["storage"] = to_string(t.storage);
        nlohmann::json axes = nlohmann::json::array();
        for (const auto &a : t.axes) axes.push_back({{"name", a.name}, {"count", a.map.count}});
        j["axes"] = axes;
        j["declared"] = {{"integration_max_rel", t.accuracy.integration_max_rel},
                         {"storage_max_rel", t.accuracy.storage_max_rel},
                         {"sampling_max_rel", t.accuracy.sampling_max_rel}};
        nlohmann::json checks = nlohmann::json::object();
        for (const auto &c : r.checks)
        {
            checks[c.name] = {{"measured_max_rel", finite_or_null(c.measured)}, {"limit", c.limit},
                              {"count", c.count}, {"pass", c.pass}};
            if (!c.reference.empty()) checks[c.name]["reference"] = c.reference;
        }
        j["checks"] = checks;
    }
    std::cout << j.dump() << "\n";
}

void print_text(const FileReport &r) {
    std::printf("%s: %s\n", r.path.c_str(), status_name(r.status));
    if (!r.loaded || r.status == kExitBadInput) {
        std::printf("  %s\n", r.message.c_str());
        return;
    }
    const Table &t = r.table;
    const Accuracy &a = t.accuracy;
    std::printf("  kind %s (quantity v%u), %s, axes %s\n", t.kind.c_str(), t.quantity_version, to_string(t.storage),
                axes_text(t).c_str());
    std::printf("  declared: integration %.2e, storage %.2e, sampling %.2e\n", a.integration_max_rel,
                a.storage_max_rel, a.sampling_max_rel);
    for (const auto &c : r.checks) {
        if (c.name == "nodes")
            std::printf("  nodes:    max rel %.2e at %llu nodes (corners + random, %s), limit %.2e  %s\n",
                        c.measured, static_cast<unsigned long long>(c.count), c.reference.c_str(), c.limit,
                        c.pass ? "PASS" : "FAIL");
        else
            std::printf("  sampling: max rel %.2e at %llu off-node points (not the generator's), limit %.2e  %s\n", c.measured,
                        static_cast<unsigned long long>(c.count), c.limit, c.pass ? "PASS" : "FAIL");
    }
    if (r.status != 0 && !r.message.empty()) std::printf("  %s\n", r.message.c_str());
}

int report_file(const FileReport &r, const ValidateOptions &opt) {
    if (!r.loaded || r.status == kExitBadInput) std::cerr << "scatterlut: " << r.message << "\n";
    if (opt.json) print_json(r);
    else print_text(r);
    return r.status;
}

// A directory: the output set its manifest lists (sizes, checksums, no stray table files,
// kinds), then every listed table as validate_file checks a file.
int validate_directory(const std::string &dir, const ValidateOptions &opt) {
    OutputSetCheck set;
    try {
        set = check_output_set(dir);
    } catch (const LoadError &e) {
        std::cerr << "scatterlut: " << e.what() << "\n";
        if (opt.json) std::cout << nlohmann::json({{"directory", dir}, {"status", "UNREADABLE"}, {"pass", false},
                                                   {"message", e.what()}}).dump() << "\n";
        else std::printf("%s: UNREADABLE\n  %s\n", dir.c_str(), e.what());
        return kExitBadInput;
    }
    int worst = set.mismatches.empty() ? 0 : kExitFailure;
    if (opt.json) {
        std::cout << nlohmann::json({{"directory", dir},
                                     {"status", set.mismatches.empty() ? "CONSISTENT" : "MISMATCH"},
                                     {"pass", set.mismatches.empty()},
                                     {"files", set.files.size()},
                                     {"mismatches", set.mismatches}})
                         .dump(-1, ' ', false, nlohmann::json::error_handler_t::replace)
                  << "\n";
    } else {
        std::printf("%s: %s (%zu file(s) listed in %s)\n", dir.c_str(),
                    set.mismatches.empty() ? "one consistent output set" : "MISMATCH: not one run's output set",
                    set.files.size(), kManifestName);
        for (const std::string &m : set.mismatches) std::printf("  %s\n", m.c_str());
    }
    for (const std::string &m : set.mismatches) std::cerr << "scatterlut: " << m << "\n";
    for (const ManifestFile &f : set.files) {
        const std::string path = dir + "/" + f.name;
        if (std::any_of(set.mismatches.begin(), set.mismatches.end(),
                        [&](const std::string &m) { return m.compare(0, path.size() + 1, path + ":") == 0; }))
            continue; // already reported
        // scatterlut reads no KTX2 (written for engines, docs/FORMAT.md §7): its size and
        // checksum above tie it to the set; its values are the set's .slut/.exr tables'.
        if (f.format == "ktx2") continue;
        FileReport r = validate_file(path, opt);
        if (r.loaded && r.table.kind != f.kind) {
            r.status = std::max(r.status, kExitFailure);
            r.message = "kind '" + r.table.kind + "', the manifest says '" + f.kind + "'";
        }
        worst = std::max(worst, report_file(r, opt));
    }
    return worst;
}

int run_validate(const ValidateOptions &opt) {
    int worst = 0;
    for (const auto &path : opt.files) {
        std::error_code ec;
        if (std::filesystem::is_directory(path, ec)) worst = std::max(worst, validate_directory(path, opt));
        else worst = std::max(worst, report_file(validate_file(path, opt), opt));
    }
    return worst;
}

} // namespace

void setup_validate(CLI::App &app, int &exit_code) {
    auto opt = std::make_shared<ValidateOptions>();
    auto *cmd = app.add_subcommand("validate",
                                   "Re-measure table files' accuracy independently and compare with what they declare");
    cmd->add_option("files", opt->files,
                    "Table files (.slut or .exr), or output directories (their manifest.json: one run's set)")
        ->required();
    cmd->add_flag("--json", opt->json, "One JSON object per file on stdout");
    add_integer_option(cmd, "--nodes", opt->nodes, "Nodes re-integrated with a finer rule (corners included)", 200,
                       1000000)
        ->capture_default_str();
    add_integer_option(cmd, "--points", opt->points, "Random off-node points for the sampling error", 2000, 10000000)
        ->capture_default_str();
    cmd->callback([opt, &exit_code] { exit_code = run_validate(*opt); });
}

} // namespace scatterlut
