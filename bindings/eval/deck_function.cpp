// SPDX-License-Identifier: MIT
// A command model's deck made by a Lua function of the point (template = function(p) ... end):
// a deck can compute (per-node stiffnesses, log-scaled inputs) while the study's evaluation
// depends on nothing but the point. The function runs in a Lua state of its own
// (luax/isolated_state.hpp), so it shares no object with the study: no file handle, no
// metatable (not even the string metatable), no table the study can still change. The function
// and what it captures are copied into that state when the model is made; each deck is a call
// with the point and the constants, copied in as numbers and strings, and the text comes out.
#include <fmt/format.h>

#include "bindings/eval/model.hpp"
#include "luax/isolated_state.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::eval {

std::function<std::string(const Eigen::VectorXd&)> deck_renderer(lua_State* L, int idx, const smi::eval::CommandConfig& cfg,
                                                                  const char* fname) {
  idx = lua_absindex(L, idx);
  if (lua_type(L, idx) != LUA_TFUNCTION || lua_iscfunction(L, idx))
    throw InvalidArgument(fmt::format("{}: option 'template' as a function must be a Lua function(p) returning the "
                                      "deck text", fname));
  auto state = std::make_shared<lua::IsolatedState>(L, &lua::cancel_token(L));
  if (const std::string why = state->adopt_function(L, idx); !why.empty()) {
    lua_Debug ar;
    lua_pushvalue(L, idx);
    lua_getinfo(L, ">S", &ar);
    throw InvalidArgument(fmt::format(
        "{}: the deck function (template, defined at {}:{}) cannot be copied into its own Lua state: {}; a deck "
        "function takes from outside only numbers, strings, booleans, tables without metatables and Lua functions "
        "of these (and the standard string, math, table and utf8 functions): give anything else through the "
        "model's constants or the point, or make it inside the function",
        fname, ar.short_src, ar.linedefined, why));
  }
  return [state, &cfg](const Eigen::VectorXd& x) {
    std::vector<lua::IsolatedState::Field> fields;
    fields.reserve(cfg.constants.size() + cfg.inputs.size());
    for (const auto& [k, v] : cfg.constants) fields.push_back({k, v.is_number, v.number, v.text});
    for (std::size_t j = 0; j < cfg.inputs.size(); ++j)
      fields.push_back({cfg.inputs[j], true, x[static_cast<Eigen::Index>(j)], ""});
    return state->call(fields, "the deck function");  // inputs after constants: a point's value wins
  };
}

}  // namespace smi::bind::eval
