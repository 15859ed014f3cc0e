// SPDX-License-Identifier: MIT
// smi-lua new-lib NAME [DIR]: a library folder that works at once: manifest, a module, a test
// that passes under `smi-lua test`, and a README saying how to share it.
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <string>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"

namespace smi::cli {
namespace fs = std::filesystem;
namespace {

void write_file(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << text;
  out.close();
  if (!out) throw Error("cannot write '" + p.string() + "'");
}

std::string subst(std::string t, const std::string& name) {
  for (std::size_t at; (at = t.find("@NAME@")) != std::string::npos;) t.replace(at, 6, name);
  return t;
}

const char* const kManifest = R"LUA(-- The manifest of library @NAME@ (data only: read without running any function).
name = "@NAME@"
version = "0.1.0"          -- MAJOR.MINOR.PATCH: raise MAJOR when a change breaks studies
description = "TODO: one line saying what @NAME@ offers"
requires = {               -- other libraries, e.g. "kdetools >= 1.2", "smi-lua >= 0.1"
}
-- where `smi-lua libs add` fetches each required library (a git URL, a folder or a .tar.gz):
-- sources = {kdetools = "https://git.example.org/kdetools.git"}
)LUA";

const char* const kInit = R"LUA(--- @NAME@: require "@NAME@" gives this table; require "@NAME@.x" loads x.lua from this folder.
local M = {}

--- Weighted mean of the numbers in `xs` with weights `ws` (an example to replace).
function M.weighted_mean(xs, ws)
  if #xs == 0 or #xs ~= #ws then
    error(("@NAME@.weighted_mean: needs as many weights as values (got %d values, %d weights)"):format(#xs, #ws), 2)
  end
  local s, w = 0, 0
  for i = 1, #xs do
    s, w = s + xs[i] * ws[i], w + ws[i]
  end
  return s / w
end

return M
)LUA";

const char* const kTest = R"LUA(-- Run with: smi-lua test <library folder>
local T = require "smi.testing"
local lib = require "@NAME@"

T.case("weighted_mean: mean of 1, 2 and 3 with weights 1, 1, 2 is 9/4", function()
  T.near(lib.weighted_mean({1, 2, 3}, {1, 1, 2}), 9 / 4, 1e-15)
end)

T.case("weighted_mean: mismatched lengths are an error", function()
  T.raises(function() lib.weighted_mean({1, 2}, {1}) end, "as many weights")
end)

T.finish()
)LUA";

const char* const kReadme = R"LUA(# @NAME@

A smi-lua library. Use it from a study:

    smi-lua --lib path/to/@NAME@ study.lua      # or SMI_PATH=path/to/@NAME@
    local @NAME@ = require "@NAME@"

Test it: `smi-lua test path/to/@NAME@`. Release it: raise `version` in smi-lib.lua
and tag the commit (`git tag v0.1.0`); studies record the version, content hash and commit.
Other teams install a release with `smi-lua libs add <repository>@v0.1.0` (or from
`smi-lua libs pack path/to/@NAME@`, a .tar.gz with checksums).
)LUA";

}  // namespace

int cmd_new_lib(const Args&, const std::vector<std::string>& args) {
  if (args.empty() || args.size() > 2) {
    std::fprintf(stderr, "usage: smi-lua new-lib NAME [DIR]   (DIR defaults to ./NAME)\n");
    return 2;
  }
  const std::string name = args[0];
  if (!vm::valid_library_name(name)) {
    std::fprintf(stderr,
                 "smi-lua new-lib: '%s' is not a valid library name: use letters, digits and '_', not starting "
                 "with a digit (it is the first part of module names: require \"%s.module\")\n",
                 name.c_str(), name.c_str());
    return 2;
  }
  const fs::path dir = args.size() == 2 ? fs::path(args[1]) : fs::path(name);
  std::error_code ec;
  if (fs::exists(dir, ec) && !(fs::is_directory(dir, ec) && fs::is_empty(dir, ec))) {
    std::fprintf(stderr, "smi-lua new-lib: '%s' already exists and is not an empty folder; choose another DIR\n",
                 dir.string().c_str());
    return 1;
  }
  write_file(dir / vm::kManifestName, subst(kManifest, name));
  write_file(dir / "init.lua", subst(kInit, name));
  write_file(dir / "tests" / ("test_" + name + ".lua"), subst(kTest, name));
  write_file(dir / "README.md", subst(kReadme, name));
  std::printf("created library '%s' in %s: smi-lib.lua, init.lua, tests/test_%s.lua, README.md\n", name.c_str(),
              dir.string().c_str(), name.c_str());
  std::printf("run its tests:   smi-lua test %s\n", dir.string().c_str());
  std::printf("use it:          smi-lua --lib %s study.lua   (require \"%s\")\n", dir.string().c_str(), name.c_str());
  return 0;
}

}  // namespace smi::cli
