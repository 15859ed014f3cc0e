// SPDX-License-Identifier: MIT
#include "vm/manifest.hpp"

#include <fmt/format.h>

#include <cerrno>
#include <cstring>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/path_walk.hpp"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>
#include <lua.hpp>

#include "platform/core/errors.hpp"

namespace smi::vm {
namespace {

constexpr std::size_t kMemoryCeiling = 1 << 20;  // bytes of Lua heap a manifest may use
constexpr int kInstructionBudget = 100000;       // a manifest is a few assignments

struct Heap {
  std::size_t used = 0;
};

void* manifest_alloc(void* ud, void* ptr, std::size_t osize, std::size_t nsize) {
  auto* h = static_cast<Heap*>(ud);
  const std::size_t old = ptr ? osize : 0;
  if (nsize == 0) {
    std::free(ptr);
    h->used -= old;
    return nullptr;
  }
  if (nsize > old && h->used + (nsize - old) > kMemoryCeiling) return nullptr;
  void* p = std::realloc(ptr, nsize);
  if (p) h->used = h->used - old + nsize;
  return p;
}

void budget_hook(lua_State* L, lua_Debug*) {
  luaL_error(L, "the manifest ran more than %d instructions (a manifest holds data only)", kInstructionBudget);
}

/// Owns the throwaway state.
struct State {
  Heap heap;
  lua_State* L = lua_newstate(manifest_alloc, &heap);
  ~State() {
    if (L) lua_close(L);
  }
};

std::string where(const std::filesystem::path& file) { return "library manifest '" + file.string() + "'"; }

/// The whole Lua string at `idx`, NUL bytes included (a name cut at a NUL would pass the checks).
std::string text_at(lua_State* L, int idx) {
  std::size_t n = 0;
  const char* s = lua_tolstring(L, idx, &n);
  return std::string(s, n);
}

std::string string_field(lua_State* L, const std::filesystem::path& file, const char* field, bool required) {
  lua_getfield(L, -1, field);
  std::string v;
  if (lua_type(L, -1) == LUA_TSTRING) {
    v = text_at(L, -1);
  } else if (!lua_isnil(L, -1) || required) {
    const std::string got = lua_isnil(L, -1) ? "nothing" : std::string("a ") + luaL_typename(L, -1);
    lua_pop(L, 1);
    throw Error(where(file) + ": field '" + field + "' must be a string, got " + got +
                (required ? std::string(" (add e.g. ") + field + " = \"" +
                                (std::string(field) == "version" ? "0.1.0" : "mylib") + "\")"
                          : ""));
  }
  lua_pop(L, 1);
  return v;
}

/// The list fields of a manifest (requires, sources) into `m`; stack: [..., manifest table].
void read_lists(lua_State* L, const std::filesystem::path& file, Manifest& m) {
  lua_getfield(L, -1, "requires");
  if (lua_istable(L, -1)) {
    const lua_Integer n = static_cast<lua_Integer>(lua_rawlen(L, -1));
    for (lua_Integer i = 1; i <= n; ++i) {
      lua_rawgeti(L, -1, i);
      if (lua_type(L, -1) != LUA_TSTRING)
        throw Error(where(file) + ": requires[" + std::to_string(i) + "] must be a string like \"other >= 1.2\", got a " +
                    luaL_typename(L, -1));
      try {
        m.requires_.push_back(Requirement::parse(text_at(L, -1)));
      } catch (const Error& e) {
        throw Error(where(file) + ": requires[" + std::to_string(i) + "]: " + e.what());
      }
      lua_pop(L, 1);
    }
  } else if (!lua_isnil(L, -1)) {
    throw Error(where(file) + ": field 'requires' must be a list of strings like {\"other >= 1.2\"}, got a " +
                luaL_typename(L, -1));
  }
  lua_pop(L, 1);
  lua_getfield(L, -1, "sources");
  if (lua_istable(L, -1)) {
    lua_pushnil(L);
    while (lua_next(L, -2)) {
      if (lua_type(L, -2) != LUA_TSTRING || lua_type(L, -1) != LUA_TSTRING)
        throw Error(where(file) + ": field 'sources' must map library names to where they are fetched, like "
                    "{kdetools = \"https://git.example.org/kdetools.git\"}; found a " + luaL_typename(L, -2) +
                    " key with a " + luaL_typename(L, -1) + " value");
      const std::string key = text_at(L, -2), value = text_at(L, -1);
      if (value.find('\0') != std::string::npos || key.find('\0') != std::string::npos)
        throw Error(where(file) + ": field 'sources': the entry for '" + key.substr(0, key.find('\0')) +
                    "' holds a NUL byte; write the address as text");
      m.sources[key] = value;
      lua_pop(L, 1);
    }
  } else if (!lua_isnil(L, -1)) {
    throw Error(where(file) + ": field 'sources' must be a table like {kdetools = \"https://...\"}, got a " +
                luaL_typename(L, -1));
  }
  lua_pop(L, 1);
}

}  // namespace

std::string visible_text(const std::string& s) {
  std::string out;
  for (char c : s) out += c == '\0' ? std::string("\\0") : std::string(1, c);
  return out;
}

bool valid_library_name(const std::string& n) {
  if (n.empty() || std::isdigit(static_cast<unsigned char>(n[0]))) return false;
  for (char c : n)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') return false;
  return true;
}

Manifest parse_manifest(const std::string& text, const std::filesystem::path& file) {
  State st;
  lua_State* L = st.L;
  if (!L) throw Error("cannot create a Lua state to read " + where(file));
  const std::string chunk = fmt::format("@{}", file.string());
  if (luaL_loadbufferx(L, text.data(), text.size(), chunk.c_str(), "t") != LUA_OK)
    throw Error(where(file) + " does not load: " + std::string(lua_tostring(L, -1)));
  lua_newtable(L);  // the environment: empty, so the manifest sees no function at all
  lua_pushvalue(L, -1);
  lua_setupvalue(L, -3, 1);  // _ENV of the main chunk; stack: [chunk, env]
  lua_insert(L, -2);         // [env, chunk]
  lua_sethook(L, budget_hook, LUA_MASKCOUNT, kInstructionBudget);
  if (lua_pcall(L, 0, 1, 0) != LUA_OK) {
    const char* msg = lua_tostring(L, -1);
    throw Error(where(file) + " failed: " + (msg ? msg : "out of memory") +
                " (a manifest only assigns name, version, description and requires)");
  }
  lua_sethook(L, nullptr, 0, 0);
  // A returned table wins; otherwise the globals the manifest assigned.
  if (!lua_istable(L, -1)) lua_pop(L, 1);  // [env]
  else lua_remove(L, -2);                  // [returned]

  static const char* const kKnown[] = {"name", "version", "description", "requires", "sources", "license", "authors", "homepage"};
  // In name order: of several unknown fields the one named is the same every run (the table's
  // traversal order changes from process to process).
  std::vector<std::string> keys;
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    lua_pop(L, 1);
    keys.push_back(lua_type(L, -1) == LUA_TSTRING ? lua_tostring(L, -1) : "(a non-string key)");
  }
  std::sort(keys.begin(), keys.end());
  for (const std::string& key : keys) {
    bool known = false;
    for (const char* k : kKnown) known = known || key == k;
    if (!known) {
      std::string hint = key == "require" || key == "requirements" || key == "depends" || key == "dependencies"
                             ? " (did you mean 'requires'?)"
                             : "";
      throw Error(where(file) + ": unknown field '" + key + "'" + hint +
                  "; known fields: name, version, description, requires, sources, license, authors, homepage");
    }
  }

  Manifest m;
  m.file = file;
  m.name = string_field(L, file, "name", true);
  if (!valid_library_name(m.name))
    throw Error(where(file) + ": name '" + visible_text(m.name) +
                "' is not a valid library name (letters, digits and '_', not starting with a digit: it is "
                "the first part of module names, require \"" + m.name + ".module\")");
  const std::string ver = string_field(L, file, "version", true);
  try {
    m.version = Version::parse(ver);
  } catch (const Error& e) {
    throw Error(where(file) + ": field 'version': " + e.what());
  }
  m.description = string_field(L, file, "description", false);
  read_lists(L, file, m);
  return m;
}

Manifest read_manifest(const std::filesystem::path& file) {
  // Read as the sandbox reads: the manifest must be a regular file inside its
  // library folder (a symlink to /dev/zero, a FIFO or a file elsewhere would hang the run before
  // any script code, or read what the library may not), at most 1 MiB.
  const pathwalk::Walk w = pathwalk::walk(file.string(), true);
  std::error_code ec;
  const std::string folder = std::filesystem::weakly_canonical(std::filesystem::absolute(file.parent_path(), ec), ec).string();
  if (w.error || !w.exists || !S_ISREG(w.st.st_mode) || !pathwalk::within(w.canonical(), folder))
    throw Error("cannot read " + where(file) + ": not a regular file inside the library folder");
  const pathwalk::Fd fd(::openat(w.dir.get(), w.leaf.c_str(), O_RDONLY | O_NOFOLLOW | O_NONBLOCK | O_CLOEXEC));
  std::string text;
  if (!fd || !pathwalk::read_all(fd.get(), text, 1 << 20))
    throw Error("cannot read " + where(file) + ": " + std::strerror(errno));
  return parse_manifest(text, file);
}

Manifest read_library_folder(const std::filesystem::path& dir) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(dir / kManifestName, ec))
    throw Error("'" + dir.string() + "' is not a library folder: it has no " + kManifestName +
                " (make one with smi-lua new-lib NAME)");
  return read_manifest(dir / kManifestName);
}

}  // namespace smi::vm
