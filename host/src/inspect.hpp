// scatterlut — `scatterlut inspect FILE`: a table file's metadata, axes, channels (with
// the decoded value range), declared accuracy and provenance, as text or JSON; with
// `--preview out.png` also a false-colour picture of a 2-D table or slice (preview.hpp).
#pragma once

#include <CLI/CLI.hpp>

namespace scatterlut {

// Adds the `inspect` subcommand; its callback sets exit_code to 0 (a LoadError or a bad
// --preview request, std::invalid_argument, propagates to main, which maps it to 2).
void setup_inspect(CLI::App &app, int &exit_code);

} // namespace scatterlut
