// SPDX-License-Identifier: MIT
#include "platform/eval/slurm_cli.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fmt/format.h>
#include <sstream>

#include "platform/eval/process.hpp"

namespace smi::eval {

CommandResult run_command(const std::vector<std::string>& argv, double timeout, const std::string& bin_dir) {
  CommandResult r;
  if (argv.empty()) return r;
  // The evaluator's process start (process.hpp): own process group and default signals, so a
  // Ctrl-C meant for smi-lua does not kill the scancel that smi-lua is about to run because of
  // it; smi-lua's whole environment (sbatch hands it on to the job), without the solver mark;
  // not killed with smi-lua (an sbatch under way finishes, its job is recorded as pending).
  const std::string prog = bin_dir.empty() ? argv[0] : (std::filesystem::path(bin_dir) / argv[0]).string();
  SpawnSpec spec;
  spec.program = bin_dir.empty() ? find_program(prog) : prog;
  spec.argv = argv;
  spec.env = current_environment();
  spec.solver_mark = false;
  spec.die_with_parent = false;
  CapturedRun c;
  try {
    if (spec.program.empty()) throw SpawnError("", ENOENT);
    c = run_captured(std::move(spec), timeout);
  } catch (const SpawnError& e) {
    r.err = fmt::format("cannot run '{}': {} (is slurm-client installed? --slurm-opt bin_dir=DIR names its folder)",
                        prog, std::strerror(e.err));
    return r;
  }
  r.status = c.status;
  r.timed_out = c.timed_out;
  r.out = std::move(c.out);
  r.err = std::move(c.err);
  if (r.timed_out) r.err += fmt::format("{}no answer within {:g} s", r.err.empty() ? "" : "; ", timeout);
  return r;
}

bool transient_failure(const CommandResult& r) {
  if (r.timed_out) return true;
  if (r.status == 0) return false;
  for (const char* s : {"Unable to contact slurm controller", "Socket timed out", "Connection refused",
                        "temporarily unavailable", "Try again", "try again", "Zero Bytes were transmitted",
                        "Connection reset", "Transport endpoint", "slurm_load_jobs error: Unable",
                        "Communication connection failure"})
    if (r.err.find(s) != std::string::npos) return true;
  return false;
}

TaskState parse_task_state(const std::string& s0) {
  // squeue prints "CANCELLED+" or "CANCELLED by 0" in some views: the first word decides.
  std::string s = s0.substr(0, s0.find_first_of(" +"));
  if (s == "PENDING" || s == "CONFIGURING" || s == "REQUEUE_HOLD" || s == "REQUEUE_FED" || s == "RESV_DEL_HOLD" ||
      s == "SPECIAL_EXIT")
    return TaskState::Pending;
  if (s == "RUNNING" || s == "COMPLETING" || s == "SUSPENDED" || s == "STOPPED" || s == "RESIZING" ||
      s == "SIGNALING" || s == "STAGE_OUT")
    return TaskState::Running;
  if (s == "REQUEUED") return TaskState::Requeued;
  if (s == "COMPLETED") return TaskState::Completed;
  if (s == "FAILED") return TaskState::Failed;
  if (s == "TIMEOUT" || s == "DEADLINE") return TaskState::Timeout;
  if (s == "OUT_OF_MEMORY") return TaskState::OutOfMemory;
  if (s == "CANCELLED" || s == "REVOKED") return TaskState::Cancelled;
  if (s == "NODE_FAIL") return TaskState::NodeFail;
  if (s == "PREEMPTED") return TaskState::Preempted;
  if (s == "BOOT_FAIL") return TaskState::BootFail;
  return TaskState::Unknown;
}

bool is_final(TaskState s) {
  return s != TaskState::Pending && s != TaskState::Running && s != TaskState::Requeued && s != TaskState::Unknown;
}

bool is_infrastructure(TaskState s) {
  return s == TaskState::NodeFail || s == TaskState::Preempted || s == TaskState::BootFail;
}

std::vector<QueueEntry> parse_squeue(const std::string& out) {
  std::vector<QueueEntry> v;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    std::vector<std::string> f;
    std::size_t a = 0;
    for (std::size_t b; (b = line.find('|', a)) != std::string::npos; a = b + 1) f.push_back(line.substr(a, b - a));
    f.push_back(line.substr(a));
    if (f.size() < 2) continue;
    QueueEntry e;
    // %i: "123_4" for a task of array 123, "123" for a plain job, "123_[5-9%2]" for tasks that
    // -r did not split (skipped: nothing to judge per task).
    const auto us = f[0].find('_');
    e.array_job_id = f[0].substr(0, us);
    if (e.array_job_id.empty() || e.array_job_id.find_first_not_of("0123456789") != std::string::npos) continue;
    if (us != std::string::npos) {
      const std::string idx = f[0].substr(us + 1);
      if (idx.empty() || idx.find_first_not_of("0123456789") != std::string::npos) continue;
      e.index = std::stoi(idx);
    }
    e.state_text = f[1];
    e.state = parse_task_state(f[1]);
    if (f.size() > 2) e.reason = f[2];
    if (f.size() > 3) e.raw_id = f[3];
    v.push_back(std::move(e));
  }
  return v;
}

std::map<std::string, std::string> parse_sacct(const std::string& out) {
  std::map<std::string, std::string> m;
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const auto bar = line.find('|');
    if (bar == std::string::npos || bar == 0) continue;
    const auto bar2 = line.find('|', bar + 1);
    std::string id = line.substr(0, bar);
    if (id.find('.') != std::string::npos) continue;  // steps (123_4.batch)
    m[id] = line.substr(bar + 1, bar2 == std::string::npos ? std::string::npos : bar2 - bar - 1);
  }
  return m;
}

int parse_max_array_size(const std::string& out) {
  std::istringstream in(out);
  std::string line;
  while (std::getline(in, line)) {
    const auto k = line.find("MaxArraySize");
    const auto eq = line.find('=');
    if (k == std::string::npos || eq == std::string::npos) continue;
    try {
      return std::stoi(line.substr(eq + 1));
    } catch (const std::exception&) {
      return 0;
    }
  }
  return 0;
}

std::string parse_sbatch_id(const std::string& out) {
  std::string s = out.substr(0, out.find_first_of(";\n"));
  while (!s.empty() && (s.back() == ' ' || s.back() == '\r')) s.pop_back();
  if (s.empty() || s.find_first_not_of("0123456789") != std::string::npos) return "";
  return s;
}

double slurm_time_minutes(const std::string& t) {
  // Slurm accepts: M, M:S, H:M:S, D-H, D-H:M, D-H:M:S.
  if (t.empty()) return -1;
  int days = 0;
  std::string rest = t;
  if (const auto dash = t.find('-'); dash != std::string::npos) {
    try {
      days = std::stoi(t.substr(0, dash));
    } catch (const std::exception&) {
      return -1;
    }
    rest = t.substr(dash + 1);
  }
  std::vector<int> parts;
  std::size_t a = 0;
  for (;;) {
    const auto b = rest.find(':', a);
    const std::string p = rest.substr(a, b == std::string::npos ? std::string::npos : b - a);
    if (p.empty() || p.find_first_not_of("0123456789") != std::string::npos) return -1;
    parts.push_back(std::stoi(p));
    if (b == std::string::npos) break;
    a = b + 1;
  }
  double min = 0;
  if (t.find('-') != std::string::npos) {  // D-H[:M[:S]]
    if (parts.size() > 3) return -1;
    min = parts[0] * 60.0 + (parts.size() > 1 ? parts[1] : 0) + (parts.size() > 2 ? parts[2] / 60.0 : 0);
  } else if (parts.size() == 1) {
    min = parts[0];
  } else if (parts.size() == 2) {
    min = parts[0] + parts[1] / 60.0;
  } else if (parts.size() == 3) {
    min = parts[0] * 60.0 + parts[1] + parts[2] / 60.0;
  } else {
    return -1;
  }
  return days * 1440.0 + min;
}

}  // namespace smi::eval
