// scatterlut — `scatterlut validate FILE…`: reloads table files and re-measures their
// accuracy independently of the generator's own measurement (finer quadrature at nodes,
// interpolation error at another random sample of off-node points).
#pragma once

#include <CLI/CLI.hpp>

namespace scatterlut {

// Adds the `validate` subcommand; its callback sets exit_code: 0 every file passes,
// 1 an accuracy or consistency failure, 2 a file unreadable or unsupported.
void setup_validate(CLI::App &app, int &exit_code);

} // namespace scatterlut
