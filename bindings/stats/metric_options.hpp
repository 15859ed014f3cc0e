#pragma once
// The option schemas of smi.metric.loglik, smi.metric.upool, upool_threshold and upool_pvalue
// (luax/option_schema.hpp); metric_doc.cpp lists their options from them.
#include "kernels/stats/metrics.hpp"
#include "kernels/stats/upool.hpp"
#include "luax/option_schema.hpp"

namespace smi::bind::stats {

struct LoglikArgs {
  double floor = smi::stats::kLoglikFloor;  ///< the smallest density used
};

/// upool's table: the groups (read by hand), the confidence (checked by hand) and the MC settings.
struct UpoolArgs : smi::stats::UpoolMcSettings {};

const lua::Schema<LoglikArgs>& loglik_schema();
const lua::Schema<UpoolArgs>& upool_schema();
/// upool_threshold's and upool_pvalue's (fname: which).
const lua::Schema<smi::stats::UpoolMcSettings>& upool_mc_schema(bool threshold);

}  // namespace smi::bind::stats
