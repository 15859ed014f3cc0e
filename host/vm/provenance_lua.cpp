// SPDX-License-Identifier: MIT
#include "vm/provenance_lua.hpp"

#include <cstring>
#include <filesystem>
#include <string>

#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "luax/run_context.hpp"
#include "platform/core/sha256.hpp"
#include "vm/build_info.hpp"
#include "vm/embedded_stdlib.hpp"
#include "vm/internal_functions.hpp"
#include "vm/library_lua.hpp"

namespace smi::vm {
namespace {

const LibrarySet& libs_of(lua_State* L) {
  return *static_cast<const LibrarySet*>(lua_touserdata(L, lua_upvalueindex(1)));
}

void set_string(lua_State* L, const char* key, const std::string& v) {
  lua_pushlstring(L, v.data(), v.size());
  lua_setfield(L, -2, key);
}

void push_strings(lua_State* L, const std::vector<std::string>& v) {
  lua_createtable(L, static_cast<int>(v.size()), 0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    lua_pushlstring(L, v[i].data(), v[i].size());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

/// {[path] = {kind =, hash =, size = ...}} of the files with seq > since. Stack: +1.
void push_files(lua_State* L, const std::map<std::string, InputFile>& files, std::uint64_t since) {
  lua_newtable(L);
  for (const auto& [path, f] : files) {
    if (f.seq <= since) continue;
    push_digest(L, f.digest);
    set_string(L, "kind", f.kind);
    if (f.changed_during_run) {
      lua_pushboolean(L, 1);
      lua_setfield(L, -2, "changed_during_run");
    }
    lua_setfield(L, -2, path.c_str());
  }
}

/// smi-lua's options that change results: {seed = "42", executor = "local", ["slurm-opt"] = {...}}.
void push_options(lua_State* L, const RunRecord& r) {
  lua_newtable(L);
  for (const auto& [k, v] : r.options) {
    if (k == "slurm-opt") {  // repeatable: a list
      if (lua_getfield(L, -1, k.c_str()) != LUA_TTABLE) {
        lua_pop(L, 1);
        lua_newtable(L);
        lua_pushvalue(L, -1);
        lua_setfield(L, -3, k.c_str());
      }
      lua_pushlstring(L, v.data(), v.size());
      lua_rawseti(L, -2, static_cast<lua_Integer>(lua_rawlen(L, -2) + 1));
      lua_pop(L, 1);
    } else {
      set_string(L, k.c_str(), v);
    }
  }
}

int smi_provenance(lua_State* L) {
  bool files = true;
  if (lua_istable(L, 1)) {
    lua_getfield(L, 1, "files");
    if (!lua_isnil(L, -1)) files = lua_toboolean(L, -1);
    lua_pop(L, 1);
  } else if (!lua_isnoneornil(L, 1)) {
    return luaL_argerror(L, 1, "expected an options table like {files = false}");
  }
  const LibrarySet& set = libs_of(L);
  const lua::Policy& pol = lua::policy(L);
  const RunContext& ctx = lua::run_context(L);
  // Hash everything first (C++ work that may throw), then build the table.
  std::map<std::string, InputFile> read;
  std::vector<ProgramRun> programs;
  std::string script_hash;
  lua::protect(L, "smi.provenance", [&] {
    for (const Library& l : set.all()) l.hash();
    if (pol.record) {
      read = pol.record->files();
      programs = pol.record->programs();
    }
    if (!ctx.script_path.empty()) {
      const auto it = read.find(lua::resolve_path(ctx.script_path).string());
      script_hash = it != read.end() ? it->second.digest.hash : "sha256:" + sha256_file(ctx.script_path);
    }
    return 0;
  });
  lua_newtable(L);
  set_string(L, "smi_lua", host_version());
  set_string(L, "lua", LUA_RELEASE);
  push_build_info(L);
  lua_setfield(L, -2, "build");
  lua_pushinteger(L, static_cast<lua_Integer>(ctx.seed));
  lua_setfield(L, -2, "seed");
  if (pol.record) {
    push_strings(L, pol.record->command_line);
    lua_setfield(L, -2, "command");
    set_string(L, "cwd", pol.record->cwd);
    push_strings(L, pol.record->script_args);
    lua_setfield(L, -2, "arguments");
    push_options(L, *pol.record);
    lua_setfield(L, -2, "options");
  }
  if (!ctx.script_path.empty()) {
    lua_newtable(L);
    set_string(L, "path", lua::resolve_path(ctx.script_path).string());  // absolute: verify runs from anywhere
    set_string(L, "hash", script_hash);
    lua_setfield(L, -2, "script");
  }
  push_files(L, read, 0);
  lua_setfield(L, -2, "files");
  lua_createtable(L, static_cast<int>(programs.size()), 0);
  for (std::size_t i = 0; i < programs.size(); ++i) {
    const ProgramRun& p = programs[i];
    push_digest(L, p.digest);
    set_string(L, "name", p.name);
    set_string(L, "path", p.path);
    if (!p.version.empty()) set_string(L, "version", p.version);
    if (!p.version_line.empty()) set_string(L, "version_line", p.version_line);
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "programs");
  lua_createtable(L, static_cast<int>(set.all().size()), 0);
  int i = 0;
  for (const Library& l : set.all()) {
    lua_newtable(L);
    push_library_fields(L, l);  // libs: where a library came from (source, locked commit) goes there
    set_string(L, "hash", l.hash().digest);
    if (files) {
      lua_newtable(L);
      for (const auto& [rel, digest] : l.hash().files) set_string(L, rel.c_str(), digest);
      lua_setfield(L, -2, "files");
    }
    lua_rawseti(L, -2, ++i);
  }
  lua_setfield(L, -2, "libraries");
  return 1;
}

/// internal.inputs([since]) -> {seq =, files = {[path] = digest}}: the files read after `since`
/// (a seq an earlier call returned), for smi.study's per-step inputs.
int internal_inputs(lua_State* L) {
  const auto since = static_cast<std::uint64_t>(luaL_optinteger(L, 1, 0));
  const lua::Policy& pol = lua::policy(L);
  std::map<std::string, InputFile> read;
  std::uint64_t seq = 0;
  if (pol.record) {
    read = pol.record->files();
    seq = pol.record->seq();
  }
  lua_createtable(L, 0, 2);
  lua_pushinteger(L, static_cast<lua_Integer>(seq));
  lua_setfield(L, -2, "seq");
  push_files(L, read, since);
  lua_setfield(L, -2, "files");
  return 1;
}

/// internal.digest(path [, kind]) -> digest | nil, why: a recorded file's digest now, opened through
/// the sandbox (without being recorded as read); "embedded:..." paths from this binary's stdlib;
/// kind "program": a program --allow-exec allows; kind "binary": this smi-lua's own executable
/// (path ignored), which smi.study's reuse of saved steps compares (a rebuilt smi-lua reruns them).
int internal_digest(lua_State* L) {
  const std::string path = luaL_checkstring(L, 1);
  const char* kind = luaL_optstring(L, 2, "");
  const bool program = std::strcmp(kind, "program") == 0;
  if (std::strcmp(kind, "binary") == 0) {
    FileDigest d;
    // the running image, even if the file was replaced since it started
    lua::protect(L, "smi.study", [&] {
      d = digest_path("/proc/self/exe");
      return 0;
    });
    push_digest(L, d);
    return 1;
  }
  if (path.rfind("embedded:", 0) == 0) {
    const std::string rel = path.substr(std::strlen("embedded:"));
    for (const EmbeddedModule* m = kEmbeddedModules; m->name; ++m) {
      if (rel != m->path) continue;
      FileDigest d;
      d.size = m->size;
      d.hash = "sha256:" + sha256_hex(std::string_view(m->data, m->size));
      push_digest(L, d);
      return 1;
    }
    lua_pushnil(L);
    lua_pushstring(L, "this smi-lua has no such embedded module");
    return 2;
  }
  FileDigest d;
  std::string why;
  lua::protect(L, "smi.study", [&] {
    try {
      if (program) {
        d = digest_path(lua::policy(L).check_exec(path, "smi.study").string());
      } else {
        const lua::CheckedFile f = lua::policy(L).open_read_unrecorded(path);
        d = digest_fd(f.fd.get(), path);
      }
    } catch (const Error& e) {  // missing, unreadable or refused: a difference, not a failure
      why = e.what();
    }
    return 0;
  });
  if (!why.empty()) {
    lua_pushnil(L);
    lua_pushstring(L, why.c_str());
    return 2;
  }
  push_digest(L, d);
  return 1;
}

/// internal.not_input(path): reads of `path` are outputs of the run, not inputs (smi.study's
/// results file when it lies outside --out). Only a path the run may write: a file it can only
/// read is an input whatever the study calls it.
int internal_not_input(lua_State* L) {
  const std::string path = luaL_checkstring(L, 1);
  lua::protect(L, "smi.study", [&] {
    const lua::Policy& pol = lua::policy(L);
    const std::filesystem::path resolved = lua::resolve_path(path);
    bool writable = pol.unrestricted;
    for (const auto& root : pol.write_roots) writable = writable || lua::path_within(resolved, root);
    if (!writable)
      throw lua::SandboxDenied("the results file '" + path + "' does not lie under --out or an --allow-write folder, so "
                          "the study cannot write it; give results = a path under " + pol.out_dir.string());
    if (RunRecord* r = pol.record) r->exclude(resolved.string());
    return 0;
  });
  return 0;
}

/// internal.sha256(text) -> "sha256:<hex>" (step results, options).
int internal_sha256(lua_State* L) {
  std::size_t n = 0;
  const char* s = luaL_checklstring(L, 1, &n);
  const std::string h = "sha256:" + sha256_hex(std::string_view(s, n));
  lua_pushstring(L, h.c_str());
  return 1;
}

}  // namespace

void push_build_info(lua_State* L) {
  lua_newtable(L);
  for (const auto& [k, v] : build_info()) set_string(L, k.c_str(), v);
}

void push_digest(lua_State* L, const FileDigest& d) {
  lua_newtable(L);
  if (!d.hash.empty()) set_string(L, "hash", d.hash);
  lua_pushinteger(L, static_cast<lua_Integer>(d.size));
  lua_setfield(L, -2, "size");
  if (d.large) {  // too large to hash (over 1 GB): size and mtime stand for the content
    lua_pushboolean(L, 1);
    lua_setfield(L, -2, "large");
    lua_pushinteger(L, static_cast<lua_Integer>(d.mtime));
    lua_setfield(L, -2, "mtime");
  }
}

void install_provenance(lua_State* L, const LibrarySet* libs) {
  lua_getglobal(L, "smi");
  lua_pushlightuserdata(L, const_cast<LibrarySet*>(libs));
  lua_pushcclosure(L, smi_provenance, 1);
  lua_setfield(L, -2, "provenance");
  lua_pushinteger(L, kResultsSchema);  // what smi.study writes as results.json's "schema"
  lua_setfield(L, -2, "results_schema");
  lua_pop(L, 1);
  // for smi.study and smi.study_inputs only (internal_functions.hpp)
  set_internal_function(L, "inputs", internal_inputs);
  set_internal_function(L, "digest", internal_digest);
  set_internal_function(L, "sha256", internal_sha256);
  set_internal_function(L, "not_input", internal_not_input);
}

}  // namespace smi::vm
