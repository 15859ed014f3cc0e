// SPDX-License-Identifier: MIT
#pragma once
// Entry points of the binding areas. Each is called by luaopen_smi with the `smi` table on
// top of the stack (stack: [smi] -> [smi]) and adds its fields to it.
//
// The one way a binding registers (README "Where a new kernel goes"):
//   - an area has one open_<area>(L), declared here and called by luaopen_smi (smi.cpp); an area
//     of several files calls one open_<part>(L) per file, declared in <area>/open_parts.hpp;
//   - a part registers its types first: lua::register_type<T> for a box (a C++ object Lua owns),
//     lua::register_table_type for a result table with methods or __tostring;
//   - then its functions: a luaL_Reg list set with luaL_setfuncs into a new table stored as
//     smi.<module>, or a single function stored as smi.<name>;
//   - metatables are named all lowercase after the smi function or module that makes the value
//     (smi.vec, smi.dist, smi.kriging, smi.model, smi.screen_result).
#include <lua.hpp>

namespace smi::bind {

void open_vec(lua_State* L);        // smi.vec            (bindings/vec.cpp)
void open_mat(lua_State* L);        // smi.mat            (bindings/mat.cpp)
void open_rng(lua_State* L);        // smi.rng            (bindings/rng.cpp)
void open_csv(lua_State* L);        // smi.csv            (bindings/csv.cpp)
void open_json(lua_State* L);       // smi.json           (bindings/json.cpp)
void open_stats(lua_State* L);      // smi.dist, smi.kde, smi.kde_bd, smi.kde_ebd, smi.ecdf, smi.metric
void open_surrogate(lua_State* L);  // smi.doe, smi.kriging, smi.propagate, smi.screen
void open_eval(lua_State* L);       // smi.model
void open_improve(lua_State* L);    // smi.calibrate, smi.refine
void open_members(lua_State* L);    // last: the suggesting __index of the module tables (members.cpp)

}  // namespace smi::bind

/// Builds the `smi` module table with every area. Stack: [] -> [smi].
extern "C++" int luaopen_smi(lua_State* L);
