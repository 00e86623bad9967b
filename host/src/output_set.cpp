#include "output_set.hpp"

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>

#include <nlohmann/json.hpp>

#include "json_guard.hpp"
#include "scatterlut/io.hpp"

namespace scatterlut {
namespace {

bool is_table_file(const std::string &name) {
    auto ends = [&](const char *suffix) {
        const std::string s(suffix);
        return name.size() > s.size() && name.compare(name.size() - s.size(), s.size(), s) == 0;
    };
    return name[0] != '.' && (ends(".slut") || ends(".exr") || ends(".ktx2"));
}

} // namespace

OutputSetCheck check_output_set(const std::string &dir) {
    const std::string path = dir + "/" + kManifestName;
    const std::vector<uint8_t> bytes = detail::read_file(path, kMaxManifestBytes, "a scatterlut manifest (JSON)");
    const std::string text(bytes.begin(), bytes.end());
    if (const std::string problem = json_text_problem(text, 16); !problem.empty())
        throw LoadError(path + ": " + problem + ", expected a scatterlut manifest");
    nlohmann::json j;
    try {
        j = nlohmann::json::parse(text);
    } catch (const nlohmann::json::exception &e) {
        throw LoadError(path + ": invalid JSON: " + e.what());
    }
    if (!j.is_object() || j.value("manifest", std::string()) != kManifestMagic || !j.contains("files") ||
        !j["files"].is_array())
        throw LoadError(path + ": not a scatterlut manifest (expected \"manifest\": \"" + kManifestMagic +
                        "\" and a \"files\" array)");
    OutputSetCheck check;
    std::set<std::string> listed;
    for (const auto &f : j["files"]) {
        ManifestFile m;
        try {
            m.name = f.at("name").get<std::string>();
            m.kind = f.at("kind").get<std::string>();
            m.format = f.at("format").get<std::string>();
            m.bytes = f.at("bytes").get<uint64_t>();
            const std::string sum = f.at("fnv1a64").get<std::string>();
            char *end = nullptr;
            m.fnv1a64 = std::strtoull(sum.c_str(), &end, 16);
            if (sum.size() != 16 || *end != '\0') throw std::invalid_argument("fnv1a64 is not 16 hex digits");
        } catch (const std::exception &e) {
            throw LoadError(path + ": a \"files\" entry is malformed (expected name, kind, format, bytes, fnv1a64): " +
                            e.what());
        }
        if (m.name.empty() || m.name.find('/') != std::string::npos || m.name[0] == '.')
            throw LoadError(path + ": file name '" + m.name + "' is not a plain name in the directory");
        listed.insert(m.name);
        check.files.push_back(m);
    }
    for (const ManifestFile &m : check.files) {
        const std::string file = dir + "/" + m.name;
        std::vector<uint8_t> content;
        try {
            content = detail::read_file(file, m.bytes, "the file the manifest lists");
        } catch (const LoadError &e) {
            check.mismatches.push_back(std::string(e.what()));
            continue;
        }
        if (content.size() != m.bytes) {
            check.mismatches.push_back(file + ": " + std::to_string(content.size()) + " bytes, the manifest says " +
                                       std::to_string(m.bytes) + " (not this set's file)");
            continue;
        }
        const uint64_t sum = fnv1a64(content.data(), content.size());
        if (sum != m.fnv1a64) {
            char buf[96];
            std::snprintf(buf, sizeof buf, "checksum %016llx, the manifest says %016llx",
                          static_cast<unsigned long long>(sum), static_cast<unsigned long long>(m.fnv1a64));
            check.mismatches.push_back(file + ": " + buf + " (not this set's file)");
        }
    }
    std::error_code ec;
    std::vector<std::string> strays;
    for (const auto &entry : std::filesystem::directory_iterator(dir, ec)) {
        const std::string name = entry.path().filename().string();
        if (is_table_file(name) && !listed.count(name)) strays.push_back(name);
    }
    std::sort(strays.begin(), strays.end());
    for (const std::string &name : strays)
        check.mismatches.push_back(dir + "/" + name + ": a table file the manifest does not list (not of this run)");
    return check;
}

} // namespace scatterlut
