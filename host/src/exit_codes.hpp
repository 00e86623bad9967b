// scatterlut — the command line's exit codes (docs/EXIT_CODES.md).
#pragma once

namespace scatterlut {

// 0 success; 1 a failure of the run or of what it checks (device, accuracy, checksum, an
// inconsistent set, another run holding the output directory); 2 usage or unreadable input
// (arguments, files, scenes, --device naming no device).
inline constexpr int kExitFailure = 1;
inline constexpr int kExitBadInput = 2;

} // namespace scatterlut
