// SPDX-License-Identifier: MIT
#pragma once
// The option schemas of smi.metric.pr, intersection (and their grid table), loglik, upool,
// upool_threshold and upool_pvalue (luax/option_schema.hpp); metric_doc.cpp lists their options
// from them.
#include <limits>

#include "kernels/stats/grid.hpp"
#include "kernels/stats/metrics.hpp"
#include "kernels/stats/upool.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::stats {

struct LoglikArgs {
  double floor = smi::stats::kLoglikFloor;  ///< the smallest density used
};

/// upool's table: the groups (read by hand), the confidence (checked by hand) and the MC settings.
struct UpoolArgs : smi::stats::UpoolMcSettings {};

/// pr's and intersection's table: nodes (a grid over both bulks) or grid (read by hand).
struct OverlapArgs {
  Eigen::Index nodes = smi::stats::Grid{}.n;  ///< grid nodes when grid is not given
};
/// Their grid = {lower =, upper =, nodes =}: lower and upper required (NaN until given).
struct GridArgs {
  double lower = std::numeric_limits<double>::quiet_NaN();
  double upper = std::numeric_limits<double>::quiet_NaN();
  Eigen::Index nodes = smi::stats::Grid{}.n;
};

const lua::Schema<LoglikArgs>& loglik_schema();
/// smi.metric.pr's (pr) or smi.metric.intersection's options, and their grid table's.
const lua::Schema<OverlapArgs>& overlap_schema(bool pr);
const lua::Schema<GridArgs>& grid_schema(bool pr);
const lua::Schema<UpoolArgs>& upool_schema();
/// upool_threshold's and upool_pvalue's (fname: which).
const lua::Schema<smi::stats::UpoolMcSettings>& upool_mc_schema(bool threshold);

}  // namespace smi::bind::stats
