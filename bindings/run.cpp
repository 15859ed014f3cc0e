// SPDX-License-Identifier: MIT
// The run-level functions of the smi table: the output folder and its lock, whole-file writes,
// the clock, the run's warnings and progress label, and failures (texts: run_doc.cpp). They act
// on the run through the policy and run context the runtime puts in the registry (luax).
#include <chrono>
#include <string>
#include <string_view>
#include <vector>

#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "luax/run_context.hpp"
#include "luax/user_error.hpp"
#include "platform/core/atomic_file.hpp"
#include "platform/eval/folder_lock.hpp"

namespace smi::bind {
namespace {

/// smi.out(name): a path in the output folder (created now). Stack: [name] -> [path].
int smi_out(lua_State* L) {
  const char* name = luaL_optstring(L, 1, "");
  std::string path;
  lua::protect(L, "smi.out", [&] {
    path = (lua::policy(L).ensure_out_dir() / name).string();
    return 0;
  });
  lua_pushstring(L, path.c_str());
  return 1;
}

/// smi.now(): wall-clock seconds from a monotonic clock, for timing steps that wait on solver
/// processes (os.clock counts only this process's CPU time).
int smi_now(lua_State* L) {
  const auto t = std::chrono::steady_clock::now().time_since_epoch();
  lua_pushnumber(L, std::chrono::duration<double>(t).count());
  return 1;
}

/// smi.write_file(path, text): writes the whole file atomically (temporary file, fsync, rename;
/// core/atomic_file.hpp) after the sandbox's write check; raises naming the file and the reason
/// (disk full) and leaves the old file as it was. Stack: [path, text] -> [path].
int smi_write_file(lua_State* L) {
  const char* path = luaL_checkstring(L, 1);
  std::size_t len = 0;
  const char* text = luaL_checklstring(L, 2, &len);
  lua::protect(L, "smi.write_file", [&] {
    // The folder is walked by the sandbox and the target must not be a symlink; the temporary
    // file is created O_EXCL | O_NOFOLLOW there and renamed over the target (core/atomic_file).
    const std::string p = lua::policy(L).checked_write_file(path);
    write_file_atomic(p, std::string_view(text, len));
    return 0;
  });
  lua_settop(L, 1);
  return 1;
}

/// smi.lock_out([folder]): takes this process's lock on the output folder (default --out;
/// eval/folder_lock.hpp); a study calls it before its first step. Raises naming the holder if
/// another process has it.
int smi_lock_out(lua_State* L) {
  const char* folder = luaL_optstring(L, 1, nullptr);
  lua::protect(L, "smi.lock_out", [&] {
    const lua::Policy& pol = lua::policy(L);
    // The output folder is a write root itself (made and checked by ensure_out_dir); any other
    // folder must lie below a write root.
    const std::string out = pol.ensure_out_dir().string();
    smi::eval::lock_output_folder(!folder || lua::resolve_path(folder) == out ? out : pol.checked_write_dir(folder));
    return 0;
  });
  return 0;
}

/// smi.progress_label([text]): what the progress lines that follow belong to ("[beam] step 2/5
/// calibrate"), written in front of each; nil clears it. Stack: [text] -> [].
int smi_progress_label(lua_State* L) {
  const char* text = luaL_optstring(L, 1, "");
  lua::run_context(L).progress.label = text;
  return 0;
}

/// smi.warnings(): the run's warnings so far ("<function>: <text>", in order), the ones printed on
/// a terminal and the ones --quiet kept off stderr alike. Stack: [] -> [list].
int smi_warnings(lua_State* L) {
  const std::vector<std::string> w = lua::run_context(L).warnings.collected();
  lua_createtable(L, static_cast<int>(w.size()), 0);
  for (std::size_t i = 0; i < w.size(); ++i) {
    lua_pushlstring(L, w[i].data(), w[i].size());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  return 1;
}

const luaL_Reg kRunFunctions[] = {
    {"out", smi_out},
    {"now", smi_now},
    {"write_file", smi_write_file},
    {"lock_out", smi_lock_out},
    {"warnings", smi_warnings},
    {"progress_label", smi_progress_label},
    {"fail", lua::l_fail},  // an error in the user's data, options or declaration (luax/user_error)
    {"failure", lua::l_failure},
    {nullptr, nullptr},
};

}  // namespace

void open_run(lua_State* L) {
  // stack: [smi]
  luaL_setfuncs(L, kRunFunctions, 0);
}

}  // namespace smi::bind
