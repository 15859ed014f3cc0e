// SPDX-License-Identifier: MIT
#include "platform/eval/progress_line.hpp"

#include <cmath>
#include <fmt/format.h>

namespace smi::eval {

std::string format_duration(double s) {
  if (!(s >= 0)) return "?";
  if (s < 10) return fmt::format("{:.2g} s", s);
  if (s < 60) return fmt::format("{:.0f} s", s);
  const long t = std::lround(s);
  if (t < 3600) return fmt::format("{}:{:02}", t / 60, t % 60);
  return fmt::format("{}:{:02}:{:02}", t / 3600, (t / 60) % 60, t % 60);
}

std::string format_progress(const std::string& model, const Progress& p) {
  return fmt::format("{}: {}/{} runs done, {} failed, {} running, mean {}, ETA {}", model, p.done, p.total, p.failed,
                     p.running, p.mean_seconds > 0 ? format_duration(p.mean_seconds) : "?",
                     p.done == p.total ? "0 s" : format_duration(p.eta_seconds));
}

std::string format_plan(const std::string& model, const Plan& p, int concurrency) {
  std::string s = fmt::format("dry run: model '{}' would launch {} solver run{} for {} point{} ({} found in the store)",
                              model, p.runs, p.runs == 1 ? "" : "s", p.points, p.points == 1 ? "" : "s", p.reused);
  if (p.runs == 0) return s;
  if (p.timing.count > 0)
    s += fmt::format("; ETA {} at concurrency {} from {} stored run{} (mean {})", format_duration(p.eta_seconds),
                     concurrency, p.timing.count, p.timing.count == 1 ? "" : "s", format_duration(p.timing.mean));
  else
    s += "; ETA unknown (no stored run of this program and version)";
  return s;
}

void show_progress(std::FILE* tty, const std::string& text, bool final) {
  std::fprintf(tty, "\r%s\033[K%s", text.c_str(), final ? "\n" : "");
  std::fflush(tty);
}

}  // namespace smi::eval
