// SPDX-License-Identifier: MIT
#include "platform/eval/evaluator.hpp"

#include "platform/core/csv.hpp"
#include "platform/core/printable.hpp"

#include <cmath>
#include <filesystem>
#include <fmt/format.h>
#include <limits>
#include <set>
#include <unordered_map>

#include "platform/core/sha256.hpp"
#include "platform/eval/pending.hpp"
#include "platform/eval/process.hpp"
#include "platform/eval/scheduler.hpp"
#include "platform/eval/text_parsers.hpp"
#include "platform/eval/work_dir.hpp"

namespace smi::eval {
namespace fs = std::filesystem;

namespace {

constexpr std::size_t kTailBytes = 2000;
const double kNaN = std::numeric_limits<double>::quiet_NaN();

void check_names(const std::vector<std::string>& names, const char* what) {
  if (names.empty()) throw InvalidArgument(fmt::format("{} must name at least one variable", what));
  std::set<std::string> seen;
  for (std::size_t i = 0; i < names.size(); ++i) {
    const auto& n = names[i];
    if (n.empty() || n.find_first_of("\t\n\r") != std::string::npos)
      throw InvalidArgument(fmt::format("{}[{}] '{}' is not a usable name (empty or with a tab/line break)", what, i + 1, n));
    if (!seen.insert(n).second) throw InvalidArgument(fmt::format("{}[{}] '{}' appears twice", what, i + 1, n));
  }
}

/// The last non-empty line of a text, cut to a readable length.
std::string last_line(const std::string& s) {
  std::size_t end = s.find_last_not_of(" \t\r\n");
  if (end == std::string::npos) return "";
  const std::size_t start = s.find_last_of('\n', end);
  std::string line = s.substr(start == std::string::npos ? 0 : start + 1, end - (start == std::string::npos ? 0 : start + 1) + 1);
  if (line.size() > 200) line = line.substr(0, 200) + "...";
  return line;
}

/// The last `n` non-empty lines of a text joined by " | ", each cut to a readable length.
std::string last_lines(std::string s, int n) {
  std::vector<std::string> out;
  while (static_cast<int>(out.size()) < n) {
    const std::string line = last_line(s);
    if (line.empty()) break;
    out.insert(out.begin(), line);
    const std::size_t end = s.find_last_not_of(" \t\r\n");
    const std::size_t start = s.find_last_of('\n', end);
    s.erase(start == std::string::npos ? 0 : start);
  }
  std::string r;
  for (const auto& l : out) r += (r.empty() ? "" : " | ") + l;
  return r;
}

/// A batch deck: the points as CSV by the one CSV codec. Numbers keep fmt's text ("{}"): the
/// deck's text is part of the store key, so existing stores stay valid.
std::string csv_of(const std::vector<std::string>& names, const Eigen::MatrixXd& rows) {
  std::vector<std::vector<std::string>> columns(static_cast<std::size_t>(rows.cols()));
  for (Eigen::Index j = 0; j < rows.cols(); ++j)
    for (Eigen::Index i = 0; i < rows.rows(); ++i) columns[static_cast<std::size_t>(j)].push_back(fmt::format("{}", rows(i, j)));
  return csv::write(names, columns);
}

}  // namespace

OnFailure parse_on_failure(const std::string& s) {
  if (s == "stop") return OnFailure::Stop;
  if (s == "skip") return OnFailure::Skip;
  if (s == "retry") return OnFailure::Retry;
  throw InvalidArgument(fmt::format("on_failure must be 'stop', 'skip' or 'retry', got '{}'", s));
}

struct Evaluator::Point {
  std::string key;
  std::vector<Eigen::Index> rows;  // every row of X with this key
  Eigen::VectorXd x;
  std::string deck;
  bool hit = false;
  Status status = Status::NotRun;
  std::string reason;
  Eigen::VectorXd y;
  double duration = 0;
};

Evaluator::Evaluator(CommandConfig cfg) : cfg_(std::move(cfg)) {
  check_names(cfg_.inputs, "inputs");
  check_names(cfg_.outputs, "outputs");
  if (cfg_.concurrency < 1) throw InvalidArgument(fmt::format("concurrency must be >= 1, got {}", cfg_.concurrency));
  if (cfg_.retries < 0) throw InvalidArgument(fmt::format("retries must be >= 0, got {}", cfg_.retries));
  if (!(cfg_.timeout >= 0)) throw InvalidArgument(fmt::format("timeout must be >= 0 seconds, got {}", cfg_.timeout));
  if (cfg_.batch_size < 0) throw InvalidArgument(fmt::format("batch_size must be >= 0, got {}", cfg_.batch_size));
  if (cfg_.deck_file.empty() || cfg_.deck_file.find('/') != std::string::npos || cfg_.deck_file == "." ||
      cfg_.deck_file == ".." || cfg_.deck_file == kStdoutFile || cfg_.deck_file == kStderrFile)
    throw InvalidArgument(fmt::format("deck file name '{}' must be a plain file name", cfg_.deck_file));
  if (!cfg_.batch && !cfg_.deck_function) {
    if (!cfg_.deck) throw InvalidArgument("a command model needs a deck template");
    for (const auto& in : cfg_.inputs) {
      if (cfg_.constants.count(in))
        throw InvalidArgument(fmt::format("'{}' is both an input and a constant", in));
      if (!cfg_.deck->uses(in))
        throw InvalidArgument(fmt::format(
            "input '{}' does not appear in template '{}'; add {{{{{}}}}} to it (points that differ only in "
            "'{}' would otherwise share one stored result)", in, cfg_.deck->source(), in, in));
    }
    // A trial render finds placeholders that are neither inputs nor constants, with their line.
    DeckValues trial = cfg_.constants;
    for (const auto& in : cfg_.inputs) trial[in] = DeckValue::num(0);
    cfg_.deck->render(trial);
  }
  // The program's content always goes into the key: a version string is the
  // script's to choose, so a record keyed on name + version alone could be forged by one study
  // and reused by another. The version stays in the key too (a solver reading data files).
  std::string program_hash;
  try {
    program_hash = "sha256:" + sha256_file(cfg_.program);
  } catch (const Error&) {
    program_hash = "unreadable";  // the run fails when it starts, with the OS's reason
  }
  if (cfg_.version.empty()) cfg_.version = program_hash;
  // Everything that determines a run's result, except the point itself.
  Sha256 h;
  h.field("smi-eval-v2").field(cfg_.batch ? "batch" : "command");
  h.field(fs::path(cfg_.program_name).filename().string()).field(program_hash).field(cfg_.version);
  for (const auto& a : cfg_.args) h.field(a);
  h.field(cfg_.deck_file);
  // The study script decides what a record holds (its parse function reads the outputs), and a
  // store may come from elsewhere (--store, or one unpacked with a study bundle): a record is
  // reused only by the script that made it. Editing the script means running again.
  h.field(cfg_.script_hash);
  for (const auto& [name, value] : cfg_.env_set) h.field("env").field(name).field(value);
  for (std::size_t i = 0; i < cfg_.files.size(); ++i)
    h.field(fs::path(cfg_.files[i]).filename().string())
        .field(i < cfg_.file_fds.size() && cfg_.file_fds[i] ? sha256_fd(cfg_.file_fds[i]->get(), cfg_.files[i])
                                                            : sha256_file(cfg_.files[i]));
  key_prefix_ = h.hex();
}

Evaluator::~Evaluator() = default;

Store& Evaluator::store() {
  if (!store_) {
    std::error_code ec;
    fs::create_directories(fs::path(cfg_.store_path).parent_path(), ec);
    store_ = std::make_unique<Store>(cfg_.store_path, false);
  }
  return *store_;
}

std::string Evaluator::render(const Eigen::VectorXd& x) const {
  if (cfg_.deck_function) {
    if (!deck_fn_) throw InvalidArgument("the model's deck function is not set (internal: set_deck_function)");
    return deck_fn_(x);
  }
  DeckValues v = cfg_.constants;
  for (std::size_t j = 0; j < cfg_.inputs.size(); ++j) v[cfg_.inputs[j]] = DeckValue::num(x[static_cast<Eigen::Index>(j)]);
  return cfg_.deck->render(v);
}

std::string Evaluator::key(const Eigen::VectorXd& x) const { return key_of(x, cfg_.batch ? "" : render(x)); }

std::string Evaluator::key_of(const Eigen::VectorXd& x, const std::string& deck) const {
  Sha256 h;
  h.field(key_prefix_);
  if (cfg_.batch) {  // no deck per point: the point's values, in shortest exact text, stand for it
    for (std::size_t j = 0; j < cfg_.inputs.size(); ++j)
      h.field(cfg_.inputs[j]).field(fmt::format("{}", x[static_cast<Eigen::Index>(j)]));
  } else {
    h.field(deck);
  }
  return h.hex();
}

std::vector<Evaluator::Point> Evaluator::points_of(const Eigen::MatrixXd& X) const {
  if (X.cols() != static_cast<Eigen::Index>(cfg_.inputs.size()))
    throw DimensionMismatch(fmt::format("X has {} columns, the model has {} inputs", X.cols(), cfg_.inputs.size()));
  std::vector<Point> pts;
  std::unordered_map<std::string, std::size_t> index;
  for (Eigen::Index i = 0; i < X.rows(); ++i) {
    for (Eigen::Index j = 0; j < X.cols(); ++j)
      if (!std::isfinite(X(i, j)))
        throw InvalidArgument(fmt::format("X[{}][{}] (input '{}') is {}; solver inputs must be finite", i + 1, j + 1,
                                          cfg_.inputs[static_cast<std::size_t>(j)], X(i, j)));
    Point p;
    p.x = X.row(i).transpose();
    if (!cfg_.batch) p.deck = render(p.x);
    p.key = key_of(p.x, p.deck);
    const auto [it, fresh] = index.emplace(p.key, pts.size());
    if (fresh) {
      p.rows.push_back(i);
      pts.push_back(std::move(p));
    } else {
      pts[it->second].rows.push_back(i);  // the same deck twice: run it once
    }
  }
  return pts;
}

bool Evaluator::lookup(Point& p) {
  if (!shared_ && !cfg_.shared_store_path.empty()) shared_ = std::make_unique<Store>(cfg_.shared_store_path, true, true);
  for (Store* s : {&store(), shared_.get()}) {
    if (!s) continue;
    auto r = s->find(p.key);
    if (!r || (!r->ok && !cfg_.reuse_failed)) continue;
    Eigen::VectorXd y = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(cfg_.outputs.size()), kNaN);
    if (r->ok) {
      // A record made before an output was added to the parser lacks it: run again.
      std::size_t found = 0;
      for (std::size_t j = 0; j < cfg_.outputs.size(); ++j)
        for (const auto& [name, value] : r->outputs)
          if (name == cfg_.outputs[j]) {
            y[static_cast<Eigen::Index>(j)] = value;
            ++found;
            break;
          }
      if (found != cfg_.outputs.size()) continue;
    }
    p.hit = true;
    p.status = r->ok ? Status::Ok : Status::Failed;
    p.reason = r->reason;
    p.y = y;
    p.duration = r->duration;
    return true;
  }
  return false;
}

Plan Evaluator::plan(const Eigen::MatrixXd& X) {
  auto pts = points_of(X);
  Plan pl;
  pl.points = static_cast<std::size_t>(X.rows());
  pl.unique = pts.size();
  for (auto& p : pts)
    if (lookup(p)) ++pl.reused;
  const std::size_t pending = pl.unique - pl.reused;
  if (cfg_.batch) {
    const std::size_t per = cfg_.batch_size > 0 ? static_cast<std::size_t>(cfg_.batch_size) : std::max<std::size_t>(pending, 1);
    pl.runs = (pending + per - 1) / per;
  } else {
    pl.runs = pending;
  }
  pl.timing = store().timing(cfg_.program_name, cfg_.version);
  if (pl.timing.count == 0 && shared_) pl.timing = shared_->timing(cfg_.program_name, cfg_.version);
  if (pending == 0)
    pl.eta_seconds = 0;
  else if (pl.timing.count > 0)
    pl.eta_seconds = static_cast<double>(pending) * pl.timing.mean / static_cast<double>(cfg_.concurrency);
  return pl;
}

std::string Evaluator::executor_plan(const Plan& pl) {
  if (cfg_.executor.kind == "local" || pl.runs == 0) return "";
  return slurm_dry_run(cfg_.executor, pl.runs, cfg_.timeout, pl.timing.count > 0 ? pl.timing.mean : -1, cfg_.runs_dir,
                       cfg_.name);
}

// One call of evaluate(): the points, the tasks that run them, and the bookkeeping of runs as
// they finish. Each step is one member; the executor calls back into on_done and on_tick.
struct Evaluator::Run {
  Evaluator& ev;
  const CommandConfig& cfg;
  const ParseFn& parse;
  const ParseBatchFn& parse_batch;
  const ProgressFn& progress;
  const Eigen::Index m;                          // outputs
  std::vector<Point> pts;
  std::vector<std::vector<std::size_t>> tasks;   // the points one process evaluates
  std::vector<int> attempts;
  std::vector<std::string> dirs, task_keys;
  EvalResult res;
  Progress prog;
  double sum_seconds = 0;
  std::unique_ptr<PendingTable> pending_runs;
  std::unique_ptr<Executor> sched;

  Run(Evaluator& e, const Eigen::MatrixXd& X, const ParseFn& p, const ParseBatchFn& pb, const ProgressFn& pr)
      : ev(e), cfg(e.cfg_), parse(p), parse_batch(pb), progress(pr), m(static_cast<Eigen::Index>(cfg.outputs.size())),
        pts(e.points_of(X)) {}

  void plan_tasks(bool launch);
  void name_tasks();
  void start_executor();
  Job make_job(std::size_t t);
  void prepare_deck(std::size_t t) const;
  Eigen::MatrixXd parse_outputs(std::size_t t) const;
  std::string failure_reason(const Outcome& o, Eigen::MatrixXd& Yt);
  void store_task(std::size_t t, const Outcome& o, const std::string& reason, const Eigen::MatrixXd& Yt);
  void check_interrupt() const;
  void on_done(const Outcome& o);
  void on_tick();
  void fill_result(Eigen::Index n, bool launch);
};

// Tasks: one point per process in command mode, chunks of batch_size in batch mode; none on a
// dry run (launch = false) or when every point is stored.
void Evaluator::Run::plan_tasks(bool launch) {
  std::vector<std::size_t> pending;
  for (std::size_t k = 0; k < pts.size(); ++k)
    if (!ev.lookup(pts[k])) pending.push_back(k);
  if (!launch) return;
  if (cfg.batch) {
    const std::size_t per = cfg.batch_size > 0 ? static_cast<std::size_t>(cfg.batch_size) : std::max<std::size_t>(pending.size(), 1);
    for (std::size_t s = 0; s < pending.size(); s += per)
      tasks.emplace_back(pending.begin() + static_cast<std::ptrdiff_t>(s),
                         pending.begin() + static_cast<std::ptrdiff_t>(std::min(pending.size(), s + per)));
  } else {
    for (std::size_t k : pending) tasks.push_back({k});
  }
}

// A task's key is its point's (a batch's: the hash of its points' keys); its work directory
// under runs_dir is named by the key's start.
void Evaluator::Run::name_tasks() {
  attempts.assign(tasks.size(), 0);
  dirs.resize(tasks.size());
  task_keys.resize(tasks.size());
  for (std::size_t t = 0; t < tasks.size(); ++t) {
    std::string id = pts[tasks[t][0]].key;
    if (cfg.batch) {
      Sha256 h;
      for (std::size_t k : tasks[t]) h.field(pts[k].key);
      id = "batch-" + h.hex();
    }
    dirs[t] = (fs::path(cfg.runs_dir) / id.substr(0, 16 + (cfg.batch ? 6 : 0))).string();
    task_keys[t] = id;
  }
}

void Evaluator::Run::start_executor() {
  prog.total = tasks.size();
  const Timing stored = tasks.empty() ? Timing{} : ev.store().timing(cfg.program_name, cfg.version);
  prog.mean_seconds = stored.count ? stored.mean : 0;
  // Slurm jobs outlive smi-lua: they are recorded in the store's pending table (written here,
  // by the evaluator's process only) so that a rerun reattaches to them.
  if (cfg.executor.kind != "local" && !tasks.empty()) pending_runs = std::make_unique<PendingTable>(ev.store().handle());
  sched = make_executor(cfg.executor, cfg.concurrency, pending_runs.get(), cfg.runs_dir, cfg.name);
}

Job Evaluator::Run::make_job(std::size_t t) {
  Job job;
  job.id = t;
  job.key = task_keys[t];
  job.attempt = attempts[t] + 1;
  job.timeout = cfg.timeout;
  job.spec.program = cfg.program;
  job.spec.workdir = dirs[t];
  job.spec.stdout_path = (fs::path(dirs[t]) / kStdoutFile).string();
  job.spec.stderr_path = (fs::path(dirs[t]) / kStderrFile).string();
  job.spec.env = solver_environment(cfg.env_names);
  apply_declared_env(job.spec.env, cfg.env_set);
  job.spec.argv.push_back(cfg.program_name);
  for (std::string a : cfg.args) {
    for (auto [pat, val] : {std::pair<std::string, std::string>{"{deck}", cfg.deck_file}, {"{workdir}", dirs[t]}})
      for (std::size_t at = a.find(pat); at != std::string::npos; at = a.find(pat, at + val.size()))
        a.replace(at, pat.size(), val);
    job.spec.argv.push_back(std::move(a));
  }
  job.prepare = [this, t] { prepare_deck(t); };
  return job;
}

// The work directory of task t with its deck: the rendered deck (command mode) or the task's
// points as CSV (batch mode).
void Evaluator::Run::prepare_deck(std::size_t t) const {
  std::string deck;
  if (cfg.batch) {
    Eigen::MatrixXd rows(static_cast<Eigen::Index>(tasks[t].size()), static_cast<Eigen::Index>(cfg.inputs.size()));
    for (std::size_t r = 0; r < tasks[t].size(); ++r) rows.row(static_cast<Eigen::Index>(r)) = pts[tasks[t][r]].x.transpose();
    deck = csv_of(cfg.inputs, rows);
  } else {
    deck = pts[tasks[t][0]].deck;
  }
  prepare_work_dir(dirs[t], cfg.deck_file, deck, cfg.files, cfg.file_fds);
}

// The outputs of a finished task, one row per point; throws ParseError when one is missing,
// the batch parser's shape is wrong, or a value is not finite.
Eigen::MatrixXd Evaluator::Run::parse_outputs(std::size_t t) const {
  Eigen::MatrixXd Yt;
  const std::size_t np = tasks[t].size();
  if (cfg.batch) {
    Yt = parse_batch(dirs[t], np);
    if (Yt.rows() != static_cast<Eigen::Index>(np) || Yt.cols() != m)
      throw ParseError(fmt::format("the batch parser returned {}x{} values for {} points and {} outputs", Yt.rows(),
                                   Yt.cols(), np, m));
  } else {
    const NamedValues vals = parse(dirs[t]);
    Yt = Eigen::MatrixXd::Constant(1, m, kNaN);
    for (Eigen::Index j = 0; j < m; ++j) {
      bool found = false;
      for (const auto& [name, v] : vals)
        if (name == cfg.outputs[static_cast<std::size_t>(j)]) {
          Yt(0, j) = v;
          found = true;
        }
      if (!found)
        throw ParseError(fmt::format("the parser returned no value for output '{}'", cfg.outputs[static_cast<std::size_t>(j)]));
    }
  }
  for (Eigen::Index i = 0; i < Yt.rows(); ++i)
    for (Eigen::Index j = 0; j < m; ++j)
      if (!std::isfinite(Yt(i, j)))
        throw ParseError(fmt::format("output '{}' is {}", cfg.outputs[static_cast<std::size_t>(j)], Yt(i, j)));
  return Yt;
}

// Why the run of outcome o failed ("" when it did not), with the end of its stderr; fills Yt
// with its outputs when it succeeded.
std::string Evaluator::Run::failure_reason(const Outcome& o, Eigen::MatrixXd& Yt) {
  const std::size_t t = o.id;
  std::string reason = o.reason;
  if (o.ok()) {
    try {
      Yt = parse_outputs(t);
    } catch (const std::exception& e) {
      reason = fmt::format("unparsable output: {}", e.what());
      // A solver that exits 0 after a fatal error says why only on stderr: show its end.
      const std::string err = last_lines(file_tail((fs::path(dirs[t]) / kStderrFile).string(), kTailBytes), 3);
      if (!err.empty()) reason += fmt::format("; the solver exited 0 but its stderr ends: {}", printable(err));
    }
    check_interrupt();  // a Ctrl-C that hit the parser is not the run's failure
  } else if (o.kind == Outcome::Exited || o.kind == Outcome::Signaled) {
    const std::string err = last_line(file_tail((fs::path(dirs[t]) / kStderrFile).string(), kTailBytes));
    if (!err.empty()) reason += ": " + printable(err);  // a solver's bytes, shown on a terminal
  }
  return reason;
}

// Task t's points take their final status and each is committed to the store.
void Evaluator::Run::store_task(std::size_t t, const Outcome& o, const std::string& reason, const Eigen::MatrixXd& Yt) {
  const std::string out_tail = file_tail((fs::path(dirs[t]) / kStdoutFile).string(), kTailBytes);
  const std::string err_tail = file_tail((fs::path(dirs[t]) / kStderrFile).string(), kTailBytes);
  const bool ok = reason.empty();
  for (std::size_t r = 0; r < tasks[t].size(); ++r) {
    Point& p = pts[tasks[t][r]];
    p.status = ok ? Status::Ok : Status::Failed;
    p.reason = reason;
    p.duration = o.seconds / static_cast<double>(tasks[t].size());
    p.y = ok ? Eigen::VectorXd(Yt.row(static_cast<Eigen::Index>(r)).transpose()) : Eigen::VectorXd::Constant(m, kNaN);
    Record rec;
    rec.key = p.key;
    rec.model = cfg.name;
    rec.program = cfg.program_name;
    rec.version = cfg.version;
    for (std::size_t j = 0; j < cfg.inputs.size(); ++j) rec.inputs.emplace_back(cfg.inputs[j], p.x[static_cast<Eigen::Index>(j)]);
    if (ok)
      for (std::size_t j = 0; j < cfg.outputs.size(); ++j) rec.outputs.emplace_back(cfg.outputs[j], p.y[static_cast<Eigen::Index>(j)]);
    rec.ok = ok;
    rec.reason = reason;
    rec.duration = p.duration;
    rec.attempts = attempts[t];
    rec.stdout_tail = out_tail;
    rec.stderr_tail = err_tail;
    rec.workdir = dirs[t];
    ev.store().put(rec);  // committed now: a SIGKILL after this line loses nothing of this run
  }
}

void Evaluator::Run::check_interrupt() const {
  if (!ev.cancel_ || !ev.cancel_->stop_requested()) return;
  const std::string why = ev.cancel_->message();
  if (!why.empty())
    throw Interrupted(fmt::format("{}; {} finished run{} of model '{}' are stored, running the study again "
                                  "resumes from there", why, prog.done, prog.done == 1 ? "" : "s", cfg.name));
}

// A run ended: retry it while retries are left, else store it and count it.
void Evaluator::Run::on_done(const Outcome& o) {
  const std::size_t t = o.id;
  ++res.launched;
  Eigen::MatrixXd Yt;
  const std::string reason = failure_reason(o, Yt);
  ++attempts[t];
  const int allowed = cfg.retries + (cfg.on_failure == OnFailure::Retry && cfg.retries == 0 ? 2 : 0);
  if (!reason.empty() && attempts[t] <= allowed) {
    sched->submit(make_job(t));  // fresh work directory, same deck: same key
    return;
  }
  store_task(t, o, reason, Yt);
  ++prog.done;
  sum_seconds += o.seconds;
  prog.mean_seconds = sum_seconds / static_cast<double>(prog.done);
  if (!reason.empty()) {
    ++prog.failed;
    if (cfg.on_failure == OnFailure::Stop) {
      sched->stop_launching();
      res.stopped = true;
    }
  }
}

void Evaluator::Run::on_tick() {
  check_interrupt();
  if (!progress) return;
  prog.running = sched->running();
  const std::size_t left = prog.total - prog.done;
  prog.eta_seconds = prog.mean_seconds > 0
                         ? static_cast<double>(left) * prog.mean_seconds / static_cast<double>(std::min<std::size_t>(
                                                                                 static_cast<std::size_t>(cfg.concurrency), std::max<std::size_t>(left, 1)))
                         : -1;
  progress(prog, false);
}

// The result per row of X, from the points (rows with the same key share one point).
void Evaluator::Run::fill_result(Eigen::Index n, bool launch) {
  res.Y = Eigen::MatrixXd::Constant(n, m, kNaN);
  res.status.assign(static_cast<std::size_t>(n), Status::NotRun);
  res.reason.assign(static_cast<std::size_t>(n), "");
  res.duration = Eigen::VectorXd::Zero(n);
  res.reused.assign(static_cast<std::size_t>(n), false);
  for (const Point& p : pts) {
    for (Eigen::Index i : p.rows) {
      const auto ui = static_cast<std::size_t>(i);
      res.status[ui] = p.status;
      res.reused[ui] = p.hit;
      res.duration[i] = p.duration;
      if (p.status == Status::Ok) res.Y.row(i) = p.y.transpose();
      if (p.status == Status::Failed) {
        res.reason[ui] = p.reason;
        ++res.failed;
      }
      if (p.status == Status::NotRun)
        res.reason[ui] = launch ? "not run: the evaluation stopped after a failure (on_failure = 'stop')"
                                : "not run: dry run";
    }
  }
}

EvalResult Evaluator::evaluate(const Eigen::MatrixXd& X, const ParseFn& parse, const ParseBatchFn& parse_batch,
                               const ProgressFn& progress, bool launch) {
  Run run(*this, X, parse, parse_batch, progress);
  run.plan_tasks(launch);
  run.name_tasks();
  run.start_executor();
  if (!run.tasks.empty()) {
    for (std::size_t t = 0; t < run.tasks.size(); ++t) run.sched->submit(run.make_job(t));
    run.sched->run([&run](const Outcome& o) { run.on_done(o); }, [&run] { run.on_tick(); });
    if (progress) progress(run.prog, true);
  }
  run.fill_result(X.rows(), launch);
  return std::move(run.res);
}

}  // namespace smi::eval
