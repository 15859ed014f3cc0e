// SPDX-License-Identifier: MIT
#include "platform/eval/slurm_executor.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <set>
#include <sstream>
#include <cerrno>
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "platform/core/atomic_file.hpp"
#include "platform/eval/pending.hpp"
#include "platform/eval/process.hpp"
#include "platform/eval/work_dir.hpp"

namespace smi::eval {
namespace fs = std::filesystem;

namespace {

void nap(double s) {
  if (s <= 0) return;
  timespec ts{};
  ts.tv_sec = static_cast<time_t>(s);
  ts.tv_nsec = static_cast<long>((s - static_cast<double>(ts.tv_sec)) * 1e9);
  nanosleep(&ts, nullptr);
}

std::string join(const std::vector<std::string>& v, const char* sep) {
  std::string s;
  for (const auto& x : v) s += (s.empty() ? "" : sep) + x;
  return s;
}

/// A shell-safe rendering of one argument (for messages and --dry-run only; nothing is run
/// through a shell).
std::string quoted(const std::string& a) {
  if (!a.empty() && a.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=.,/:%@") ==
                        std::string::npos)
    return a;
  std::string q = "'";
  for (char c : a) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string exit_file(const std::string& workdir) { return (fs::path(workdir) / ".smi" / "exit").string(); }

/// The outcome the job wrapper recorded: "rc timed_out seconds".
bool read_exit_file(const std::string& workdir, double timeout, Outcome& o) {
  std::ifstream in(exit_file(workdir));
  if (!in) return false;
  int rc = -1, to = 0;
  double secs = 0;
  if (!(in >> rc >> to >> secs)) return false;  // not there yet in full (it is renamed into place, so rare)
  o.seconds = secs;
  if (to) {
    o.kind = Outcome::TimedOut;
    o.reason = fmt::format("timeout after {:g} s (process group killed)", timeout);
  } else if (rc > 128 && rc < 128 + 65) {
    o.kind = Outcome::Signaled;
    o.reason = fmt::format("killed by signal {} ({})", rc - 128, strsignal(rc - 128));
  } else {
    o.kind = Outcome::Exited;
    o.exit_code = rc;
    if (rc != 0) o.reason = fmt::format("exit status {}", rc);
  }
  return true;
}

}  // namespace

namespace {

std::string write_job_script(const std::string& slurm_dir, const std::string& name) {
  // The runs folder is writable by the study, so nothing found there is trusted: the chunk's
  // folder must be new (mkdir, not "exists is fine"), it is held by a descriptor opened without
  // following links, and the script is created in it with O_EXCL. sbatch reads the script at
  // submission and the controller keeps its copy, so what happens to the file later does not matter.
  ::mkdir(slurm_dir.c_str(), 0755);  // may exist (earlier chunks); checked through the walk below
  const int parent = ::open(slurm_dir.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC);
  if (parent < 0)
    throw Error(fmt::format("cannot open the Slurm folder {}: {} (a link there is refused)", slurm_dir, std::strerror(errno)));
  std::string why;
  if (::mkdirat(parent, name.c_str(), 0700) != 0) why = fmt::format("cannot make {}/{}: {}", slurm_dir, name, std::strerror(errno));
  const int dir = why.empty() ? ::openat(parent, name.c_str(), O_RDONLY | O_DIRECTORY | O_NOFOLLOW | O_CLOEXEC) : -1;
  ::close(parent);
  if (why.empty() && dir < 0) why = fmt::format("cannot open {}/{}: {}", slurm_dir, name, std::strerror(errno));
  const int fd = dir >= 0 ? ::openat(dir, "job.sh", O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC, 0500) : -1;
  if (dir >= 0) ::close(dir);
  if (why.empty() && fd < 0) why = fmt::format("cannot create {}/{}/job.sh: {}", slurm_dir, name, std::strerror(errno));
  if (!why.empty()) throw Error(why + " (smi-lua writes the job script itself, into a folder it has just made)");
  const std::string text = SlurmExecutor::job_script();
  std::size_t done = 0;
  while (done < text.size()) {
    const ssize_t w = ::write(fd, text.data() + done, text.size() - done);
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      const int e = errno;
      ::close(fd);
      throw Error(fmt::format("cannot write {}/{}/job.sh: {}", slurm_dir, name, std::strerror(e)));
    }
    done += static_cast<std::size_t>(w);
  }
  ::close(fd);
  return (fs::path(slurm_dir) / name / "job.sh").string();
}

}  // namespace

std::string SlurmExecutor::job_script() {
  // slurm_job.sh beside this file, embedded at build time (cmake/embed_file.cmake).
  static const unsigned char text[] = {
#include "platform/eval/slurm_job.sh.inc"
  };
  return std::string(reinterpret_cast<const char*>(text), sizeof text);
}

double SlurmExecutor::time_limit_minutes(const ExecutorConfig& cfg, double timeout) {
  if (!cfg.time.empty()) {
    const double m = slurm_time_minutes(cfg.time);
    if (timeout > 0 && m * 60 < timeout + 60)
      throw InvalidArgument(fmt::format(
          "executor option time={} ({:g} min) leaves no margin over the model's timeout of {:g} s: Slurm's limit is "
          "a backstop and must exceed it by a minute at least (or leave time out: smi-lua derives it)",
          cfg.time, m, timeout));
    return m;
  }
  if (timeout <= 0) return -1;
  // Slurm rounds limits up to minutes and checks them about every 30 s; staging takes a moment.
  return std::ceil((timeout + std::max(60.0, 0.1 * timeout) + 30) / 60);
}

std::vector<std::string> SlurmExecutor::sbatch_argv(const ExecutorConfig& cfg, const std::string& job_name,
                                                    std::size_t tasks, double timeout, const std::string& log_dir) {
  std::vector<std::string> a = {"sbatch", "--parsable", "--job-name=" + job_name,
                                fmt::format("--array=0-{}%{}", tasks - 1, cfg.throttle),
                                "--output=" + log_dir + "/%a.out", "--chdir=" + log_dir, "--requeue", "--export=NONE"};
  if (!cfg.partition.empty()) a.push_back("--partition=" + cfg.partition);
  if (!cfg.account.empty()) a.push_back("--account=" + cfg.account);
  if (!cfg.qos.empty()) a.push_back("--qos=" + cfg.qos);
  const double minutes = time_limit_minutes(cfg, timeout);
  if (!cfg.time.empty()) a.push_back("--time=" + cfg.time);
  else if (minutes > 0) a.push_back(fmt::format("--time={}", static_cast<long>(minutes)));
  if (!cfg.mem.empty()) a.push_back("--mem=" + cfg.mem);
  if (cfg.cpus > 0) a.push_back(fmt::format("--cpus-per-task={}", cfg.cpus));
  a.insert(a.end(), cfg.sbatch_args.begin(), cfg.sbatch_args.end());
  return a;
}

SlurmExecutor::SlurmExecutor(ExecutorConfig cfg, PendingTable* pending, std::string runs_dir, std::string tag)
    : cfg_(std::move(cfg)), pending_(pending), runs_dir_(std::move(runs_dir)), tag_(std::move(tag)) {
  slurm_dir_ = (fs::path(runs_dir_) / ".slurm").string();
  interval_ = cfg_.poll_min;
}

SlurmExecutor::~SlurmExecutor() {
  if (live_.empty() || cfg_.detach || down_) return;
  // One scancel for every array still live: queued tasks never start, running ones get TERM.
  std::set<std::string> ids;
  for (const Task& t : live_)
    if (!t.job_id.empty()) ids.insert(t.job_id);
  if (ids.empty()) return;
  std::vector<std::string> argv = {"scancel"};
  argv.insert(argv.end(), ids.begin(), ids.end());
  try {
    ++calls_.scancel;
    const CommandResult r = run_command(argv, cfg_.cmd_timeout, cfg_.bin_dir);
    if (r.status == 0 && pending_)
      for (const Task& t : live_) pending_->erase(t.job.key, t.job_id);
  } catch (const std::exception&) {  // a destructor reports nothing; the rerun reattaches
  }
}

std::size_t SlurmExecutor::running() const {
  return static_cast<std::size_t>(std::count_if(live_.begin(), live_.end(), [](const Task& t) { return t.state == TaskState::Running; }));
}

CommandResult SlurmExecutor::call(const std::vector<std::string>& argv, const char* what, bool harvest) {
  const double t0 = monotonic_seconds();
  double backoff = 0.5;
  for (;;) {
    CommandResult r = run_command(argv, cfg_.cmd_timeout, cfg_.bin_dir);
    if (!transient_failure(r)) return r;
    const double spent = monotonic_seconds() - t0;
    if (harvest && on_done_) scan_exit_files(*on_done_);  // what finished meanwhile is kept
    if (spent >= cfg_.down_after) {
      down_ = true;
      std::string err = r.err;
      while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
      throw SchedulerDown(fmt::format(
          "Slurm is not answering: '{}' ({}) failed for {:.0f} s: {}. The study stops here; finished runs are "
          "stored, and submitted jobs stay in the store's pending table: run the study again once the controller "
          "answers and it reattaches to them", join(argv, " ").substr(0, 200), what, spent, err));
    }
    const double until = monotonic_seconds() + std::min({backoff, 5.0, std::max(0.05, cfg_.down_after - spent)});
    while (monotonic_seconds() < until) {
      nap(std::min(0.2, until - monotonic_seconds()));
      if (harvest && on_tick_ && *on_tick_) (*on_tick_)();  // Ctrl-C and --timeout still stop the study
    }
    backoff *= 2;
  }
}

int SlurmExecutor::max_array() {
  if (max_array_ > 0) return max_array_;
  // Asked once per smi-lua process (a study makes an executor per evaluation).
  static std::map<std::string, int> known;  // bin_dir -> MaxArraySize
  int cluster = known[cfg_.bin_dir];
  if (cluster <= 0) {
    ++calls_.scontrol;
    const CommandResult r = run_command({"scontrol", "show", "config"}, cfg_.cmd_timeout, cfg_.bin_dir);
    if (r.status == 0) cluster = known[cfg_.bin_dir] = parse_max_array_size(r.out);
    if (cluster <= 0) cluster = 1001;  // Slurm's default (asked again next time)
  }
  max_array_ = cfg_.max_array > 0 ? std::min(cfg_.max_array, cluster) : cluster;
  return max_array_;
}

void SlurmExecutor::submit_queued(const std::function<void(const Outcome&)>& on_done) {
  std::vector<Task> fresh;
  while (!queue_.empty()) {
    Job job = std::move(queue_.front());
    queue_.pop_front();
    // A job of an earlier smi-lua (killed, detached, scheduler down): reattach, never resubmit.
    if (pending_ && !job.key.empty()) {
      if (auto row = pending_->find(job.key); row && row->workdir == job.spec.workdir) {
        Task t;
        t.job_name = row->job_name;
        t.job_id = row->job_id;
        t.index = row->array_index;
        const bool finished = fs::exists(exit_file(row->workdir));
        if (t.job_id.empty() && !finished) {
          // Killed between writing the row and sbatch's answer: did sbatch get through?
          ++calls_.squeue;
          const CommandResult r = call({"squeue", "-h", "-r", "-t", "all", "-n", t.job_name, "-o", "%i|%T|%r"}, "find a submitted job");
          for (const auto& e : parse_squeue(r.out))
            if (e.index == t.index) t.job_id = e.array_job_id;
        }
        if (!t.job_id.empty() || finished) {
          t.job = std::move(job);
          live_.push_back(std::move(t));
          ++reattached_;
          continue;
        }
      }
    }
    Outcome failed;
    try {
      if (job.prepare) job.prepare();
      // The inputs as prepared, kept apart: the wrapper restores them for every attempt.
      const fs::path w = job.spec.workdir, smi = w / ".smi", input = smi / "input";
      fs::create_directories(input);
      for (const auto& e : fs::directory_iterator(w))
        if (e.path().filename() != ".smi")
          fs::copy(e.path(), input / e.path().filename(), fs::copy_options::recursive | fs::copy_options::overwrite_existing);
      std::string argv(job.spec.program);
      argv.push_back('\0');
      for (const auto& a : job.spec.argv) {
        argv += a;
        argv.push_back('\0');
      }
      write_text_file((smi / "argv").string(), argv);
      write_text_file((smi / "timeout").string(), fmt::format("{:g}\n", job.timeout));
      std::string env;
      for (const auto& kv : job.spec.env) {
        env += kv;
        env.push_back('\0');
      }
      write_text_file((smi / "env").string(), env);
    } catch (const std::exception& e) {
      failed.id = job.id;
      failed.kind = Outcome::SpawnFailed;
      failed.reason = e.what();
      on_done(failed);
      continue;
    }
    Task t;
    t.job = std::move(job);
    fresh.push_back(std::move(t));
  }
  const std::size_t per = static_cast<std::size_t>(max_array());
  for (std::size_t s = 0; s < fresh.size(); s += per) {
    std::vector<Task> chunk(std::make_move_iterator(fresh.begin() + static_cast<std::ptrdiff_t>(s)),
                            std::make_move_iterator(fresh.begin() + static_cast<std::ptrdiff_t>(std::min(fresh.size(), s + per))));
    submit_chunk(std::move(chunk));
  }
}

void SlurmExecutor::submit_chunk(std::vector<Task> chunk) {
  if (chunk.empty()) return;
  // A job name unique to this chunk: a rerun finds the array by it when smi-lua died between
  // sbatch and recording the id, and a retried sbatch checks it did not get through already.
  const auto ns = std::chrono::system_clock::now().time_since_epoch().count();
  const std::string name = fmt::format("smi-{}-{:x}{:x}-{}", tag_, static_cast<unsigned long long>(ns) & 0xffffffffULL,
                                       static_cast<unsigned>(::getpid()) & 0xfff, chunks_++);
  const fs::path dir = fs::path(slurm_dir_) / name;
  const std::string script = write_job_script(slurm_dir_, name);
  std::string manifest;
  double timeout = 0;
  std::vector<PendingRun> rows;
  for (std::size_t k = 0; k < chunk.size(); ++k) {
    manifest += chunk[k].job.spec.workdir + "\n";
    timeout = std::max(timeout, chunk[k].job.timeout);
    rows.push_back({chunk[k].job.key, name, "", static_cast<int>(k), chunk[k].job.attempt, chunk[k].job.spec.workdir});
  }
  const std::string manifest_path = (dir / "manifest").string();
  write_text_file(manifest_path, manifest);
  std::vector<std::string> argv = sbatch_argv(cfg_, name, chunk.size(), timeout, dir.string());
  argv.push_back(script);
  argv.push_back(manifest_path);
  if (pending_) pending_->put(rows);  // before sbatch: a crash in between is found by the job name

  std::string id;
  const double t0 = monotonic_seconds();
  double backoff = 0.5;
  for (;;) {
    ++calls_.sbatch;
    const CommandResult r = run_command(argv, cfg_.cmd_timeout, cfg_.bin_dir);
    if (r.status == 0) {
      id = parse_sbatch_id(r.out);
      if (id.empty()) throw Error(fmt::format("sbatch answered '{}' instead of a job id", r.out));
      break;
    }
    if (!transient_failure(r)) {
      if (pending_)
        for (const auto& row : rows) pending_->erase(row.key, "");
      std::string err = r.err;
      while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
      throw Error(fmt::format("sbatch rejected the job array of {} run{}: {}\n  command: {}\n  check the executor "
                              "options (--slurm-opt partition=, account=, qos=, time=, mem=, cpus=, sbatch=)",
                              chunk.size(), chunk.size() == 1 ? "" : "s", err, join(argv, " ")));
    }
    // It may have got through before the answer was lost: look for the job name first.
    ++calls_.squeue;
    const CommandResult q = run_command({"squeue", "-h", "-n", name, "-o", "%F"}, cfg_.cmd_timeout, cfg_.bin_dir);
    if (q.status == 0 && !parse_sbatch_id(q.out).empty()) {
      id = parse_sbatch_id(q.out);
      break;
    }
    const double spent = monotonic_seconds() - t0;
    if (spent >= cfg_.down_after) {
      down_ = true;
      std::string err = r.err;
      while (!err.empty() && (err.back() == '\n' || err.back() == ' ')) err.pop_back();
      throw SchedulerDown(fmt::format("Slurm is not answering: sbatch failed for {:.0f} s: {}. The study stops here; "
                                      "finished runs are stored: run it again once the controller answers",
                                      spent, err));
    }
    nap(std::min(backoff, 5.0));
    backoff *= 2;
  }
  if (pending_) pending_->set_job_id(name, id);
  std::ofstream log(fs::path(slurm_dir_) / "submissions.log", std::ios::app);
  for (std::size_t k = 0; k < chunk.size(); ++k) {
    log << id << '_' << k << ' ' << chunk[k].job.key << ' ' << chunk[k].job.attempt << ' ' << chunk[k].job.spec.workdir << '\n';
    chunk[k].job_name = name;
    chunk[k].job_id = id;
    chunk[k].index = static_cast<int>(k);
    chunk[k].state = TaskState::Pending;
    live_.push_back(std::move(chunk[k]));
  }
  submitted_ += chunk.size();
}

void SlurmExecutor::finish(std::size_t i, Outcome o, const std::function<void(const Outcome&)>& on_done) {
  Task t = std::move(live_[i]);
  live_.erase(live_.begin() + static_cast<std::ptrdiff_t>(i));
  o.id = t.job.id;
  on_done(o);
  if (pending_) pending_->erase(t.job.key, t.job_id);
}

void SlurmExecutor::requeue(std::size_t i, const std::string& why, const std::function<void(const Outcome&)>& on_done) {
  Task& t = live_[i];
  const int n = ++requeues_[t.job.key];
  if (n > cfg_.max_requeues) {
    Outcome o;
    o.kind = Outcome::Signaled;
    o.reason = fmt::format("gave up after {} infrastructure failures (last: {})", n, why);
    finish(i, o, on_done);
    return;
  }
  // Not counted against the run: the same attempt again, in a clean folder.
  if (pending_) pending_->erase(t.job.key, t.job_id);
  queue_.push_front(std::move(t.job));
  live_.erase(live_.begin() + static_cast<std::ptrdiff_t>(i));
  ++requeued_;
}

bool SlurmExecutor::scan_exit_files(const std::function<void(const Outcome&)>& on_done) {
  bool any = false;
  for (std::size_t i = 0; i < live_.size();) {
    Outcome o;
    if (read_exit_file(live_[i].job.spec.workdir, live_[i].job.timeout, o)) {
      // Out of memory kills the solver with SIGKILL: name the cause the scheduler saw.
      if (live_[i].state == TaskState::OutOfMemory && !o.ok())
        o.reason = "out of memory (Slurm OUT_OF_MEMORY; raise --slurm-opt mem=): " + o.reason;
      finish(i, o, on_done);
      any = true;
    } else {
      ++i;
    }
  }
  return any;
}

bool SlurmExecutor::poll_queue(const std::function<void(const Outcome&)>&) {
  std::set<std::string> ids;
  for (const Task& t : live_)
    if (!t.job_id.empty()) ids.insert(t.job_id);
  if (ids.empty()) return false;
  ++calls_.squeue;
  const CommandResult r = call({"squeue", "-h", "-r", "-t", "all", "-j", join({ids.begin(), ids.end()}, ","), "-o", "%i|%T|%r|%A"},
                               "poll the study's jobs", true);
  std::vector<QueueEntry> entries;
  if (r.status == 0) entries = parse_squeue(r.out);
  else if (r.err.find("Invalid job id") == std::string::npos)  // one unknown id alone makes squeue fail
    throw Error(fmt::format("squeue failed (exit status {}): {}", r.status, r.err));
  std::map<std::pair<std::string, int>, const QueueEntry*> by_task;
  for (const auto& e : entries) by_task[{e.array_job_id, e.index}] = &e;
  bool changed = false;
  const double now = monotonic_seconds();
  for (Task& t : live_) {
    const auto it = by_task.find({t.job_id, t.index});
    if (it == by_task.end()) {
      if (t.gone_since < 0) {
        t.gone_since = now;
        changed = true;
      }
      continue;
    }
    const QueueEntry& e = *it->second;
    if (e.state_text != t.state_text) changed = true;
    t.state = e.state;
    t.state_text = e.state_text;
    t.reason = e.reason;
    if (!e.raw_id.empty()) t.raw_id = e.raw_id;
    if (is_final(e.state)) {
      if (t.gone_since < 0) t.gone_since = now;
    } else {
      t.gone_since = -1;  // requeued by Slurm (node failure): wait for the new run
    }
  }
  return changed;
}

void SlurmExecutor::judge_gone(const std::function<void(const Outcome&)>& on_done) {
  const double now = monotonic_seconds();
  std::vector<std::size_t> due;
  for (std::size_t i = 0; i < live_.size(); ++i)
    if (live_[i].gone_since >= 0 && now - live_[i].gone_since >= cfg_.exit_wait && !fs::exists(exit_file(live_[i].job.spec.workdir)))
      due.push_back(i);
  if (due.empty()) return;
  // Why did they leave? sacct only for those squeue no longer shows; one call for all of them.
  std::vector<std::string> ask, ask_raw;
  for (std::size_t i : due)
    if (!is_final(live_[i].state)) {
      ask.push_back(fmt::format("{}_{}", live_[i].job_id, live_[i].index));
      if (!live_[i].raw_id.empty()) ask_raw.push_back(live_[i].raw_id);
    }
  std::map<std::string, std::string> acct;
  if (!ask.empty()) {
    ++calls_.sacct;
    CommandResult r = call({"sacct", "-n", "-P", "-X", "-j", join(ask, ","), "-o", "JobID,State,ExitCode"}, "ask why jobs ended");
    if (r.status == 0) acct = parse_sacct(r.out);
    if ((r.status != 0 || acct.empty()) && !ask_raw.empty()) {
      // No slurmdbd: the job completion log still answers, but knows array tasks by raw id only.
      ++calls_.sacct;
      r = call({"sacct", "-c", "-n", "-P", "-j", join(ask_raw, ","), "-o", "JobID,State,ExitCode"}, "ask why jobs ended");
      if (r.status == 0) acct = parse_sacct(r.out);
    }
  }
  // From the last index down, so erasing keeps the earlier indices valid.
  for (auto it = due.rbegin(); it != due.rend(); ++it) {
    const std::size_t i = *it;
    Task& t = live_[i];
    TaskState s = t.state;
    std::string text = t.state_text;
    if (!is_final(s)) {
      auto a = acct.find(fmt::format("{}_{}", t.job_id, t.index));
      if (a == acct.end() && !t.raw_id.empty()) a = acct.find(t.raw_id);
      if (a != acct.end()) {
        s = parse_task_state(a->second);
        text = a->second;
      }
    }
    const std::string where = fmt::format("job {}_{}", t.job_id, t.index);
    if (!is_final(s) || is_infrastructure(s)) {
      requeue(i, is_final(s) ? fmt::format("{} ended {}", where, text) : fmt::format("{} is lost (no exit file, not in the queue)", where),
              on_done);
      continue;
    }
    Outcome o;
    o.seconds = now - t.gone_since;
    if (s == TaskState::Timeout) {
      o.kind = Outcome::TimedOut;
      o.reason = fmt::format("Slurm time limit reached ({} TIMEOUT): raise --slurm-opt time= or the model's timeout", where);
    } else if (s == TaskState::OutOfMemory) {
      o.kind = Outcome::Signaled;
      o.reason = fmt::format("out of memory ({} OUT_OF_MEMORY): raise --slurm-opt mem=", where);
    } else if (s == TaskState::Cancelled) {
      o.kind = Outcome::Signaled;
      o.reason = fmt::format("cancelled outside smi-lua ({} CANCELLED)", where);
    } else {
      o.kind = Outcome::SpawnFailed;
      o.reason = fmt::format("the job wrapper ended without an exit file ({} {}{}); see {}/{}.out", where, text,
                             t.reason.empty() || t.reason == "None" ? "" : ", " + t.reason,
                             (fs::path(slurm_dir_) / t.job_name).string(), t.index);
    }
    finish(i, o, on_done);
  }
}

void SlurmExecutor::cancel_pending_tasks() {
  std::vector<std::string> ids;
  for (const Task& t : live_)
    if (!t.job_id.empty() && t.state != TaskState::Running && !is_final(t.state))
      ids.push_back(fmt::format("{}_{}", t.job_id, t.index));
  if (ids.empty()) return;
  std::vector<std::string> argv = {"scancel"};
  argv.insert(argv.end(), ids.begin(), ids.end());
  ++calls_.scancel;
  call(argv, "cancel queued runs after a failure");
  for (std::size_t i = live_.size(); i-- > 0;) {
    const Task& t = live_[i];
    if (t.job_id.empty() || t.state == TaskState::Running || is_final(t.state)) continue;
    if (fs::exists(exit_file(t.job.spec.workdir))) continue;  // it finished meanwhile: report it
    if (pending_) pending_->erase(t.job.key, t.job_id);
    live_.erase(live_.begin() + static_cast<std::ptrdiff_t>(i));
  }
}

void SlurmExecutor::run(const std::function<void(const Outcome&)>& on_done, const std::function<void()>& on_tick,
                        double tick) {
  // Exit files are read often (a stat per live run, no load on the scheduler); the queue is
  // asked once per cycle, from poll_min backing off to poll_max while nothing changes.
  // A stat per live run costs the scheduler nothing: a tenth of the polling interval, 0.2 to 1 s.
  const double scan_every = std::clamp(0.1 * cfg_.poll_min, 0.2, 1.0);
  on_done_ = &on_done;
  on_tick_ = &on_tick;
  struct Reset {
    SlurmExecutor* x;
    ~Reset() { x->on_done_ = nullptr, x->on_tick_ = nullptr; }
  } reset{this};
  double now = monotonic_seconds();
  double last_tick = now, next_scan = now, next_poll = now + interval_;
  while (!live_.empty() || (!stopping_ && !queue_.empty())) {
    if (stopping_ && !stop_done_) {
      cancel_pending_tasks();
      stop_done_ = true;
    }
    if (!stopping_ && !queue_.empty()) {
      submit_queued(on_done);
      interval_ = cfg_.poll_min;
      next_poll = monotonic_seconds() + interval_;
    }
    now = monotonic_seconds();
    bool event = false;
    if (now >= next_scan) {
      event = scan_exit_files(on_done);
      judge_gone(on_done);
      next_scan = now + scan_every;
    }
    if (now >= next_poll && !live_.empty()) {
      const bool changed = poll_queue(on_done) || event;
      judge_gone(on_done);
      interval_ = changed ? cfg_.poll_min : std::min(cfg_.poll_max, interval_ * 1.5);
      next_poll = monotonic_seconds() + interval_;
    } else if (event) {
      interval_ = cfg_.poll_min;
      next_poll = std::min(next_poll, now + interval_);
    }
    now = monotonic_seconds();
    if (event || now - last_tick >= tick) {
      if (on_tick) on_tick();
      last_tick = now;
    }
    if (live_.empty() && (stopping_ || queue_.empty())) break;
    if (!queue_.empty() && !stopping_) continue;
    nap(std::max(0.0, std::min({last_tick + tick, next_scan, next_poll}) - monotonic_seconds()));
  }
}

std::string slurm_dry_run(const ExecutorConfig& cfg, std::size_t runs, double timeout, double mean_seconds,
                          const std::string& runs_dir, const std::string& tag) {
  cfg.validate();
  int per = cfg.max_array;
  std::string per_src = "max_array";
  if (per <= 0) {
    const CommandResult r = run_command({"scontrol", "show", "config"}, cfg.cmd_timeout, cfg.bin_dir);
    per = r.status == 0 ? parse_max_array_size(r.out) : 0;
    per_src = per > 0 ? "the cluster's MaxArraySize" : "Slurm's default MaxArraySize (the cluster did not answer)";
    if (per <= 0) per = 1001;
  }
  const std::string slurm_dir = (fs::path(runs_dir) / ".slurm").string();
  const std::size_t chunks = (runs + static_cast<std::size_t>(per) - 1) / static_cast<std::size_t>(per);
  std::string s = fmt::format("slurm executor: {} run{} in {} job array{} of at most {} ({}), {} at once (%{})\n",
                              runs, runs == 1 ? "" : "s", chunks, chunks == 1 ? "" : "s", per, per_src, cfg.throttle,
                              cfg.throttle);
  s += fmt::format("job script ({}/<job name>/job.sh, written afresh for every array):\n", slurm_dir);
  std::istringstream js(SlurmExecutor::job_script());
  for (std::string line; std::getline(js, line);) s += "  | " + line + "\n";
  s += "sbatch lines:\n";
  for (std::size_t c = 0; c < chunks; ++c) {
    const std::size_t n = std::min<std::size_t>(static_cast<std::size_t>(per), runs - c * static_cast<std::size_t>(per));
    const std::string name = fmt::format("smi-{}-TOKEN-{}", tag, c);
    auto argv = SlurmExecutor::sbatch_argv(cfg, name, n, timeout, slurm_dir + "/" + name);
    argv.push_back(slurm_dir + "/" + name + "/job.sh");
    argv.push_back(slurm_dir + "/" + name + "/manifest");
    std::string line;
    for (const auto& a : argv) {
      if (!line.empty()) line += ' ';
      line += quoted(a);
    }
    s += "  " + line + "\n";
  }
  const double minutes = SlurmExecutor::time_limit_minutes(cfg, timeout);
  const int cpus = cfg.cpus > 0 ? cfg.cpus : 1;
  s += "cost plan: ";
  if (minutes > 0)
    s += fmt::format("{} run{} x {} CPU x {:g} min limit = at most {:.2f} CPU-hours requested", runs, runs == 1 ? "" : "s",
                     cpus, minutes, static_cast<double>(runs) * cpus * minutes / 60);
  else
    s += "no --time (the partition's limit applies; give a model timeout or --slurm-opt time=)";
  if (mean_seconds >= 0)
    s += fmt::format("; from stored timings about {:.3f} CPU-hours", static_cast<double>(runs) * cpus * mean_seconds / 3600);
  return s + "\n";
}

}  // namespace smi::eval
