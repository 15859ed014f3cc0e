// Entry point of the stats binding area (see modules.hpp).
#include "modules.hpp"

namespace smi::bind {

void open_stats(lua_State* /*L*/) {}

}  // namespace smi::bind
