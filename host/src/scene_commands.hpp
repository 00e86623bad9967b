// scatterlut — `scatterlut plan` and `scatterlut generate`: a scene (a file, or the
// embedded default scene) → the planner (plan.hpp) → the plan printed, or the tables written.
#pragma once

#include <string>

#include <CLI/CLI.hpp>

namespace scatterlut {

// Adds the subcommands. `command_line` is recorded in every table (read when they run).
// Exit codes through exit_code: 0 done; a bad scene throws SceneError (exit 2 in main).
void setup_plan(CLI::App &app, int &exit_code);
void setup_generate(CLI::App &app, int &exit_code, const std::string &command_line);

} // namespace scatterlut
