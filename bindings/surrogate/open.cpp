// SPDX-License-Identifier: MIT
// Entry point of the surrogate binding area (see modules.hpp): smi.doe, smi.kriging,
// smi.propagate, smi.screen, smi.kriging.sequential.
#include "bindings/modules.hpp"
#include "bindings/surrogate/open_parts.hpp"

namespace smi::bind {

void open_surrogate(lua_State* L) {
  surrogate::open_doe(L);
  surrogate::open_kriging(L);
  surrogate::open_sequential(L);  // smi.kriging.sequential
  surrogate::open_propagate(L);
  surrogate::open_screen(L);
}

}  // namespace smi::bind
