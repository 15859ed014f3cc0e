// SPDX-License-Identifier: MIT
#pragma once
// Subcommands for sharing libraries (the word in the script position selects one; a script
// file literally named like a command is run as ./libs):
//   smi-lua libs                 the libraries a study would see: name, version, commit, path
//   smi-lua libs add SOURCE[@REF] | NAME[@RANGE] / update [NAME] / sync [--check] / tree /
//                outdated / remove NAME / pack DIR
//                                install, restore and inspect the project's library tree,
//                                smi-project.json and smi-lock.json (libs_install.cpp, libs_pack.cpp)
//   smi-lua libs registry NAME URL / publish REGISTRY SOURCE@REF / search WORD
//                                team registries (libs_registry.cpp)
//   smi-lua new-lib NAME [DIR]   scaffold a library (manifest, module, a passing test, README)
//   smi-lua test DIR             run DIR/tests/test_*.lua sandboxed; prints "N passed, N failed"
//   smi-lua verify RESULTS.json  does everything a study recorded (files, programs, libraries,
//                                build) still hash the same? (--json for tools)
//   smi-lua doc [NAME]           the reference (help() text); doc --html DIR writes it as pages
//   smi-lua report --pdf HTML    prints a report.html to PDF beside it (headless Chromium)
// Options such as --lib, --allow-read and --seed may come before or after the command word.
#include <filesystem>
#include <string>
#include <vector>

#include "cli/args.hpp"
#include "vm/libraries.hpp"

namespace smi::cli {

bool is_command(const std::string& word);

/// Runs the command named at argv[a.script_index]; returns the exit status (0 ok, 1 failure,
/// 2 usage error).
int run_command(const Args& a, int argc, char** argv);

// The commands, each in its own file. `args` are the positional words after the command.
int cmd_libs(const Args& a, const std::vector<std::string>& args);
int libs_add(const Args& a, const std::vector<std::string>& args);
int libs_sync(const Args& a, const std::vector<std::string>& args);
int libs_remove(const Args& a, const std::vector<std::string>& args);
int libs_outdated(const Args& a, const std::vector<std::string>& args);
int libs_update(const Args& a, const std::vector<std::string>& args);
int libs_publish(const Args& a, const std::vector<std::string>& args);
int libs_search(const Args& a, const std::vector<std::string>& args);
int libs_registry(const Args& a, const std::vector<std::string>& args);
int libs_pack(const Args& a, const std::vector<std::string>& args);
int cmd_new_lib(const Args& a, const std::vector<std::string>& args);
int cmd_test(const Args& a, const std::vector<std::string>& args, const char* argv0);
int cmd_verify(const Args& a, const std::vector<std::string>& args);
int cmd_doc(const Args& first, int argc, char** argv);
int cmd_report(const Args& a, const std::vector<std::string>& args);

/// Prints `html` to a PDF of the same name (report.html -> report.pdf) through headless
/// Chromium (commands_report.cpp); says where it went, or why not and how to get it. Returns 0
/// when written, 1 when not.
int print_report_pdf(const std::string& html);

/// A git commit as the libs commands print it: its first 12 hex digits (a shorter string as is).
inline std::string short_commit(const std::string& c) { return c.size() == 40 ? c.substr(0, 12) : c; }

/// The library set the options and environment describe (SMI_PATH unless -E).
vm::LibrarySet current_libraries(const Args& a);

/// For `smi-lua test DIR`: the library tree holding what the library in DIR requires, resolved
/// from its `sources` (and installed with a lockfile under `work`), or "" when the --lib folders
/// already meet every requirement.
std::string test_dependencies(const Args& a, const std::filesystem::path& dir, const std::filesystem::path& work);

}  // namespace smi::cli
