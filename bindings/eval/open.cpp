// Entry point of the eval binding area (see modules.hpp).
#include "modules.hpp"

namespace smi::bind {

void open_eval(lua_State* /*L*/) {}

}  // namespace smi::bind
