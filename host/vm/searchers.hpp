// SPDX-License-Identifier: MIT
#pragma once
// Where `require` looks, in order (package.searchers is replaced wholesale):
//   1. package.preload
//   2. the stdlib: from --stdlib-dir / SMI_STDLIB_DIR when given (development), else compiled in
//   3. Lua files under the script's folder, the --lib folders and SMI_PATH (text chunks only,
//      each candidate checked by the sandbox policy)
// There is no C searcher and no package.loadlib. A failed require lists every place searched.
#include <filesystem>
#include <vector>
#include <lua.hpp>

namespace smi::vm {

struct ModuleSearch {
  std::filesystem::path stdlib_dir;               // empty: the embedded stdlib only
  std::vector<std::filesystem::path> roots;       // script folder, --lib, SMI_PATH, in that order

  /// The folders to search for module `name`, in order. The one place to extend (library
  /// manifests, per-module roots) without touching the searcher itself.
  std::vector<std::filesystem::path> candidate_roots(const char* name) const;
};

/// Replaces package.searchers and clears package.path/cpath. `ms` must outlive the state.
void install_searchers(lua_State* L, const ModuleSearch* ms);

/// "a.b" -> "a/b"; throws smi::Error for names that could climb out of a root ("..", "/").
std::filesystem::path module_relpath(const char* name);

}  // namespace smi::vm
