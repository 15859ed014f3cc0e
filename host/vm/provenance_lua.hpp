// SPDX-License-Identifier: MIT
#pragma once
// smi.provenance(): everything a run's numbers depend on, as results.json records it
// under "provenance" and `smi-lua verify` re-checks it:
//   smi_lua, lua, build = {compiler =, eigen =, nlopt =, sqlite =, re2 =, ...}, seed,
//   command = {argv...}, cwd, arguments = {script args...}, options = {seed =, executor =, ...},
//   script = {path =, hash =}, files = {[path] = {kind =, hash =, size = [, large =, mtime =]}},
//   programs = {{name =, path =, hash =, version =}, ...}, libraries = {... as smi.libraries,
//   with hash and files}.
// The files are the ones the run read so far (runtime's RunRecord), so a study asks again after
// every step. Helpers for smi.study's per-step inputs, handed to the stdlib only
// (internal_functions.hpp): inputs(since), digest(path), sha256(text), not_input(path).
#include <lua.hpp>

#include "platform/core/run_record.hpp"
#include "vm/libraries.hpp"

namespace smi::vm {

/// Sets smi.provenance and the stdlib's internal helpers. `libs` must outlive the state. Stack: unchanged.
void install_provenance(lua_State* L, const LibrarySet* libs);

/// Pushes {name = version} of build_info() (also used by smi.provenance). Stack: +1.
void push_build_info(lua_State* L);

/// Pushes one file digest as {hash =, size = [, large = true, mtime =]}. Stack: +1.
void push_digest(lua_State* L, const FileDigest& d);

}  // namespace smi::vm
