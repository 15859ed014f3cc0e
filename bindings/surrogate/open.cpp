// Entry point of the surrogate binding area (see modules.hpp): smi.doe, smi.kriging,
// smi.propagate, smi.screen.
#include "bindings/modules.hpp"

namespace smi::bind {
namespace surrogate {
void open_doe(lua_State* L);
void open_kriging(lua_State* L);
void open_propagate(lua_State* L);
void open_screen(lua_State* L);
}  // namespace surrogate

void open_surrogate(lua_State* L) {
  surrogate::open_doe(L);
  surrogate::open_kriging(L);
  surrogate::open_propagate(L);
  surrogate::open_screen(L);
}

}  // namespace smi::bind
