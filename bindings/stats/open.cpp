// Entry point of the stats binding area (see modules.hpp).
#include "modules.hpp"
#include "stats/dist_box.hpp"
#include "stats/open_parts.hpp"

namespace smi::bind {

void open_stats(lua_State* L) {
  register_distribution_type(L);
  stats::open_dist(L);
  stats::open_kde(L);
  stats::open_metric(L);
}

}  // namespace smi::bind
