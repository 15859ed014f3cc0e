// SPDX-License-Identifier: MIT
#pragma once
// The pieces open_surrogate() assembles (stack: [smi] -> [smi]).
#include <lua.hpp>

namespace smi::bind::surrogate {
void open_doe(lua_State* L);        // smi.doe.*                      (doe.cpp)
void open_kriging(lua_State* L);    // smi.kriging.*, type smi.kriging (kriging.cpp)
void open_propagate(lua_State* L);  // smi.propagate                  (propagate.cpp)
void open_screen(lua_State* L);     // smi.screen                     (screen.cpp)
void open_sequential(lua_State* L); // smi.kriging.sequential        (sequential.cpp)
}  // namespace smi::bind::surrogate
