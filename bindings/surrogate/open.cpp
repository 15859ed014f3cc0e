// Entry point of the surrogate binding area (see modules.hpp).
#include "modules.hpp"

namespace smi::bind {

void open_surrogate(lua_State* /*L*/) {}

}  // namespace smi::bind
