// scatterlut runtime — the OpenEXR table encoder (docs/FORMAT.md §4; the mapping is described
// in io_exr_format.hpp).
#include "scatterlut/io.hpp"

#include <cstring>
#include <limits>

#include <ImfChannelList.h>
#include <ImfFrameBuffer.h>
#include <ImfIntAttribute.h>
#include <ImfOutputFile.h>
#include <ImfStringAttribute.h>
#include <ImfStringVectorAttribute.h>

#include "io_exr_format.hpp"
#include "io_text.hpp"

namespace scatterlut {

using namespace exr_format;
using detail::hex64;

bool have_openexr() { return true; }

// =====================================================================================
// Writer
// =====================================================================================

std::vector<uint8_t> encode_exr(const Table &t) {
    if (t.storage == Storage::F64)
        throw std::invalid_argument("EXR cannot store f64 (its pixel types are HALF and FLOAT): use the binary "
                                    "format for f64 tables, or storage f32/f16");
    detail::check_limits(t);
    if (t.quantity_version > static_cast<uint32_t>(std::numeric_limits<int>::max()))
        throw std::invalid_argument("quantity_version " + std::to_string(t.quantity_version) +
                                    " does not fit an EXR int attribute");
    const std::vector<uint8_t> payload = detail::encode_payload(t); // rounds, refuses overflow

    const size_t nc = t.channels.size();
    const size_t width = static_cast<size_t>(t.axes[0].map.count);
    const size_t height = t.node_count() / width; // ≤ 2^30, fits int
    Imf::Header h(static_cast<int>(width), static_cast<int>(height));
    h.compression() = Imf::ZIP_COMPRESSION;
    const Imf::PixelType type = t.storage == Storage::F16 ? Imf::HALF : Imf::FLOAT;
    std::vector<std::string> exr_names;
    for (size_t i = 0; i < nc; ++i) exr_names.push_back(exr_channel_name(nc, i, t.channels[i].name));
    for (const std::string &n : exr_names) h.channels().insert(n, Imf::Channel(type));
    // Every real number as text: the shortest decimal that reads back exactly.
    auto real = [](double x) { return Imf::StringAttribute(detail::decimal_text(x)); };

    h.insert(kPrefix + "format_major", Imf::IntAttribute(static_cast<int>(kExrFormatMajor)));
    h.insert(kPrefix + "format_minor", Imf::IntAttribute(static_cast<int>(kExrFormatMinor)));
    h.insert(kPrefix + "kind", Imf::StringAttribute(t.kind));
    h.insert(kPrefix + "quantity_version", Imf::IntAttribute(static_cast<int>(t.quantity_version)));
    h.insert(kPrefix + "storage", Imf::StringAttribute(to_string(t.storage)));
    h.insert(kPrefix + "layout", Imf::StringAttribute(kLayout));
    h.insert(kPrefix + "axes", Imf::IntAttribute(static_cast<int>(t.axes.size())));
    for (size_t i = 0; i < t.axes.size(); ++i) {
        const Axis &a = t.axes[i];
        h.insert(axis_key(i, "name"), Imf::StringAttribute(a.name));
        h.insert(axis_key(i, "meaning"), Imf::StringAttribute(a.meaning));
        h.insert(axis_key(i, "min"), real(a.map.min));
        h.insert(axis_key(i, "max"), real(a.map.max));
        h.insert(axis_key(i, "scale"), real(a.map.scale));
        h.insert(axis_key(i, "warp"), Imf::IntAttribute(a.map.warp));
        h.insert(axis_key(i, "warp_name"), Imf::StringAttribute(warp_name(a.map.warp)));
        h.insert(axis_key(i, "count"), Imf::IntAttribute(a.map.count));
    }
    h.insert(kPrefix + "channels", Imf::IntAttribute(static_cast<int>(nc)));
    for (size_t i = 0; i < nc; ++i) {
        h.insert(channel_key(i, "name"), Imf::StringAttribute(t.channels[i].name));
        h.insert(channel_key(i, "meaning"), Imf::StringAttribute(t.channels[i].meaning));
        h.insert(channel_key(i, "encoding"), Imf::StringAttribute(to_string(t.channels[i].encoding)));
        h.insert(channel_key(i, "exr_channel"), Imf::StringAttribute(exr_names[i]));
    }
    const Accuracy &ac = t.accuracy;
    h.insert(kPrefix + "accuracy.integration_max_rel", real(ac.integration_max_rel));
    h.insert(kPrefix + "accuracy.sampling_max_rel", real(ac.sampling_max_rel));
    h.insert(kPrefix + "accuracy.sampling_p99_rel", real(ac.sampling_p99_rel));
    h.insert(kPrefix + "accuracy.sampling_median_rel", real(ac.sampling_median_rel));
    h.insert(kPrefix + "accuracy.storage_max_rel", real(ac.storage_max_rel));
    h.insert(kPrefix + "accuracy.sampling_points", Imf::StringAttribute(std::to_string(ac.sampling_points)));
    h.insert(kPrefix + "accuracy.sampling_domain", Imf::StringAttribute(ac.sampling_domain));
    const Provenance &pv = t.provenance;
    h.insert(kPrefix + "provenance.generator_version", Imf::StringAttribute(pv.generator_version));
    h.insert(kPrefix + "provenance.command_line", Imf::StringAttribute(pv.command_line));
    h.insert(kPrefix + "provenance.scene", Imf::StringAttribute(pv.scene));
    h.insert(kPrefix + "provenance.device", Imf::StringAttribute(pv.device));
    h.insert(kPrefix + "provenance.created_by", Imf::StringAttribute(pv.created_by));
    Imf::StringVector extra;
    for (const auto &kv : t.extra) {
        extra.push_back(kv.first);
        extra.push_back(kv.second);
    }
    h.insert(kPrefix + "extra", Imf::StringVectorAttribute(extra));
    h.insert(kChecksumPrefix + "header", Imf::StringAttribute(hex64(header_checksum(h))));
    h.insert(kChecksumPrefix + "payload", Imf::StringAttribute(hex64(fnv1a64(payload.data(), payload.size()))));

    // Pixels in native layout, built from the little-endian payload (host-independent).
    const size_t n = t.values.size();
    std::vector<uint16_t> half_px;
    std::vector<float> float_px;
    char *base;
    size_t elem;
    if (type == Imf::HALF) {
        half_px.resize(n);
        for (size_t i = 0; i < n; ++i)
            half_px[i] = static_cast<uint16_t>(payload[2 * i] | payload[2 * i + 1] << 8);
        base = reinterpret_cast<char *>(half_px.data());
        elem = 2;
    } else {
        float_px.resize(n);
        for (size_t i = 0; i < n; ++i) {
            const uint8_t *p = &payload[4 * i];
            const uint32_t w = uint32_t{p[0]} | uint32_t{p[1]} << 8 | uint32_t{p[2]} << 16 | uint32_t{p[3]} << 24;
            std::memcpy(&float_px[i], &w, 4);
        }
        base = reinterpret_cast<char *>(float_px.data());
        elem = 4;
    }
    Imf::FrameBuffer fb;
    for (size_t c = 0; c < nc; ++c)
        fb.insert(exr_names[c], Imf::Slice::Make(type, base + c * elem, h.dataWindow(), nc * elem, nc * elem * width));

    MemOStream out;
    try {
        Imf::OutputFile file(out, h);
        file.setFrameBuffer(fb);
        file.writePixels(static_cast<int>(height));
    } catch (const std::exception &e) {
        throw std::runtime_error(std::string("OpenEXR could not encode the table: ") + e.what());
    }
    return std::move(out.bytes);
}

void save_exr(const Table &table, const std::string &path) { write_file_atomic(path, encode_exr(table)); }

} // namespace scatterlut
