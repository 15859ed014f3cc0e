// SPDX-License-Identifier: MIT
#include "bindings/improve/progress_line.hpp"

#include <fmt/format.h>
#include <unistd.h>

#include <cmath>
#include <cstdio>

#include "luax/policy.hpp"
#include "luax/run_context.hpp"
#include "platform/eval/progress_line.hpp"

namespace smi::bind::improve {

std::string format_progress_row(const smi::improve::ProgressRow& r) {
  std::string s = r.stage + ": ";
  if (r.stage == "calibration")
    s += fmt::format("start {}/{}, {} evaluations", std::min(r.done + (r.final ? 0 : 1), r.total), r.total, r.evaluations);
  else if (r.stage == "bootstrap")
    s += fmt::format("{}/{} replicates, {} evaluations", r.done, r.total, r.evaluations);
  else
    s += fmt::format("{} evaluations", r.evaluations);
  if (std::isfinite(r.best)) s += fmt::format(", best {:.6g}", r.best);
  if (r.final) s += ", done";
  else if (r.eta >= 0.0) s += ", ETA " + smi::eval::format_duration(r.eta);
  return s;
}

smi::improve::ProgressLine terminal_progress_line(lua_State* L, bool wanted) {
  if (!wanted || !lua::run_context(L).progress.live) return {};
  return [prefix = lua::run_context(L).progress.prefix()](const smi::improve::ProgressRow& r) {
    smi::eval::show_progress(stderr, prefix + format_progress_row(r), r.final);
  };
}

}  // namespace smi::bind::improve
