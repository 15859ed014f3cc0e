// SPDX-License-Identifier: MIT
#include "platform/eval/executor.hpp"

#include <cmath>
#include <fmt/format.h>

#include "platform/core/errors.hpp"
#include "platform/eval/sbatch_args.hpp"
#include "platform/eval/slurm_cli.hpp"
#include "platform/eval/slurm_executor.hpp"

namespace smi::eval {
namespace {

/// Today's local path: the Scheduler's process groups, unchanged.
class LocalExecutor final : public Executor {
 public:
  explicit LocalExecutor(int concurrency) : sched_(concurrency) {}
  void submit(Job job) override { sched_.submit(std::move(job)); }
  void stop_launching() override { sched_.stop_launching(); }
  void run(const std::function<void(const Outcome&)>& on_done, const std::function<void()>& on_tick,
           double tick) override {
    sched_.run(on_done, on_tick, tick);
  }
  std::size_t running() const override { return sched_.running(); }

 private:
  Scheduler sched_;
};

double positive(const std::string& key, const std::string& v, bool allow_zero = false) {
  char* end = nullptr;
  const double d = std::strtod(v.c_str(), &end);
  if (v.empty() || *end || !std::isfinite(d) || d < 0 || (!allow_zero && d == 0))
    throw InvalidArgument(fmt::format("executor option {}={}: expected a {} number", key, v,
                                      allow_zero ? "non-negative" : "positive"));
  return d;
}

int whole(const std::string& key, const std::string& v) {
  const double d = positive(key, v, true);
  if (d != std::floor(d) || d > 1e9) throw InvalidArgument(fmt::format("executor option {}={}: expected a whole number", key, v));
  return static_cast<int>(d);
}

}  // namespace

const char* executor_option_keys() {
  return "kind, partition, account, qos, time, mem, cpus, sbatch, throttle, max_array, poll, poll_max, "
         "cmd_timeout, down_after, exit_wait, max_requeues, bin_dir";
}

void ExecutorConfig::set(const std::string& kv) {
  const auto eq = kv.find('=');
  if (eq == std::string::npos || eq == 0)
    throw InvalidArgument(fmt::format("--slurm-opt '{}': expected KEY=VALUE (keys: {})", kv, executor_option_keys()));
  set(kv.substr(0, eq), kv.substr(eq + 1));
}

void ExecutorConfig::set(const std::string& k, const std::string& v) {
  if (k == "kind") kind = v;
  else if (k == "partition") partition = v;
  else if (k == "account") account = v;
  else if (k == "qos") qos = v;
  else if (k == "time") {
    if (slurm_time_minutes(v) <= 0)
      throw InvalidArgument(fmt::format("executor option time={}: expected minutes or a Slurm time such as 1:30:00", v));
    time = v;
  } else if (k == "mem") mem = v;
  else if (k == "cpus") cpus = whole(k, v);
  else if (k == "sbatch") {
    // Extra sbatch arguments, split at spaces ("--gres=gpu:1 --constraint=avx2").
    std::size_t a = 0;
    while (a < v.size()) {
      const auto b = v.find(' ', a);
      const std::string w = v.substr(a, b == std::string::npos ? std::string::npos : b - a);
      if (!w.empty()) sbatch_args.push_back(w);
      if (b == std::string::npos) break;
      a = b + 1;
    }
  } else if (k == "throttle") throttle = whole(k, v);
  else if (k == "max_array") max_array = whole(k, v);
  else if (k == "poll") poll_min = positive(k, v);
  else if (k == "poll_max") poll_max = positive(k, v);
  else if (k == "cmd_timeout") cmd_timeout = positive(k, v);
  else if (k == "down_after") down_after = positive(k, v, true);
  else if (k == "exit_wait") exit_wait = positive(k, v, true);
  else if (k == "max_requeues") max_requeues = whole(k, v);
  else if (k == "bin_dir") bin_dir = v;
  else
    throw InvalidArgument(fmt::format("unknown executor option '{}' (known: {})", k, executor_option_keys()));
}

void ExecutorConfig::validate() const {
  if (kind != "local" && kind != "slurm")
    throw InvalidArgument(fmt::format("executor kind '{}' is not known: use 'local' or 'slurm'", kind));
  if (throttle < 1) throw InvalidArgument("executor option throttle must be at least 1");
  if (poll_max < poll_min)
    throw InvalidArgument(fmt::format("executor option poll_max={:g} is below poll={:g}", poll_max, poll_min));
  // Parsed as sbatch parses them, then held to an allow-list (sbatch_args.hpp).
  check_sbatch_args(sbatch_args);
}

std::unique_ptr<Executor> make_executor(const ExecutorConfig& cfg, int concurrency, PendingTable* pending,
                                        const std::string& runs_dir, const std::string& tag) {
  cfg.validate();
  if (cfg.kind == "slurm") return std::make_unique<SlurmExecutor>(cfg, pending, runs_dir, tag);
  return std::make_unique<LocalExecutor>(concurrency);
}

}  // namespace smi::eval
