// scatterlut — `scatterlut report`: what accuracy costs in time, for every table a scene
// calls for. Three ladders per table, each written as Markdown, CSV and an SVG chart:
//   tolerance   integration tolerance 1e-3 … 1e-13 → generation time (median of interleaved
//               rounds) and the achieved maximum node error against a finer reference;
//   resolution  node counts around the planner's choice, f16 and f32 → maximum and p99
//               error of the sampled radiance against exact quadrature over the scene's
//               domain, bytes, ns per lookup;
//   methods     exact quadrature, the table, the thin-medium and distant-light closed forms
//               → error distribution of the radiance over the scene's domain against ns per call.
// Where spot lights light surfaces, a section on the engines' approximations of the spot's
// scattered surface terms against the exact ones (report_spot_surfaces.hpp).
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace scatterlut {

// `command_line` is recorded in the report (read when it runs).
void setup_report(CLI::App &app, int &exit_code, const std::string &command_line);

} // namespace scatterlut
