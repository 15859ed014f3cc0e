// SPDX-License-Identifier: MIT
#pragma once
// The command line of smi-lua, parsed the way lua.c reads its own (options, then the script
// and its arguments), plus the sandbox and run options. Parsing never runs anything.
#include <string>
#include <vector>

#include "app/runtime.hpp"

namespace smi::cli {

/// -e and -l run in the order given, before the script.
struct Action {
  enum Kind { exec, require } kind;
  std::string text;
};

struct Args {
  app::Config cfg;
  std::vector<Action> actions;
  bool interactive = false;   // -i
  bool version = false;       // -v
  bool version_build = false;  // --version: version and build line, then exit 0
  bool help = false;          // --help / -h
  bool warnings = false;      // -W
  bool quiet_given = false;   // --quiet
  bool ignore_env = false;    // -E
  std::string libs_into;      // smi-lua libs add/sync --into DIR
  bool libs_check = false;    // smi-lua libs sync --check
  int script_index = 0;       // index in argv of the script (or "-"); 0 if none
  std::string error;          // a usage error (exit status 2)
};

Args parse(int argc, char** argv);

/// The --help text (every option).
const char* help_text();
/// The one-line usage shown with a usage error.
const char* usage_line();

}  // namespace smi::cli
