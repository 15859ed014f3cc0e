// SPDX-License-Identifier: MIT
#include "repl/repl.hpp"

#include <cstdio>
#include <cstring>
#include <string>

#include "luax/load_guard.hpp"
#include "repl/line_reader.hpp"
#include "repl/printer.hpp"

namespace smi::repl {
namespace {

constexpr const char* kPrompt = "> ";
constexpr const char* kPrompt2 = ">> ";
constexpr const char* kChunkName = "=stdin";

/// Compiles "return <line>"; on success the chunk is on the stack. Stack: [] -> [chunk] or [].
bool load_as_expression(lua_State* L, const std::string& line) {
  const std::string code = "return " + line;
  if (lua::load_buffer(L, code.data(), code.size(), kChunkName) == LUA_OK) return true;
  lua_pop(L, 1);
  return false;
}

/// The REPL's `help` global (stdlib/smi/doc.lua): help(smi.kde), help "bandwidth", help().
/// Loaded lazily by a small stub so that starting the REPL does not parse the reference.
constexpr const char* kHelpStub =
    "if help == nil then help = function(...) return require('smi.doc').help(...) end end";

/// "?smi.kde" / "? bandwidth" / "?" -> help("smi.kde") / help("bandwidth") / help() (as in trepl).
std::string question_to_help(const std::string& line) {
  std::size_t a = 1;
  while (a < line.size() && (line[a] == ' ' || line[a] == '\t')) ++a;
  std::size_t b = line.size();
  while (b > a && (line[b - 1] == ' ' || line[b - 1] == '\t')) --b;
  if (a == b) return "help()";
  return "help([==[" + line.substr(a, b - a) + "]==])";
}

}  // namespace

bool incomplete(lua_State* L, int status) {
  if (status != LUA_ERRSYNTAX) return false;
  std::size_t len = 0;
  const char* msg = lua_tolstring(L, -1, &len);
  static constexpr char kEof[] = "<eof>";
  constexpr std::size_t n = sizeof kEof - 1;
  return len >= n && std::strcmp(msg + len - n, kEof) == 0;
}

int run(app::Runtime& rt) {
  lua_State* L = rt.state();
  rt.set_one_line_errors(true);  // an error is one line at the prompt (--traceback: with its traceback)
  LineReader reader(L);
  const char* p1 = reader.interactive() ? kPrompt : "";
  const char* p2 = reader.interactive() ? kPrompt2 : "";
  if (luaL_loadbufferx(L, kHelpStub, std::strlen(kHelpStub), "=help", "t") == LUA_OK) rt.docall(0, 0);
  lua_settop(L, 0);
  for (;;) {
    auto first = reader.read(p1);
    if (!first) break;
    if (reader.interrupted()) continue;  // Ctrl-C at the prompt: a fresh line
    std::string entry = *first;
    const std::string typed = entry;  // history keeps what was typed, not the rewrite below
    if (!entry.empty() && entry[0] == '=') entry = "return " + entry.substr(1);  // Lua 5.1 habit
    if (!entry.empty() && entry[0] == '?') entry = question_to_help(entry);
    lua_settop(L, 0);
    int status = LUA_OK;
    if (!load_as_expression(L, entry)) {
      // A statement, possibly spread over several lines.
      for (;;) {
        status = lua::load_buffer(L, entry.data(), entry.size(), kChunkName);
        if (!incomplete(L, status)) break;
        auto more = reader.read(p2);
        if (!more) break;  // end of input inside a chunk: report the syntax error
        lua_pop(L, 1);
        if (reader.interrupted()) {
          status = -1;  // Ctrl-C abandons the unfinished chunk
          break;
        }
        entry += "\n" + *more;
      }
    }
    reader.remember(entry.rfind("help([==[", 0) == 0 || entry == "help()" ? typed : entry);
    if (status == -1) {
      lua_settop(L, 0);
      continue;
    }
    if (status == LUA_OK) status = rt.docall(0, LUA_MULTRET);
    if (status == LUA_OK && lua_gettop(L) > 0) {
      lua_pushcfunction(L, print_values);
      lua_insert(L, 1);
      status = rt.docall(lua_gettop(L) - 1, 0);
    }
    if (status != LUA_OK) {
      const int code = rt.report(status);
      if (rt.exit_requested()) return code;
    }
  }
  if (reader.interactive()) std::fputs("\n", stdout);
  return 0;
}

}  // namespace smi::repl
