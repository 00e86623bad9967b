#include "inspect.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <iostream>
#include <limits>
#include <memory>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "png_writer.hpp"
#include "preview.hpp"
#include "scatterlut/io.hpp"
#include "scatterlut/sampler.hpp"

namespace scatterlut {
namespace {

struct InspectOptions {
    std::string file;
    bool json = false;
    std::string preview_png; // "" = no picture
    PreviewRequest preview;
};

struct Range {
    double min = std::numeric_limits<double>::infinity();
    double max = -std::numeric_limits<double>::infinity();
};

// Decoded (quantity, not stored encoding) range of each channel.
std::vector<Range> channel_ranges(const Table &t) {
    std::vector<Range> out(t.channels.size());
    const size_t nc = t.channels.size();
    for (size_t i = 0; i < t.values.size(); ++i) {
        const double q = decode(t.channels[i % nc].encoding, t.values[i]);
        Range &r = out[i % nc];
        r.min = std::min(r.min, q);
        r.max = std::max(r.max, q);
    }
    return out;
}

// The file's own format version, for a file the loader has already accepted: the binary
// preamble (magic, u32 major, u32 minor, little-endian), or the EXR attributes
// scatterlut.format_major/minor (int), found by walking the EXR attribute list
// (name\0 type\0 i32 size value …, \0 after the 8-byte preamble).
std::string file_format_version(const std::string &path) {
    std::ifstream in(path, std::ios::binary);
    const std::vector<unsigned char> b((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    auto u32 = [&](size_t o) {
        return static_cast<uint32_t>(b[o]) | static_cast<uint32_t>(b[o + 1]) << 8 |
               static_cast<uint32_t>(b[o + 2]) << 16 | static_cast<uint32_t>(b[o + 3]) << 24;
    };
    if (b.size() >= 16 && std::memcmp(b.data(), "SLUTTBL\0", 8) == 0)
        return std::to_string(u32(8)) + "." + std::to_string(u32(12)) + " (binary)";
    long major = -1, minor = -1;
    for (size_t pos = 8; pos < b.size() && b[pos] != 0;) {
        const void *name_end = std::memchr(&b[pos], 0, b.size() - pos);
        if (!name_end) break;
        const std::string name(reinterpret_cast<const char *>(&b[pos]));
        pos += name.size() + 1;
        const void *type_end = pos < b.size() ? std::memchr(&b[pos], 0, b.size() - pos) : nullptr;
        if (!type_end) break;
        const std::string type(reinterpret_cast<const char *>(&b[pos]));
        pos += type.size() + 1;
        if (b.size() - pos < 4) break;
        const size_t size = u32(pos);
        pos += 4;
        if (size > b.size() - pos) break;
        if (type == "int" && size == 4 && name == "scatterlut.format_major") major = static_cast<int32_t>(u32(pos));
        if (type == "int" && size == 4 && name == "scatterlut.format_minor") minor = static_cast<int32_t>(u32(pos));
        pos += size;
    }
    if (major < 0 || minor < 0) return "unknown (OpenEXR)";
    return std::to_string(major) + "." + std::to_string(minor) + " (OpenEXR)";
}

nlohmann::json num(double x) { return std::isfinite(x) ? nlohmann::json(x) : nlohmann::json(nullptr); }

// A negative declared accuracy means "not measured".
nlohmann::json declared(double x) { return x >= 0 ? num(x) : nlohmann::json(nullptr); }

// Renders the picture, writes it atomically and describes it (for --json).
nlohmann::json write_preview(const InspectOptions &opt, const Table &t) {
    PreviewRequest req = opt.preview;
    req.title = std::filesystem::path(opt.file).filename().string();
    const Preview p = render_preview(t, req); // std::invalid_argument → main → exit 2
    write_file_atomic(opt.preview_png, png::encode_rgb8(p.image.rgb, p.image.width, p.image.height));
    nlohmann::json slice = nlohmann::json::array();
    for (const SliceAxis &s : p.slice)
        slice.push_back({{"axis", t.axes[s.axis].name}, {"value", s.param},
                         {"node", s.node >= 0 ? nlohmann::json(s.node) : nlohmann::json(nullptr)}});
    return {{"file", opt.preview_png},
            {"width", p.image.width},
            {"height", p.image.height},
            {"channel", t.channels[p.channel].name},
            {"x_axis", t.axes[p.x_axis].name},
            {"y_axis", p.y_axis >= 0 ? nlohmann::json(t.axes[static_cast<size_t>(p.y_axis)].name) : nlohmann::json(nullptr)},
            {"slice", slice},
            {"slice_text", p.slice_text},
            {"plot", {{"x", p.plot_x}, {"y", p.plot_y}, {"width", p.plot_w}, {"height", p.plot_h}}},
            {"stored_value_range", {p.value_lo, p.value_hi}}};
}

void print_json(const InspectOptions &opt, const Table &t, const nlohmann::json &preview) {
    nlohmann::json j;
    j["file"] = opt.file;
    j["format_version"] = file_format_version(opt.file);
    j["kind"] = t.kind;
    j["quantity_version"] = t.quantity_version;
    j["storage"] = to_string(t.storage);
    j["nodes"] = t.node_count();
    nlohmann::json axes = nlohmann::json::array();
    for (const auto &a : t.axes)
        axes.push_back({{"name", a.name}, {"meaning", a.meaning}, {"min", num(a.map.min)}, {"max", num(a.map.max)},
                        {"warp", warp_name(a.map.warp)}, {"scale", a.map.scale}, {"count", a.map.count}});
    j["axes"] = axes;
    const auto ranges = channel_ranges(t);
    nlohmann::json channels = nlohmann::json::array();
    for (size_t c = 0; c < t.channels.size(); ++c)
        channels.push_back({{"name", t.channels[c].name}, {"meaning", t.channels[c].meaning},
                            {"encoding", to_string(t.channels[c].encoding)},
                            {"decoded_min", num(ranges[c].min)}, {"decoded_max", num(ranges[c].max)}});
    j["channels"] = channels;
    const Accuracy &a = t.accuracy;
    j["accuracy"] = {{"integration_max_rel", declared(a.integration_max_rel)},
                     {"storage_max_rel", declared(a.storage_max_rel)},
                     {"sampling_max_rel", declared(a.sampling_max_rel)},
                     {"sampling_p99_rel", declared(a.sampling_p99_rel)},
                     {"sampling_median_rel", declared(a.sampling_median_rel)},
                     {"sampling_points", a.sampling_points},
                     {"sampling_domain", a.sampling_domain}};
    const Provenance &p = t.provenance;
    j["provenance"] = {{"generator_version", p.generator_version}, {"command_line", p.command_line},
                       {"device", p.device}, {"created_by", p.created_by}, {"scene_bytes", p.scene.size()}};
    j["extra"] = t.extra;
    if (!preview.is_null()) j["preview"] = preview;
    std::cout << j.dump() << "\n";
}

void print_text(const InspectOptions &opt, const Table &t, const nlohmann::json &preview) {
    std::printf("%s\n", opt.file.c_str());
    const std::string version = file_format_version(opt.file);
    if (version.find("OpenEXR") != std::string::npos)
        std::printf("  format version  %s, read by a %u.%u EXR reader (and 1.x)\n", version.c_str(), kExrFormatMajor,
                    kExrFormatMinor);
    else
        std::printf("  format version  %s, read by a %u.%u reader\n", version.c_str(), kFormatMajor, kFormatMinor);
    std::printf("  kind            %s (quantity version %u)\n", t.kind.c_str(), t.quantity_version);
    std::printf("  storage         %s, %zu nodes\n", to_string(t.storage), t.node_count());
    std::printf("  axes (axis 0 varies fastest):\n");
    for (const auto &a : t.axes)
        std::printf("    %-4s [%.6g, %.6g]  warp %s, scale %g, %d nodes  -- %s\n", a.name.c_str(), a.map.min,
                    a.map.max, warp_name(a.map.warp), a.map.scale, a.map.count, a.meaning.c_str());
    std::printf("  channels:\n");
    const auto ranges = channel_ranges(t);
    for (size_t c = 0; c < t.channels.size(); ++c)
        std::printf("    %-6s encoding %s, decoded range [%.6g, %.6g]  -- %s\n", t.channels[c].name.c_str(),
                    to_string(t.channels[c].encoding), ranges[c].min, ranges[c].max, t.channels[c].meaning.c_str());
    const Accuracy &a = t.accuracy;
    std::printf("  declared accuracy (relative, on the quantity):\n");
    std::printf("    integration max %.3e, storage rounding max %.3e\n", a.integration_max_rel, a.storage_max_rel);
    std::printf("    sampling max %.3e, p99 %.3e, median %.3e over %llu points (%s)\n", a.sampling_max_rel,
                a.sampling_p99_rel, a.sampling_median_rel, static_cast<unsigned long long>(a.sampling_points),
                a.sampling_domain.c_str());
    const Provenance &p = t.provenance;
    std::printf("  provenance:\n");
    std::printf("    generator     %s (created by %s)\n", p.generator_version.c_str(), p.created_by.c_str());
    std::printf("    command line  %s\n", p.command_line.c_str());
    std::printf("    device        %s\n", p.device.c_str());
    std::printf("    scene         %s\n", p.scene.empty() ? "(none)" : (std::to_string(p.scene.size()) + " bytes").c_str());
    for (const auto &[k, v] : t.extra) std::printf("    %s = %s\n", k.c_str(), v.c_str());
    if (!preview.is_null())
        std::printf("  preview         %s (%d x %d px): channel %s over %s, %s\n", opt.preview_png.c_str(),
                    preview["width"].get<int>(), preview["height"].get<int>(),
                    preview["channel"].get<std::string>().c_str(),
                    (preview["x_axis"].get<std::string>() +
                     (preview["y_axis"].is_null() ? "" : " x " + preview["y_axis"].get<std::string>()))
                        .c_str(),
                    preview["slice_text"].get<std::string>().c_str());
}

int run_inspect(const InspectOptions &opt) {
    const Table t = load_table(opt.file); // LoadError → main → exit 2
    const nlohmann::json preview = opt.preview_png.empty() ? nlohmann::json() : write_preview(opt, t);
    if (opt.json) print_json(opt, t, preview);
    else print_text(opt, t, preview);
    return 0;
}

} // namespace

void setup_inspect(CLI::App &app, int &exit_code) {
    auto opt = std::make_shared<InspectOptions>();
    auto *cmd = app.add_subcommand("inspect", "Print a table file's metadata, axes, channels, accuracy and provenance");
    cmd->add_option("file", opt->file, "Table file (.slut or .exr)")->required();
    cmd->add_flag("--json", opt->json, "One JSON object on stdout");
    auto *png = cmd->add_option("--preview", opt->preview_png,
                                "Write a false-colour PNG of one channel over two axes (a 2-D table or a slice)");
    cmd->add_option("--channel", opt->preview.channel, "Channel to show (default: the first)")->needs(png);
    cmd->add_option("--axes", opt->preview.plot_axes, "Axes to plot as X,Y by name (default: axes 0 and 1)")
        ->delimiter(',')
        ->expected(1, 2)
        ->needs(png);
    cmd->add_option("--slice", opt->preview.slice,
                    "Where to cut the other axes: NAME=VALUE (parameter units) or NAME=#NODE, comma-separated; "
                    "default: each at its middle node")
        ->needs(png);
    cmd->callback([opt, &exit_code] { exit_code = run_inspect(*opt); });
}

} // namespace scatterlut
