// SPDX-License-Identifier: MIT
#pragma once
// What this smi-lua binary is: its version and the versions of what it was built with
// (compiler, Lua, Eigen, NLopt, SQLite, RE2, nettle, fmt). `smi-lua --version` prints it and
// every results.json records it (provenance.build), since a different Eigen or NLopt can move
// the last digits of a calibration.
#include <string>
#include <utility>
#include <vector>

namespace smi::vm {

/// The version of results.json's layout ("schema" at its top; docs/provenance.md lists the
/// fields). 1: files without "schema" (provenance of the script, seed and libraries only).
/// 2: provenance of every file read, program, option and the build; per-step inputs.
inline constexpr int kResultsSchema = 2;

/// {component, version} in a fixed order: smi-lua, build type, compiler, lua, eigen, nlopt,
/// sqlite, re2, nettle, fmt.
std::vector<std::pair<std::string, std::string>> build_info();

/// One line: "smi-lua 0.1.0 (Release; GCC 12.2.0; Lua 5.4.6; Eigen 3.4.0; ...)".
std::string build_line();

}  // namespace smi::vm
