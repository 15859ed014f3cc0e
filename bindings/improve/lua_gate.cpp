// SPDX-License-Identifier: MIT
#include "bindings/improve/lua_gate.hpp"

#include <exception>

#include "bindings/improve/lua_values.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

namespace {

struct Turn {
  const std::function<void()>* body;
  std::exception_ptr thrown;
};

/// Runs the turn's body; a C++ exception is kept for the caller (a Lua error, not derived from
/// std::exception, unwinds to the pcall in LuaGate::run). Its arguments are copies of the
/// calling frame's slots, so the callbacks' absolute slots name the same values here, then the turn.
int run_turn(lua_State* L) {
  auto* turn = static_cast<Turn*>(lua_touserdata(L, lua_gettop(L)));
  try {
    (*turn->body)();
  } catch (const std::exception&) {
    turn->thrown = std::current_exception();
  }
  return 0;
}

}  // namespace

void LuaGate::run(const std::function<void()>& body) const {
  const std::lock_guard<std::mutex> lock(*mutex_);
  Turn turn{&body, nullptr};
  {
    StackGuard guard(L_);
    const int slots = lua_gettop(L_);
    if (!lua_checkstack(L_, slots + 3)) throw Error("out of memory for the Lua stack of a model call");
    lua_pushcfunction(L_, run_turn);
    for (int i = 1; i <= slots; ++i) lua_pushvalue(L_, i);
    lua_pushlightuserdata(L_, &turn);
    lua::call(L_, slots + 1, 0);  // a Lua error in the turn: LuaError, thrown here
  }
  if (turn.thrown) std::rethrow_exception(turn.thrown);
}

}  // namespace smi::bind::improve
