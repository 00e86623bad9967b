#include "opencl_device.hpp"

#include <algorithm>
#include <list>
#include <cctype>
#include <cstdio>
#include <cstdlib>
#include <optional>
#include <set>
#include <sstream>

#include "embedded_kernels.hpp"
#include "scatterlut/io.hpp"

namespace scatterlut {
namespace {

std::string lower(std::string s) {
    std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return static_cast<char>(std::tolower(c)); });
    return s;
}

std::string trim(std::string s) {
    while (!s.empty() && (s.back() == '\0' || std::isspace(static_cast<unsigned char>(s.back())))) s.pop_back();
    return s;
}

std::string device_type_name(cl_device_type type) {
    if (type & CL_DEVICE_TYPE_GPU) return "GPU";
    if (type & CL_DEVICE_TYPE_CPU) return "CPU";
    if (type & CL_DEVICE_TYPE_ACCELERATOR) return "ACCELERATOR";
    return "OTHER";
}

const embedded::EmbeddedFile *find_embedded(const std::string &name) {
    for (std::size_t i = 0; i < embedded::kFileCount; ++i)
        if (name == embedded::kFiles[i].name) return &embedded::kFiles[i];
    return nullptr;
}

void inline_includes(const std::string &name, std::set<std::string> &seen, std::ostringstream &out) {
    const embedded::EmbeddedFile *file = find_embedded(name);
    if (!file) throw DeviceError("internal error: kernel file '" + name + "' is not embedded in this build");
    if (!seen.insert(name).second) return;
    std::istringstream in(file->contents);
    std::string line;
    int line_number = 0;
    out << "#line 1 \"" << name << "\"\n";
    while (std::getline(in, line)) {
        ++line_number;
        const auto first = line.find_first_not_of(" \t");
        if (first != std::string::npos && line.compare(first, 9, "#include ") == 0) {
            const auto open = line.find('"');
            const auto close = line.rfind('"');
            if (open != std::string::npos && close > open) {
                inline_includes(line.substr(open + 1, close - open - 1), seen, out);
                out << "#line " << line_number + 1 << " \"" << name << "\"\n";
                continue;
            }
        }
        out << line << '\n';
    }
}

// PoCL reads POCL_AFFINITY when the platform is first queried: 1 pins its worker threads
// to cores, one source of variation less for sub-millisecond kernels (what it measured:
// docs/POCL.md, "Pinned worker threads"). A value the user set wins. Other drivers ignore
// the variable.
void pin_pocl_threads() { ::setenv("POCL_AFFINITY", "1", 0); }

DeviceInfo describe_device(const cl::Platform &platform, const cl::Device &device, int p, int d) {
    DeviceInfo info;
    info.platform_index = p;
    info.device_index = d;
    info.platform_name = trim(platform.getInfo<CL_PLATFORM_NAME>());
    info.device_name = trim(device.getInfo<CL_DEVICE_NAME>());
    info.device_version = trim(device.getInfo<CL_DEVICE_VERSION>());
    info.driver_version = trim(device.getInfo<CL_DRIVER_VERSION>());
    info.type = device_type_name(device.getInfo<CL_DEVICE_TYPE>());
    info.compute_units = device.getInfo<CL_DEVICE_MAX_COMPUTE_UNITS>();
    const std::string extensions = device.getInfo<CL_DEVICE_EXTENSIONS>();
    info.fp64 = extensions.find("cl_khr_fp64") != std::string::npos ||
                device.getInfo<CL_DEVICE_DOUBLE_FP_CONFIG>() != 0;
    return info;
}

} // namespace

std::string DeviceInfo::describe() const {
    return platform_name + " / " + device_name + " (" + device_version + ", driver " + driver_version + ")";
}

std::string embedded_source(const std::string &name) {
    std::set<std::string> seen;
    std::ostringstream out;
    inline_includes(name, seen, out);
    return out.str();
}

std::vector<DeviceInfo> list_devices() {
    std::vector<DeviceInfo> out;
    pin_pocl_threads();
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error &e) {
        if (e.err() == CL_PLATFORM_NOT_FOUND_KHR) return out; // no ICD installed
        throw;
    }
    for (std::size_t p = 0; p < platforms.size(); ++p) {
        std::vector<cl::Device> devices;
        try {
            platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error &) {
            continue; // a platform without devices
        }
        for (std::size_t d = 0; d < devices.size(); ++d)
            out.push_back(describe_device(platforms[p], devices[d], static_cast<int>(p), static_cast<int>(d)));
    }
    return out;
}

Device::Device(const std::string &selector_in) {
    std::string selector = selector_in;
    if (selector.empty()) {
        if (const char *env = std::getenv("SCATTERLUT_DEVICE")) selector = env;
    }
    pin_pocl_threads();
    std::vector<cl::Platform> platforms;
    try {
        cl::Platform::get(&platforms);
    } catch (const cl::Error &) {
        platforms.clear();
    }
    if (platforms.empty())
        throw DeviceError("no OpenCL platform found: install an OpenCL driver (on Debian: apt-get install pocl-opencl-icd)");

    bool found = false;
    std::string candidates;
    for (std::size_t p = 0; p < platforms.size() && !found; ++p) {
        std::vector<cl::Device> devices;
        try {
            platforms[p].getDevices(CL_DEVICE_TYPE_ALL, &devices);
        } catch (const cl::Error &) {
            continue;
        }
        for (std::size_t d = 0; d < devices.size() && !found; ++d) {
            DeviceInfo info = describe_device(platforms[p], devices[d], static_cast<int>(p), static_cast<int>(d));
            candidates += "\n  " + std::to_string(p) + ":" + std::to_string(d) + "  " + info.describe() +
                          (info.fp64 ? "" : "  [no fp64]");
            bool match;
            if (selector.empty()) {
                match = info.fp64;
            } else if (selector == std::to_string(p) + ":" + std::to_string(d)) {
                match = true;
            } else {
                match = lower(info.device_name).find(lower(selector)) != std::string::npos ||
                        lower(info.platform_name).find(lower(selector)) != std::string::npos;
            }
            if (!match) continue;
            if (!info.fp64)
                throw DeviceError("device " + info.describe() +
                                  " lacks cl_khr_fp64; scatterlut integrates in double precision. Choose another "
                                  "device with --device or SCATTERLUT_DEVICE.");
            info_ = info;
            device_ = devices[d];
            found = true;
        }
    }
    if (!found) {
        if (!selector.empty())
            throw DeviceSelectionError("--device (or SCATTERLUT_DEVICE) '" + selector +
                                       "': no OpenCL device matches (expected P:D from `scatterlut devices` or a "
                                       "name substring); devices:" + candidates);
        throw DeviceError("no OpenCL device with cl_khr_fp64 found; devices:" + candidates);
    }
    context_ = cl::Context(device_);
    queue_ = cl::CommandQueue(context_, device_);
}

namespace {

// Builds `program` for `device`, turning a failure into a DeviceError with the build log.
void build_or_throw(cl::Program &program, const cl::Device &device, const DeviceInfo &info, const std::string &cl_file,
                    const std::string &options) {
    try {
        program.build(std::vector<cl::Device>{device}, options.c_str());
    } catch (const cl::Error &) {
        std::string log;
        try {
            log = program.getBuildInfo<CL_PROGRAM_BUILD_LOG>(device);
        } catch (const cl::Error &) {
            log = "(no build log available)";
        }
        throw DeviceError("OpenCL build of " + cl_file + " failed\n  platform: " + info.platform_name +
                          "\n  device:   " + info.device_name + " (" + info.device_version + ", driver " +
                          info.driver_version + ")\n  options:  " + options + "\n  build log:\n" + log);
    }
}

} // namespace

cl::Program &Device::program(const std::string &cl_file) {
    for (auto &entry : programs_)
        if (entry.file == cl_file) return entry.program;
    const std::string source = embedded_source(cl_file);
    const std::string options = "-cl-std=CL1.2";
    char source_hash[40];
    std::snprintf(source_hash, sizeof source_hash, "%016llx/%zu",
                  static_cast<unsigned long long>(fnv1a64(source.data(), source.size())), source.size());
    ProgramEntry entry{cl_file, cl::Program(),
                       ProgramCache("scatterlut program cache v1\nfile: " + cl_file + "\nplatform: " +
                                    info_.platform_name + "\ndevice: " + info_.device_name +
                                    "\ndevice version: " + info_.device_version + "\ndriver: " +
                                    info_.driver_version + "\noptions: " + options + "\nsource: " + source_hash),
                       ProgramOrigin::Source, 0};
    if (std::optional<std::vector<uint8_t>> binary = entry.cache.load()) {
        try {
            std::vector<cl_int> status;
            cl::Program cached(context_, std::vector<cl::Device>{device_},
                               cl::Program::Binaries{std::vector<unsigned char>(binary->begin(), binary->end())},
                               &status);
            cached.build(std::vector<cl::Device>{device_}, options.c_str());
            entry.program = std::move(cached);
            entry.origin = ProgramOrigin::Cache;
            entry.binary_size = binary->size();
        } catch (const cl::Error &e) {
            entry.cache.log(std::string("ignored (the driver rejected the binary: ") + e.what() + " " +
                            std::to_string(e.err()) + "); building from source");
        }
    }
    if (entry.origin == ProgramOrigin::Source) {
        entry.program = cl::Program(context_, source);
        build_or_throw(entry.program, device_, info_, cl_file, options);
    }
    programs_.push_back(std::move(entry));
    return programs_.back().program;
}

ProgramOrigin Device::program_origin(const std::string &cl_file) const {
    for (const auto &entry : programs_)
        if (entry.file == cl_file) return entry.origin;
    return ProgramOrigin::None;
}

void Device::kernels_ran(const std::string &cl_file) {
    for (auto &entry : programs_) {
        if (entry.file != cl_file || !entry.cache.enabled()) continue;
        // PoCL compiles a work-group function per launch shape at the first enqueue that
        // needs it, so the binary grows as new shapes run: store it whenever its size
        // differs from the one stored or loaded (a size query; the binary only then).
        try {
            const std::vector<size_t> sizes = entry.program.getInfo<CL_PROGRAM_BINARY_SIZES>();
            if (sizes.size() != 1 || sizes[0] == 0 || sizes[0] == entry.binary_size) return;
            const std::vector<std::vector<unsigned char>> binaries = entry.program.getInfo<CL_PROGRAM_BINARIES>();
            if (binaries.size() != 1 || binaries[0].empty()) return;
            entry.cache.store(std::vector<uint8_t>(binaries[0].begin(), binaries[0].end()));
            entry.binary_size = binaries[0].size();
        } catch (const cl::Error &e) {
            entry.cache.log(std::string("not stored (") + e.what() + ")");
        }
        return;
    }
}

} // namespace scatterlut
