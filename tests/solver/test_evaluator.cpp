// SPDX-License-Identifier: MIT
// The evaluator driving a real child process (smi-test-solver): results in input order, reuse
// from the store, overlap at concurrency 2, failures as records, timeout killing the process
// group, retry, hostile values, batch form, and a study killed with SIGKILL that resumes.
#include <catch2/catch.hpp>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <sys/wait.h>
#include <unistd.h>

#include "platform/eval/evaluator.hpp"
#include "platform/eval/text_parsers.hpp"

using namespace smi::eval;
namespace fs = std::filesystem;

namespace {

fs::path fresh_dir(const std::string& name) {
  const fs::path d = fs::absolute("eval-tests") / name;
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

/// A model of the test solver: f = sum x_i^2, g = sum i*x_i; `extra` lines go into the deck.
CommandConfig config(const fs::path& dir, const std::string& extra, int concurrency = 1) {
  CommandConfig c;
  c.name = "t";
  c.inputs = {"x1", "x2"};
  c.outputs = {"f", "g"};
  c.deck = std::make_shared<DeckTemplate>("# test deck\nx1 = {{x1}}\nx2 = {{x2}}\n" + extra, "test.tpl");
  c.deck_file = "run.deck";
  c.program = SMI_TEST_SOLVER;
  c.program_name = "smi-test-solver";
  c.args = {"{deck}", "-o", "out.txt"};
  c.version = "test-1";
  c.concurrency = concurrency;
  c.runs_dir = (dir / "runs").string();
  c.store_path = (dir / "evaluations.sqlite").string();
  return c;
}

NamedValues parse_out(const std::string& wd) {
  const std::string t = read_text_file(wd + "/out.txt");
  return {{"f", regex_number(t, R"(f = (\S+))", "out.txt")}, {"g", regex_number(t, R"(g = (\S+))", "out.txt")},
          {"start", regex_number(t, R"(start = (\S+))", "out.txt")}, {"end", regex_number(t, R"(end = (\S+))", "out.txt")}};
}

Eigen::MatrixXd design(int n) {
  Eigen::MatrixXd X(n, 2);
  for (int i = 0; i < n; ++i) X.row(i) << 0.5 * i + 0.1, 1.0 - 0.25 * i;
  return X;
}

long lines_in(const fs::path& p) {
  std::ifstream in(p);
  long n = 0;
  std::string s;
  while (std::getline(in, s)) ++n;
  return n;
}

bool process_alive(pid_t pid) {
  std::ifstream st("/proc/" + std::to_string(pid) + "/stat");
  std::string s;
  if (!std::getline(st, s)) return false;
  const auto close = s.rfind(')');
  return close != std::string::npos && close + 2 < s.size() && s[close + 2] != 'Z';
}

}  // namespace

TEST_CASE("outputs come back in input order and a second evaluation reuses the store") {
  const fs::path dir = fresh_dir("basic");
  Evaluator ev(config(dir, "log = " + (dir / "log.txt").string() + "\n"));
  Eigen::MatrixXd X = design(4);
  X.row(3) = X.row(1);  // a repeated point runs once
  const EvalResult r = ev.evaluate(X, parse_out, nullptr, nullptr);
  REQUIRE(r.failed == 0);
  CHECK(r.launched == 3);
  for (int i = 0; i < 4; ++i) {
    CHECK(r.status[i] == Status::Ok);
    CHECK(r.Y(i, 0) == X(i, 0) * X(i, 0) + X(i, 1) * X(i, 1));
    CHECK(r.Y(i, 1) == X(i, 0) + 2 * X(i, 1));
  }
  CHECK(lines_in(dir / "log.txt") == 3);
  const EvalResult again = Evaluator(config(dir, "log = " + (dir / "log.txt").string() + "\n")).evaluate(X, parse_out, nullptr, nullptr);
  CHECK(again.launched == 0);
  CHECK(again.reused[0]);
  CHECK(again.Y == r.Y);
  CHECK(lines_in(dir / "log.txt") == 3);
  const Plan pl = ev.plan(design(6));
  CHECK(pl.reused == 3);
  CHECK(pl.runs == 3);
  CHECK(pl.timing.count == 3);
  CHECK(pl.eta_seconds == Approx(3 * pl.timing.mean));
}

TEST_CASE("concurrency 2 overlaps runs and gives the same numbers as concurrency 1") {
  Eigen::MatrixXd X = design(4);
  EvalResult r1, r2;
  std::vector<std::pair<double, double>> spans;
  for (int conc : {1, 2}) {
    const fs::path dir = fresh_dir("overlap" + std::to_string(conc));
    CommandConfig c = config(dir, "sleep = 0.3\n", conc);
    c.outputs = {"f", "g", "start", "end"};
    EvalResult r = Evaluator(c).evaluate(X, parse_out, nullptr, nullptr);
    REQUIRE(r.failed == 0);
    int overlaps = 0;
    for (int i = 0; i < 4; ++i)
      for (int j = i + 1; j < 4; ++j)
        if (r.Y(i, 2) < r.Y(j, 3) && r.Y(j, 2) < r.Y(i, 3)) ++overlaps;
    if (conc == 1) {
      CHECK(overlaps == 0);
      r1 = r;
    } else {
      CHECK(overlaps >= 2);  // (1,2) and (3,4) at least
      r2 = r;
    }
  }
  CHECK(r1.Y.leftCols(2) == r2.Y.leftCols(2));
}

TEST_CASE("failures become records with their reason; skip keeps going, stop stops") {
  const fs::path dir = fresh_dir("failures");
  // Each point picks its own behaviour through a string constant rendered into the deck.
  struct Case { const char* mode; const char* reason; };
  for (const Case& k : {Case{"crash", "killed by signal 6"}, Case{"exit", "exit status 1: smi-test-solver: fatal error 1234"},
                        Case{"garbage", "unparsable output"}, Case{"no_output", "out.txt' is missing"},
                        // exit 0, no output, the cause only on stderr: the reason shows it
                        Case{"stderr_only", "licence expired (on purpose)"}}) {
    CommandConfig c = config(dir / k.mode, std::string("mode = ") + k.mode + "\n");
    c.on_failure = OnFailure::Skip;
    const EvalResult r = Evaluator(c).evaluate(design(2), parse_out, nullptr, nullptr);
    CHECK(r.failed == 2);
    CHECK(r.status[0] == Status::Failed);
    CHECK_THAT(r.reason[0], Catch::Contains(k.reason));
    CHECK(std::isnan(r.Y(0, 0)));
    Store s(c.store_path, true);
    CHECK(s.count() == 2);
  }
  // stop: the first failure ends the evaluation; later points are not run.
  CommandConfig c = config(dir / "stop", "mode = exit\n");
  c.on_failure = OnFailure::Stop;
  const EvalResult r = Evaluator(c).evaluate(design(3), parse_out, nullptr, nullptr);
  CHECK(r.stopped);
  CHECK(r.launched == 1);
  CHECK(r.status[1] == Status::NotRun);
  CHECK_THAT(r.reason[2], Catch::Contains("on_failure = 'stop'"));
}

TEST_CASE("a timeout kills the whole process group, and a bad program is a failure, not a crash") {
  const fs::path dir = fresh_dir("timeout");
  CommandConfig c = config(dir, "mode = hang_group\n");
  c.timeout = 0.3;
  c.on_failure = OnFailure::Skip;
  const EvalResult r = Evaluator(c).evaluate(design(1), parse_out, nullptr, nullptr);
  REQUIRE(r.status[0] == Status::Failed);
  CHECK_THAT(r.reason[0], Catch::Contains("timeout after 0.3 s"));
  // The solver forked a helper that ignores nothing; it must be gone with its group.
  fs::path pidfile;
  for (const auto& e : fs::directory_iterator(dir / "runs")) pidfile = e.path() / "child.pid";
  std::ifstream in(pidfile);
  pid_t child = 0;
  REQUIRE(in >> child);
  bool alive = true;
  for (int i = 0; i < 200 && alive; ++i, usleep(10000)) alive = process_alive(child);
  CHECK_FALSE(alive);

  CommandConfig bad = config(dir / "bad", "");
  bad.program = "/nonexistent/solver";
  bad.on_failure = OnFailure::Skip;
  const EvalResult b = Evaluator(bad).evaluate(design(1), parse_out, nullptr, nullptr);
  CHECK_THAT(b.reason[0], Catch::Contains("cannot start '/nonexistent/solver'"));
}

TEST_CASE("retry runs a failed point again in a fresh work directory") {
  const fs::path dir = fresh_dir("retry");
  CommandConfig c = config(dir, "mode = flaky\nlog = " + (dir / "log.txt").string() + "\n");
  c.on_failure = OnFailure::Retry;
  const EvalResult r = Evaluator(c).evaluate(design(1), parse_out, nullptr, nullptr);
  CHECK(r.status[0] == Status::Ok);
  CHECK(r.launched == 2);
  CHECK(lines_in(dir / "log.txt") == 2);
}

TEST_CASE("hostile values reach the deck literally and nothing interprets them") {
  const fs::path dir = fresh_dir("hostile");
  const std::string hostile = "a;rm -rf " + dir.string() + " ; $(touch pwned) `touch pwned2` > pwned3";
  CommandConfig c = config(dir, "label = {{label}}\n");
  c.constants["label"] = DeckValue::str(hostile);
  const EvalResult r = Evaluator(c).evaluate(design(1), parse_out, nullptr, nullptr);
  REQUIRE(r.status[0] == Status::Ok);
  fs::path wd;
  for (const auto& e : fs::directory_iterator(dir / "runs")) wd = e.path();
  CHECK(read_text_file((wd / "run.deck").string()).find("label = " + hostile + "\n") != std::string::npos);
  CHECK(read_text_file((wd / "echo.txt").string()) == hostile + "\n");
  for (const char* f : {"pwned", "pwned2", "pwned3"}) {
    CHECK_FALSE(fs::exists(wd / f));
    CHECK_FALSE(fs::exists(fs::current_path() / f));
  }
  // A placeholder that is neither input nor constant is caught before anything runs.
  CHECK_THROWS_WITH(Evaluator(config(dir, "E = {{E}}\n")), Catch::Contains("test.tpl' line 4") && Catch::Contains("{{E}}"));
}

TEST_CASE("batch form: one run for many points, results per point in order and stored per point") {
  const fs::path dir = fresh_dir("batch");
  CommandConfig c = config(dir, "");
  c.deck = nullptr;
  c.batch = true;
  c.batch_size = 3;
  c.deck_file = "points.csv";
  c.args = {"{deck}"};
  c.concurrency = 2;
  auto parse_batch = [](const std::string& wd, std::size_t n) {
    const std::string t = read_text_file(wd + "/results.csv");
    Eigen::MatrixXd Y(static_cast<Eigen::Index>(n), 2);
    Y.col(0) = csv_column(t, "f", "results.csv");
    Y.col(1) = csv_column(t, "g", "results.csv");
    return Y;
  };
  const Eigen::MatrixXd X = design(7);
  const EvalResult r = Evaluator(c).evaluate(X, nullptr, parse_batch, nullptr);
  CHECK(r.launched == 3);  // 3 + 3 + 1
  for (int i = 0; i < 7; ++i) CHECK(r.Y(i, 1) == X(i, 0) + 2 * X(i, 1));
  const EvalResult again = Evaluator(c).evaluate(design(8), nullptr, parse_batch, nullptr);
  CHECK(again.launched == 1);  // only the new point
  CHECK(again.Y(7, 0) == Approx(design(8)(7, 0) * design(8)(7, 0) + design(8)(7, 1) * design(8)(7, 1)));
}

TEST_CASE("a study killed with SIGKILL resumes and loses nothing that had finished") {
  const fs::path dir = fresh_dir("kill9");
  const fs::path log = dir / "log.txt";
  const CommandConfig c = config(dir, "sleep = 0.15\nlog = " + log.string() + "\n");
  const Eigen::MatrixXd X = design(8);
  const pid_t study = fork();
  REQUIRE(study >= 0);
  if (study == 0) {
    Evaluator(c).evaluate(X, parse_out, nullptr, nullptr);
    _exit(0);
  }
  // Wait until three runs are stored, then kill the study mid-run.
  long stored = 0;
  for (int i = 0; i < 500 && stored < 3; ++i, usleep(10000))
    if (fs::exists(c.store_path)) try {
        stored = Store(c.store_path, true).count();
      } catch (const std::exception&) {
      }
  REQUIRE(stored >= 3);
  kill(study, SIGKILL);
  int st = 0;
  waitpid(study, &st, 0);
  CHECK(WIFSIGNALED(st));
  // Its solver, orphaned in its own process group, finishes or is reaped by init; wait for it.
  usleep(300000);
  const long before = Store(c.store_path, true).count();
  const long launched_before = lines_in(log);
  CHECK(before >= 3);
  CHECK(before < 8);
  const EvalResult r = Evaluator(c).evaluate(X, parse_out, nullptr, nullptr);
  REQUIRE(r.failed == 0);
  CHECK(static_cast<long>(r.launched) == 8 - before);
  CHECK(lines_in(log) == launched_before + 8 - before);
  for (int i = 0; i < 8; ++i) CHECK(r.Y(i, 0) == X(i, 0) * X(i, 0) + X(i, 1) * X(i, 1));
}

TEST_CASE("the key changes with the deck, version, command line and extra files, and only with them") {
  const fs::path dir = fresh_dir("keys");
  const Eigen::VectorXd x = design(1).row(0).transpose();
  const std::string base = Evaluator(config(dir, "")).key(x);
  CHECK(base.size() == 64);
  CHECK(Evaluator(config(dir, "")).key(x) == base);
  CommandConfig other_out = config(dir / "elsewhere", "");  // other folders, same run
  CHECK(Evaluator(other_out).key(x) == base);
  CHECK(Evaluator(config(dir, "")).key(x + Eigen::VectorXd::Constant(2, 1e-15)) != base);
  CommandConfig v = config(dir, "");
  v.version = "test-2";
  CHECK(Evaluator(v).key(x) != base);
  CommandConfig a = config(dir, "");
  a.args = {"{deck}", "-o", "other.txt"};
  CHECK(Evaluator(a).key(x) != base);
  std::ofstream(dir / "mesh.dat") << "grid 1\n";
  CommandConfig f = config(dir, "");
  f.files = {(dir / "mesh.dat").string()};
  const std::string with_file = Evaluator(f).key(x);
  CHECK(with_file != base);
  std::ofstream(dir / "mesh.dat") << "grid 2\n";
  CHECK(Evaluator(f).key(x) != with_file);
  CommandConfig d = config(dir, "");
  d.version = "";  // default: the program file's hash
  CHECK_THAT(Evaluator(d).version(), Catch::StartsWith("sha256:"));
}
