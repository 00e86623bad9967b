// scatterlut generator — one run's output set: the files `generate` writes into a
// directory together (under a flock on the directory that keeps a second run out), and the manifest
// (written last) that lets `validate DIR` check that the directory holds one run's set.
// Layout of the manifest: docs/FORMAT.md, "Output sets".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace scatterlut {

inline constexpr const char *kManifestName = "manifest.json";
inline constexpr const char *kManifestMagic = "scatterlut output set";
inline constexpr uint64_t kMaxManifestBytes = 16u << 20; // scene text ≤ 4 MiB, command line ≤ 1 MiB

// One file the manifest lists.
struct ManifestFile {
    std::string name;   // file name inside the directory
    std::string kind;   // table kind
    std::string format; // "bin", "exr" or "ktx2"
    uint64_t bytes = 0;
    uint64_t fnv1a64 = 0; // of the whole file
};

// What `validate DIR` learns from DIR/manifest.json and the directory: the listed files and
// every mismatch (a listed file missing, of another size or checksum, a table file present
// but not listed). Throws LoadError for a missing or malformed manifest.
struct OutputSetCheck {
    std::vector<ManifestFile> files;
    std::vector<std::string> mismatches;
};
OutputSetCheck check_output_set(const std::string &dir);

} // namespace scatterlut
