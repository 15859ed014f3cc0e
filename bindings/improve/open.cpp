// Entry point of the improve binding area (see modules.hpp).
#include "modules.hpp"

namespace smi::bind {

void open_improve(lua_State* /*L*/) {}

}  // namespace smi::bind
