// SPDX-License-Identifier: MIT
#pragma once
// The pieces open_stats() assembles (stack: [smi] -> [smi]).
#include <lua.hpp>

namespace smi::bind::stats {
void open_dist(lua_State* L);    // smi.dist.*        (dist_lua.cpp)
void open_kde(lua_State* L);     // smi.kde, smi.kde_bd, smi.kde_ebd, smi.ecdf (kde_lua.cpp)
void open_metric(lua_State* L);  // smi.metric.*      (metric_lua.cpp)
}  // namespace smi::bind::stats
