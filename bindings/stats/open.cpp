// SPDX-License-Identifier: MIT
// Entry point of the stats binding area (see modules.hpp).
#include "bindings/modules.hpp"
#include "bindings/stats/dist_box.hpp"
#include "bindings/stats/open_parts.hpp"

namespace smi::bind {

void open_stats(lua_State* L) {
  register_distribution_type(L);
  stats::open_dist(L);
  stats::open_kde(L);
  stats::open_metric(L);
}

}  // namespace smi::bind
