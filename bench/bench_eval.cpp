// SPDX-License-Identifier: MIT
// Overhead of one solver evaluation (spawn, deck, parse, store) with a trivial solver.
// usage: bench_eval SOLVER WORKDIR [N]
// Prints markdown table rows (ms per evaluation; 9 interleaved repeats: least wall time, median CPU):
//   bare      posix_spawn + waitpid of the solver in ready folders: the floor a process costs
//   evaluator the C++ evaluator (render, hash, store lookup, work dir, spawn, regex parse, commit)
//   lua       the same through smi.model.command with a Lua parser, in a sandboxed runtime
//   hit       a second evaluation of the same points: everything found in the store
// at concurrency 1 and 2. Overhead = evaluator (or lua) minus bare at the same concurrency.
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fmt/format.h>
#include <fstream>
#include <string>
#include <sys/resource.h>
#include <sys/wait.h>
#include <vector>

#include "app/runtime.hpp"
#include "platform/eval/evaluator.hpp"
#include "platform/eval/process.hpp"
#include "platform/eval/text_parsers.hpp"

namespace fs = std::filesystem;
using namespace smi::eval;

namespace {

/// CPU seconds (user + system) of this process itself, children excluded: the host's own cost.
double self_cpu() {
  rusage u{};
  getrusage(RUSAGE_SELF, &u);
  return static_cast<double>(u.ru_utime.tv_sec + u.ru_stime.tv_sec) + 1e-6 * static_cast<double>(u.ru_utime.tv_usec + u.ru_stime.tv_usec);
}

struct Cost {
  double wall, cpu;  // seconds per evaluation
};

template <class F>
Cost measure(int n, F&& f) {
  const double w0 = monotonic_seconds(), c0 = self_cpu();
  f();
  return {(monotonic_seconds() - w0) / n, (self_cpu() - c0) / n};
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Wall times: the least of the repeats, the run least disturbed by the rest of the machine.
double least(const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); }

Eigen::MatrixXd design(int n, double shift) {
  Eigen::MatrixXd X(n, 2);
  for (int i = 0; i < n; ++i) X.row(i) << shift + 0.001 * i, 1.0 - 0.002 * i;
  return X;
}

/// N runs of the solver, `conc` at a time, each in its own folder prepared beforehand (deck
/// written, outside the timing): the cost of the processes alone.
Cost bare(const std::string& solver, const fs::path& dir, int n, int conc) {
  std::vector<SpawnSpec> specs;
  for (int i = 0; i < n; ++i) {
    const fs::path d = dir / std::to_string(i);
    fs::create_directories(d);
    std::ofstream(d / "run.deck") << "x1 = " << 0.5 + 0.001 * i << "\nx2 = 0.25\n";
    specs.push_back({solver, {"smi-test-solver", "run.deck", "-o", "out.txt"}, d.string(), (d / "stdout.log").string(),
                     (d / "stderr.log").string()});
  }
  return measure(n, [&] {
    int started = 0, running = 0;
    while (started < n || running > 0) {
      while (running < conc && started < n) {
        spawn_process(specs[static_cast<std::size_t>(started)]);
        ++started;
        ++running;
      }
      int st = 0;
      if (::waitpid(-1, &st, 0) > 0) --running;
    }
  });
}

CommandConfig config(const std::string& solver, const fs::path& dir, int conc) {
  CommandConfig c;
  c.name = "bench";
  c.inputs = {"x1", "x2"};
  c.outputs = {"f", "g"};
  c.deck = std::make_shared<DeckTemplate>("x1 = {{x1}}\nx2 = {{x2}}\n", "bench.tpl");
  c.deck_file = "run.deck";
  c.program = solver;
  c.program_name = "smi-test-solver";
  c.args = {"{deck}", "-o", "out.txt"};
  c.version = "bench";
  c.concurrency = conc;
  c.runs_dir = (dir / "runs").string();
  c.store_path = (dir / "evaluations.sqlite").string();
  return c;
}

NamedValues parse(const std::string& wd) {
  const std::string t = read_text_file(wd + "/out.txt");
  return {{"f", regex_number(t, R"(f = (\S+))", "out.txt")}, {"g", regex_number(t, R"(g = (\S+))", "out.txt")}};
}

/// Seconds per point for a fresh evaluation and for a second one (all hits).
std::pair<Cost, Cost> evaluator(const std::string& solver, const fs::path& dir, int n, int conc) {
  fs::remove_all(dir);
  Evaluator ev(config(solver, dir, conc));
  const Eigen::MatrixXd X = design(n, conc);
  EvalResult r;
  const Cost fresh = measure(n, [&] { r = ev.evaluate(X, parse, nullptr, nullptr); });
  if (r.failed || r.launched != static_cast<std::size_t>(n)) throw std::runtime_error("bench: failures: " + r.reason[0]);
  const Cost hit = measure(n, [&] { r = ev.evaluate(X, parse, nullptr, nullptr); });
  if (r.launched != 0) throw std::runtime_error("bench: the second evaluation ran the solver");
  return {fresh, hit};
}

Cost through_lua(const std::string& solver, const fs::path& dir, int n, int conc) {
  fs::remove_all(dir);
  fs::create_directories(dir);
  smi::app::Config cfg;
  cfg.quiet = true;
  cfg.allow_exec = {solver};
  cfg.out_dir = dir.string();
  smi::app::Runtime rt(cfg);
  const std::string chunk = fmt::format(R"lua(
    local m = smi.model.command{{name = "bench", inputs = {{"x1", "x2"}}, outputs = {{"f", "g"}},
      template_string = "x1 = {{{{x1}}}}\nx2 = {{{{x2}}}}\n", deck = "run.deck", version = "bench-lua",
      command = {{"{}", "{{deck}}", "-o", "out.txt"}}, concurrency = {},
      parse = function(dir, h) return {{f = h.regex("out.txt", "f = (\\S+)"), g = h.regex("out.txt", "g = (\\S+)")}} end}}
    local rows = {{}}
    for i = 1, {} do rows[i] = {{{} + 0.001 * i, 1 - 0.002 * i}} end
    local Y, info = m:evaluate(smi.mat(rows))
    assert(info.failed == 0 and info.launched == {}, "bench: failures")
  )lua", solver, conc, n, conc, n);
  int status = 0;
  const Cost c = measure(n, [&] { status = rt.run_string(chunk, "=bench"); });
  if (status != 0) throw std::runtime_error("bench: the Lua study failed");
  return c;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: bench_eval SOLVER WORKDIR [N]\n");
    return 2;
  }
  const std::string solver = fs::absolute(argv[1]).string();
  const fs::path work = fs::absolute(argv[2]);
  const int n = argc > 3 ? std::atoi(argv[3]) : 50;
  try {
    for (int conc : {1, 2}) {
      std::vector<double> bw, bc, ew, ec, lw, lc, hw;
      for (int rep = 0; rep < 9; ++rep) {  // interleaved, so load from elsewhere hits all alike
        // A fresh folder per measurement, as in a study (no just-deleted inodes to skip over).
        const std::string tag = fmt::format("-{}-{}", conc, rep);
        const Cost b = bare(solver, work / ("bare" + tag), n, conc);
        const auto [e, h] = evaluator(solver, work / ("evaluator" + tag), n, conc);
        const Cost l = through_lua(solver, work / ("lua" + tag), n, conc);
        bw.push_back(b.wall); bc.push_back(b.cpu);
        ew.push_back(e.wall); ec.push_back(e.cpu);
        lw.push_back(l.wall); lc.push_back(l.cpu);
        hw.push_back(h.wall);
      }
      const double BW = least(bw), BC = median(bc), EW = least(ew), EC = median(ec), LW = least(lw),
                   LC = median(lc), HW = least(hw);
      std::printf("| %d | %d | %.2f | %.2f | %.2f | %.3f | %.3f | %.3f | %.2f | %.2f | %.4f |\n", conc, n, BW * 1e3,
                  EW * 1e3, LW * 1e3, BC * 1e3, EC * 1e3, LC * 1e3, (EW - BW) * 1e3, (LW - BW) * 1e3, HW * 1e3);
    }
  } catch (const std::exception& ex) {
    std::fprintf(stderr, "bench_eval: %s\n", ex.what());
    return 1;
  }
  return 0;
}
