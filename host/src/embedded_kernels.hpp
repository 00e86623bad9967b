// The OpenCL sources and shared headers, embedded at build time (cmake/embed_kernels.cmake).
#pragma once

#include <cstddef>
#include <string>

namespace scatterlut::embedded {

struct EmbeddedFile {
    const char *name;     // file name, e.g. "slut_airlight.h"
    const char *contents; // the file, verbatim
};

extern const EmbeddedFile kFiles[];
extern const std::size_t kFileCount;

} // namespace scatterlut::embedded
