// scatterlut generator — the OpenCL device: discovery, selection, program build.
#pragma once

#include <stdexcept>
#include <string>
#include <list>
#include <vector>

#include <CL/opencl.hpp>

#include "program_cache.hpp"

namespace scatterlut {

struct DeviceInfo {
    int platform_index = 0;
    int device_index = 0;
    std::string platform_name;
    std::string device_name;
    std::string device_version;
    std::string driver_version;
    std::string type; // "CPU", "GPU", "ACCELERATOR", ...
    bool fp64 = false;
    unsigned compute_units = 0;
    std::string describe() const; // "platform / device (driver …)"
};

std::vector<DeviceInfo> list_devices();

// Thrown when no usable device exists or a kernel fails to build; the message carries
// platform, device, build options and the build log.
class DeviceError : public std::runtime_error {
public:
    using std::runtime_error::runtime_error;
};

// A --device (or SCATTERLUT_DEVICE) selector that names no device: a usage error (exit 2).
class DeviceSelectionError : public DeviceError {
public:
    using DeviceError::DeviceError;
};

// Where a program came from: not built yet, compiled from the embedded source, or loaded
// from the program binary cache (program_cache.hpp).
enum class ProgramOrigin { None, Source, Cache };

// A context + queue on one device, and the program built from the embedded kernels.
class Device {
public:
    // selector: "" = the first device with cl_khr_fp64 (PoCL on the CPU here);
    // "P:D" = platform P, device D (indices from `scatterlut devices`); otherwise a
    // case-insensitive substring of the platform or device name. The environment
    // variable SCATTERLUT_DEVICE is used when selector is empty.
    explicit Device(const std::string &selector);

    const DeviceInfo &info() const { return info_; }
    cl::Context &context() { return context_; }
    cl::CommandQueue &queue() { return queue_; }

    // The program of one embedded .cl file (its #include "…" lines resolved against
    // the embedded headers), built once and kept for the life of this Device; taken from
    // the program binary cache when it holds an intact entry for this device and source.
    cl::Program &program(const std::string &cl_file);
    ProgramOrigin program_origin(const std::string &cl_file) const;

    // Generators call this once the program's kernels have completed a run: the program's
    // binary then goes into the binary cache if it grew since it was stored (after the
    // run, so that it holds the work-group functions PoCL compiles at the first enqueue).
    void kernels_ran(const std::string &cl_file);

private:
    DeviceInfo info_;
    cl::Device device_;
    cl::Context context_;
    cl::CommandQueue queue_;
    struct ProgramEntry {
        std::string file;
        cl::Program program;
        ProgramCache cache;
        ProgramOrigin origin;
        size_t binary_size; // of the binary last stored or loaded (0: none)
    };
    std::list<ProgramEntry> programs_; // stable references
};

// The embedded source of `name` with its local includes inlined (each header once).
std::string embedded_source(const std::string &name);

} // namespace scatterlut
