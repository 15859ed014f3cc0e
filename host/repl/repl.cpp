#include "repl/repl.hpp"

#include <cstdio>
#include <cstring>
#include <string>

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
  if (luaL_loadbufferx(L, code.data(), code.size(), kChunkName, "t") == LUA_OK) return true;
  lua_pop(L, 1);
  return false;
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

int run(vm::Runtime& rt) {
  lua_State* L = rt.state();
  LineReader reader(L);
  const char* p1 = reader.interactive() ? kPrompt : "";
  const char* p2 = reader.interactive() ? kPrompt2 : "";
  for (;;) {
    auto first = reader.read(p1);
    if (!first) break;
    if (reader.interrupted()) continue;  // Ctrl-C at the prompt: a fresh line
    std::string entry = *first;
    if (!entry.empty() && entry[0] == '=') entry = "return " + entry.substr(1);  // Lua 5.1 habit
    lua_settop(L, 0);
    int status = LUA_OK;
    if (!load_as_expression(L, entry)) {
      // A statement, possibly spread over several lines.
      for (;;) {
        status = luaL_loadbufferx(L, entry.data(), entry.size(), kChunkName, "t");
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
    reader.remember(entry);
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
