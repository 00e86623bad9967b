// scatterlut generator — a cache of compiled OpenCL program binaries, so that a second
// `generate` does not pay the device compiler again (PoCL: seconds cold; docs/POCL.md),
// even where the driver's own cache is unavailable or disabled.
//
// An entry is the program's CL_PROGRAM_BINARIES, saved after its kernels have run once
// (PoCL compiles the work-group functions lazily at the first enqueue; a binary saved
// after the run holds them). It is keyed by everything that changes the binary: platform,
// device, device and driver version, build options and the embedded source, hashed into
// the file name and stored in full in the entry, which is checked on load. Entries live
// in $XDG_CACHE_HOME/scatterlut (else ~/.cache/scatterlut), are written atomically and
// are never trusted: any problem (unreadable, wrong key, bad checksum, the driver rejects
// the binary or its build) is logged on stderr and the program is built from source.
// SCATTERLUT_PROGRAM_CACHE=0 turns the cache off.
#pragma once

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace scatterlut {

class ProgramCache {
public:
    // identity: the full key text (platform, device, versions, options, source hash).
    explicit ProgramCache(std::string identity);

    // false when SCATTERLUT_PROGRAM_CACHE=0 or no cache directory can be named.
    bool enabled() const { return !path_.empty(); }
    const std::string &path() const { return path_; }

    // The stored binary when the entry exists and is intact (key and checksum match);
    // nullopt otherwise. A damaged entry is logged (a missing one is not).
    std::optional<std::vector<uint8_t>> load() const;

    // Stores the binary atomically; failures are logged, never thrown.
    void store(const std::vector<uint8_t> &binary) const;

    // Logs "scatterlut: program cache <path>: <what>" on stderr.
    void log(const std::string &what) const;

private:
    std::string identity_;
    std::string path_;
};

// The cache directory: $XDG_CACHE_HOME/scatterlut or $HOME/.cache/scatterlut; "" if the
// cache is disabled (SCATTERLUT_PROGRAM_CACHE=0) or neither variable is set.
std::string program_cache_directory();

} // namespace scatterlut
