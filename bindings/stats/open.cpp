// Entry point of the stats binding area (see modules.hpp).
#include "modules.hpp"
#include "stats/dist_box.hpp"

namespace smi::bind {

void open_stats(lua_State* L) { register_distribution_type(L); }

}  // namespace smi::bind
