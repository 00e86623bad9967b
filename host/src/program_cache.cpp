#include "program_cache.hpp"

#include "text_format.hpp"

#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>

#include "scatterlut/io.hpp"

namespace scatterlut {
namespace {

// Entry layout (little-endian on the machines PoCL runs on; a foreign entry fails the
// checks and is rebuilt): magic "SLUTPRG1", u64 identity length, identity bytes,
// u64 binary length, binary bytes, u64 FNV-1a of everything before it.
constexpr char kMagic[8] = {'S', 'L', 'U', 'T', 'P', 'R', 'G', '1'};

void put_u64(std::vector<uint8_t> &out, uint64_t v) {
    for (int i = 0; i < 8; ++i) out.push_back(static_cast<uint8_t>(v >> (8 * i)));
}

bool get_u64(const std::vector<uint8_t> &in, size_t *pos, uint64_t *v) {
    if (in.size() < 8 || *pos > in.size() - 8) return false;
    *v = 0;
    for (int i = 0; i < 8; ++i) *v |= static_cast<uint64_t>(in[*pos + static_cast<size_t>(i)]) << (8 * i);
    *pos += 8;
    return true;
}

} // namespace

std::string program_cache_directory() {
    if (const char *off = std::getenv("SCATTERLUT_PROGRAM_CACHE"); off && std::strcmp(off, "0") == 0) return "";
    if (const char *xdg = std::getenv("XDG_CACHE_HOME"); xdg && *xdg) return std::string(xdg) + "/scatterlut";
    if (const char *home = std::getenv("HOME"); home && *home) return std::string(home) + "/.cache/scatterlut";
    return "";
}

ProgramCache::ProgramCache(std::string identity) : identity_(std::move(identity)) {
    const std::string dir = program_cache_directory();
    if (dir.empty()) return;
    // Two independent 64-bit hashes of the identity name the file; the identity itself is
    // compared on load, so a collision costs a rebuild, never a wrong program.
    const uint64_t h1 = fnv1a64(identity_.data(), identity_.size());
    const uint64_t h2 = fnv1a64(identity_.data(), identity_.size(), 0x84222325cbf29ce4ull);
    path_ = dir + "/program-" + hex64(h1) + hex64(h2) + ".bin";
}

void ProgramCache::log(const std::string &what) const {
    std::fprintf(stderr, "scatterlut: program cache %s: %s\n", path_.c_str(), what.c_str());
}

std::optional<std::vector<uint8_t>> ProgramCache::load() const {
    if (!enabled()) return std::nullopt;
    std::ifstream in(path_, std::ios::binary);
    if (!in) return std::nullopt; // no entry yet: nothing to report
    const std::vector<uint8_t> bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const auto damaged = [&](const char *why) -> std::optional<std::vector<uint8_t>> {
        log(std::string("ignored (") + why + "); building from source");
        return std::nullopt;
    };
    if (bytes.size() < sizeof kMagic || std::memcmp(bytes.data(), kMagic, sizeof kMagic) != 0)
        return damaged("not a scatterlut program cache entry");
    size_t pos = sizeof kMagic;
    uint64_t id_len = 0, bin_len = 0, checksum = 0;
    if (!get_u64(bytes, &pos, &id_len) || id_len > bytes.size() - pos) return damaged("truncated");
    const std::string id(reinterpret_cast<const char *>(bytes.data() + pos), static_cast<size_t>(id_len));
    pos += static_cast<size_t>(id_len);
    if (!get_u64(bytes, &pos, &bin_len) || bin_len > bytes.size() - pos) return damaged("truncated");
    const size_t bin_pos = pos;
    pos += static_cast<size_t>(bin_len);
    const size_t checked = pos;
    if (!get_u64(bytes, &pos, &checksum) || pos != bytes.size()) return damaged("truncated or trailing bytes");
    if (fnv1a64(bytes.data(), checked) != checksum) return damaged("checksum mismatch");
    if (id != identity_) return damaged("key mismatch (another device, driver, option set or source)");
    if (bin_len == 0) return damaged("empty binary");
    return std::vector<uint8_t>(bytes.begin() + static_cast<long>(bin_pos),
                                bytes.begin() + static_cast<long>(bin_pos + bin_len));
}

void ProgramCache::store(const std::vector<uint8_t> &binary) const {
    if (!enabled() || binary.empty()) return;
    std::vector<uint8_t> out(kMagic, kMagic + sizeof kMagic);
    put_u64(out, identity_.size());
    out.insert(out.end(), identity_.begin(), identity_.end());
    put_u64(out, binary.size());
    out.insert(out.end(), binary.begin(), binary.end());
    put_u64(out, fnv1a64(out.data(), out.size()));
    try {
        std::filesystem::create_directories(std::filesystem::path(path_).parent_path());
        write_file_atomic(path_, out);
    } catch (const std::exception &e) {
        log(std::string("not stored: ") + e.what());
    }
}

} // namespace scatterlut
