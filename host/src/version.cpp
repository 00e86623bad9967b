#include "version.hpp"
namespace scatterlut {
std::string generator_version() { return std::string("scatterlut ") + SCATTERLUT_VERSION; }
} // namespace scatterlut
