#pragma once
#include <string>
namespace scatterlut {
// "scatterlut X.Y.Z" — recorded in every table file.
std::string generator_version();
} // namespace scatterlut
