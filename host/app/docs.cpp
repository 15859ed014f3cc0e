// SPDX-License-Identifier: MIT
// smi._docs(): hands the compiled-in reference texts of the C++ side to stdlib/smi/doc.lua,
// with the methods table of every smi userdata type (found in the registry), so that the doc
// module can walk the public API at run time. The texts of the host functions registered in
// runtime.cpp and library_lua.cpp (smi.out, smi.now, smi.write_file, smi.lock_out, smi.warnings,
// smi.libraries, smi.provenance) are here.
#include <cstring>
#include <exception>
#include <string>

#include "app/docs.hpp"
#include "app/runtime.hpp"
#include "luax/luax.hpp"

namespace smi::app {
namespace {

const char* const kHostDoc = R"(
@ module smi
The smi-lua runtime: every kernel is a field of this table (help() lists them).
Values set by the command line: smi.seed (--seed, default ${seed}), smi.quiet (--quiet, or
output not a terminal), smi.out_dir (--out, default smi-out/<script>), smi.script_dir (the
script's folder), smi.version (the program's version), smi.dry_run (--dry-run), smi.pdf (--pdf:
a study also prints its report to PDF).

@ smi.out([name]) -> path
A path in the run's output folder (--out, default smi-out/<script>/), which is created on
first use. Scripts write their files here: the sandbox allows writes under it.
returns: the path as a string (the folder itself when name is omitted)
errors: the folder cannot be created (a file is in the way, or no permission)
example:
  local p = smi.out("table.csv")
  print(p:match("table%.csv$") ~= nil)

@ smi.now() -> seconds
Wall-clock seconds from a monotonic clock, for timing steps that wait on solver processes
(os.clock counts only this process's CPU time).
returns: a number of seconds from an arbitrary origin; differences are durations
errors: none
example:
  local t0 = smi.now()
  print(smi.now() - t0 >= 0)

@ smi.libraries() -> list
The libraries a study sees (--lib, SMI_PATH), as the manifests declare them.
returns: a list of {name =, version =, path =, description =, commit =} (commit when the
  folder is a git checkout)
errors: none (a bad library stops the run before the script starts)
example:
  print(#smi.libraries() >= 0)

@ smi.write_file(path, text) -> path
Writes a whole file atomically: a temporary file in the same folder (created O_EXCL, never
through a symlink), every write checked, fsync, then renamed over the target. A full disk or a
kill leaves the old file as it was. smi.study writes results.json and report.html this way.
returns: the path as given
errors: the sandbox refuses the folder (write only under --out and --allow-write); the target is
  a symlink; a write fails (the message names the file and the reason, e.g. no space left)
example:
  local p = smi.write_file(smi.out("note.txt"), "done\n")
  print(p:match("note%.txt$") ~= nil)

@ smi.lock_out([folder]) -> nothing
Takes this process's lock on an output folder (default --out), so that two studies never share
work folders or results; smi.study calls it before its first step. The lock is released when the
process ends.
returns: nothing
errors: another process holds the lock (the message names its pid, host, start time and command,
  and the fix: wait for it or give another --out); the sandbox refuses the folder
example:
  smi.lock_out()
  print("locked")

@ smi.warnings() -> list
The run's warnings so far, in order, each as "<function>: <text>" (data outside a KDE's bounds,
duplicated CSV rows, an integration grid too coarse for a pdf, ...). Every warning a smi function
gives comes here; it is also printed on stderr as "<function>: warning: <text>" unless the run is
quiet (--quiet, or output not a terminal), so a quiet run loses none.
returns: a list of strings (empty when nothing was warned)
errors: none
example:
  for _, w in ipairs(smi.warnings()) do print(w) end
  print(#smi.warnings() >= 0)

@ smi.fail(message [, traceback]) -> never returns
Raises a failure: an error in the user's data, options or declaration (a missing column, a bad
option value, an unknown distribution family), as opposed to an error in code. smi-lua prints a
failure as one line, "smi-lua: <message>", with no Lua traceback (--traceback adds it); an error
in code keeps its traceback. The message names the culprit (file, line, field, value) and the
fix. The error value is a table whose tostring is the message; string methods (e:find, e:match)
and `..` act on the message, and smi.failure(e) returns it. Every check of smi's own raises one,
and so does a smi function called by the stdlib. With a traceback (a step of smi.study catching an
error in the user's code), the failure carries that traceback, which is printed under it.
returns: never (raises)
errors: always: the failure
example:
  local msg = "tests.csv: no column 'mode2_Hz' (did you mean mode_2_Hz?); columns: mode_1_Hz, mode_2_Hz"
  local ok, e = pcall(smi.fail, msg)
  print(ok, smi.failure(e), e:find('mode2') ~= nil)

@ smi.failure(e) -> message | nil
The message of a failure raised by smi.fail (or by a smi check), nil for any other error value:
tells an error in the user's data or declaration from an error in code after a pcall.
returns: a string, or nil
errors: none
example:
  local _, e = pcall(smi.fail, 'bad value')
  local _, plain = pcall(error, 'plain error')
  print(smi.failure(e), smi.failure(plain))

@ smi.progress_label([text]) -> nothing
What the progress lines that follow belong to, written in front of each ("[beam] step 4/7
calibrate: calibration: start 2/4, 310 evaluations"); no text clears it. smi.study sets it to
the step that runs.
returns: nothing
errors: none
example:
  smi.progress_label('[demo] fit')
  smi.progress_label()
  print("ok")

@ smi.provenance([opts]) -> table
What this run's numbers depend on so far: every file it read (Lua modules, dofile/loadfile
chunks, data, priors, templates, the embedded stdlib modules), each with its SHA-256 taken from
the bytes read (files over 1 GB: size and mtime, marked large); every program a model runs (path,
SHA-256, declared version); the command line, the script's arguments and smi-lua's options that
change results (seed, executor, --slurm-opt, --timeout, --max-memory, --store); the version and
build of smi-lua (compiler, Lua, Eigen, NLopt, SQLite, RE2, nettle, fmt); every library's version,
content hash and git commit. smi.study records it in results.json after every step (schema 2,
docs/provenance.md); `smi-lua verify results.json` hashes it all again.
options:
  files = true  -- include each library file's SHA-256 (false: only the folder hash)
returns: {smi_lua =, lua =, build = {compiler =, eigen =, ...}, seed =, command = {...}, cwd =,
  arguments = {...}, options = {seed =, executor =, ...}, script = {path =, hash =},
  files = {[path] = {kind = "lua" | "data" | "stdlib" | "program" | "script", hash =, size =
  [, large = true, mtime =]}}, programs = {{name =, path =, hash =, size =, version =}, ...},
  libraries = {{name =, version =, path =, hash =, commit =, source =, files = {...}}, ...}}
  (source and commit of a library of the project's tree come from smi-lock.json: where `smi-lua
  libs add` fetched it and what it resolved)
errors: a library file that cannot be read
example:
  local p = smi.provenance{files = false}
  print(p.smi_lua ~= nil, p.seed == smi.seed)
)";

/// Pushes {methods table by type name} for every registry metatable named "smi.*".
void push_types(lua_State* L) {
  lua_newtable(L);
  const int out = lua_gettop(L);
  lua_pushnil(L);
  while (lua_next(L, LUA_REGISTRYINDEX)) {  // [out, key, value]
    if (lua_type(L, -2) == LUA_TSTRING && lua_istable(L, -1) && std::strncmp(lua_tostring(L, -2), "smi.", 4) == 0) {
      lua_getfield(L, -1, "__index");  // [out, key, mt, index]
      bool pushed = false;
      if (lua_istable(L, -1)) {
        pushed = true;
      } else if (lua_iscfunction(L, -1) && lua_getupvalue(L, -1, 1)) {  // smi types: methods upvalue
        if (lua_istable(L, -1)) {
          lua_remove(L, -2);
          pushed = true;
        } else {
          lua_pop(L, 1);
        }
      }
      if (pushed) {
        lua_pushvalue(L, -3);  // key
        lua_insert(L, -2);
        lua_settable(L, out);
      } else {
        lua_pop(L, 1);
      }
    }
    lua_pop(L, 1);
  }
}

using BindingDocs = std::vector<lua::DocText> (*)();

int smi_docs(lua_State* L) {
  std::vector<lua::DocText> texts;
  // The bindings' list came with the closure (install_docs), in a userdata upvalue.
  const auto* source = static_cast<const BindingDocs*>(lua_touserdata(L, lua_upvalueindex(1)));
  const int r = lua::protect(L, "smi._docs", [&] {
    texts = (*source)();
    texts.push_back({"host/app/docs.cpp", lua::fill(kHostDoc, {{"seed", std::to_string(kDefaultSeed)}})});
    return 0;
  });
  lua_createtable(L, 0, 2);
  lua_createtable(L, static_cast<int>(texts.size()), 0);
  int i = 0;
  for (const auto& t : texts) {
    lua_createtable(L, 0, 2);
    lua_pushstring(L, t.source);
    lua_setfield(L, -2, "source");
    lua_pushlstring(L, t.text.data(), t.text.size());
    lua_setfield(L, -2, "text");
    lua_rawseti(L, -2, ++i);
  }
  lua_setfield(L, -2, "texts");
  push_types(L);
  lua_setfield(L, -2, "types");
  return r + 1;
}

}  // namespace

void install_docs(lua_State* L, BindingDocs binding_docs) {
  // stack: [smi] -> [smi]. The pointer lives in a full userdata (a function pointer is no
  // void*): [smi, ud] -> [smi, closure].
  auto* slot = static_cast<BindingDocs*>(lua_newuserdatauv(L, sizeof(BindingDocs), 0));
  *slot = binding_docs;
  lua_pushcclosure(L, smi_docs, 1);
  lua_setfield(L, -2, "_docs");
}

}  // namespace smi::app
