// scatterlut runtime — the EXR entry points of a library built without OpenEXR
// (SCATTERLUT_WITH_OPENEXR=OFF; tables/CMakeLists.txt compiles this file instead of
// io_exr_*.cpp): they exist and say so.
#include "scatterlut/io.hpp"

#ifdef SCATTERLUT_HAS_OPENEXR
#error "io_exr_unavailable.cpp is the build without OpenEXR; with it, compile io_exr_*.cpp"
#endif

namespace scatterlut {

namespace {
const char *kNoExr = "this scatterlut library was built without OpenEXR (configure with "
                     "-DSCATTERLUT_WITH_OPENEXR=ON), or use the binary format";
}
bool have_openexr() { return false; }
Table load_exr(const std::string &path) { throw LoadError(path + ": cannot read EXR: " + kNoExr); }
Table decode_exr(const uint8_t *, size_t, const std::string &name) {
    throw LoadError(name + ": cannot read EXR: " + kNoExr);
}
std::vector<uint8_t> encode_exr(const Table &) { throw std::runtime_error(std::string("cannot write EXR: ") + kNoExr); }
void save_exr(const Table &, const std::string &path) {
    throw std::runtime_error(path + ": cannot write EXR: " + kNoExr);
}

} // namespace scatterlut
