// SPDX-License-Identifier: MIT
#pragma once
// Entry points of the binding areas. Each is called by luaopen_smi with the `smi` table on
// top of the stack (stack: [smi] -> [smi]) and adds its fields to it.
//
// The one way a binding registers (README "Where a new kernel goes"):
//   - an area is one record in areas.cpp: its name, its open_<area>(L) and its reference texts
//     (doc_<area>(), in <area>_doc.cpp beside the registration), both declared here; luaopen_smi
//     opens the areas in that order and binding_docs() lists their texts in it. A new function of
//     an existing area touches that area's files only;
//   - an area of several files calls one open_<part>(L) per file, declared in <area>/open_parts.hpp;
//   - a part registers its types first: lua::register_type<T> for a box (a C++ object Lua owns),
//     lua::register_table_type for a result table with methods or __tostring;
//   - then its functions: a luaL_Reg list set with luaL_setfuncs into a new table stored as
//     smi.<module>, or a single function stored as smi.<name>;
//   - metatables are named all lowercase after the smi function or module that makes the value
//     (smi.vec, smi.dist, smi.kriging, smi.model, smi.screen_result).
#include <lua.hpp>
#include <vector>

#include "luax/doc_text.hpp"

namespace smi::bind {

/// One binding area: what luaopen_smi calls and the reference texts it contributes.
struct Area {
  const char* name;
  void (*open)(lua_State* L);
  std::vector<lua::DocText (*)()> docs;
};

/// Every area, in the order luaopen_smi opens them (areas.cpp).
const std::vector<Area>& areas();

void open_vec(lua_State* L);        // smi.vec            (bindings/vec.cpp)
void open_mat(lua_State* L);        // smi.mat            (bindings/mat.cpp)
void open_rng(lua_State* L);        // smi.rng            (bindings/rng.cpp)
void open_csv(lua_State* L);        // smi.csv            (bindings/csv.cpp)
void open_json(lua_State* L);       // smi.json           (bindings/json.cpp)
void open_stats(lua_State* L);      // smi.dist, smi.kde, smi.kde_bd, smi.kde_ebd, smi.ecdf, smi.metric
void open_surrogate(lua_State* L);  // smi.doe, smi.kriging, smi.propagate, smi.screen
void open_eval(lua_State* L);       // smi.model
void open_improve(lua_State* L);    // smi.calibrate, smi.refine
void open_run(lua_State* L);        // smi.out, smi.now, smi.write_file, smi.lock_out, smi.warnings,
                                    // smi.progress_label, smi.fail, smi.failure (bindings/run.cpp)
void open_members(lua_State* L);    // last: the suggesting __index of the module tables (members.cpp)

lua::DocText doc_vec();
lua::DocText doc_mat();
lua::DocText doc_rng();
lua::DocText doc_csv_json();
lua::DocText doc_stats_dist();
lua::DocText doc_stats_kde();
lua::DocText doc_stats_metric();
lua::DocText doc_surrogate();
lua::DocText doc_eval();
lua::DocText doc_improve();
lua::DocText doc_run();

}  // namespace smi::bind

/// Builds the `smi` module table with every area. Stack: [] -> [smi].
extern "C++" int luaopen_smi(lua_State* L);
