#pragma once
// Entry points of the binding areas. Each is called by luaopen_smi with the `smi` table on
// top of the stack (stack: [smi] -> [smi]) and adds its fields to it.
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

}  // namespace smi::bind

/// Builds the `smi` module table with every area. Stack: [] -> [smi].
extern "C++" int luaopen_smi(lua_State* L);
