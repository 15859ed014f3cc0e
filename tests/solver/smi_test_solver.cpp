// SPDX-License-Identifier: MIT
// smi-test-solver DECK [-o RESULTS]: a stand-in for a CAE solver, built in the tree so the
// evaluation tests run real child processes.
//
// The deck is "key = value" lines ('#' comments). Numeric keys named x<anything> are inputs; it
// writes RESULTS (default results.txt) with
//     f = sum of x_i^2        g = sum of i * x_i (i = 1.. in deck order)
//     start = t0   end = t1   (CLOCK_MONOTONIC seconds, so tests can see runs overlap)
// and results.csv with columns f,g. Behaviour keys:
//     mode = ok | crash | exit | hang | hang_group | hang_setsid | garbage | no_output | stderr_only | flaky
//     hang_setsid: like hang, with a child that leaves the group and session (setsid) and
//     appends "<its pid> escape" to `log`, as a solver's licence daemon would
//     sleep = seconds before writing    exit_code = n (mode = exit)
//     log = /abs/path: appends "<pid> <first x>" per run (counts launches across a study)
//     flaky: fails (exit 7) unless the file flaky.ok exists in the folder of `log`; creates it
// Any other string value (e.g. label = $(rm -rf ~)) is copied verbatim to echo.txt.
// `smi-test-solver --version` prints a version line.
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <fstream>
#include <map>
#include <optional>
#include <sstream>
#include <string>
#include <unistd.h>
#include <vector>

namespace {

double now() {
  timespec ts{};
  clock_gettime(CLOCK_MONOTONIC, &ts);
  return static_cast<double>(ts.tv_sec) + 1e-9 * static_cast<double>(ts.tv_nsec);
}

void nap(double s) {
  timespec ts{static_cast<time_t>(s), static_cast<long>((s - std::floor(s)) * 1e9)};
  while (nanosleep(&ts, &ts) != 0) {
  }
}

std::string trim(const std::string& s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string::npos) return "";
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

/// Batch form: a CSV of points (header x1,x2,...) in, results.csv (f,g per row, same order) out.
int batch(const char* path) {
  std::ifstream in(path);
  std::string line;
  if (!std::getline(in, line)) {
    std::fprintf(stderr, "smi-test-solver: empty batch file '%s'\n", path);
    return 2;
  }
  std::ofstream out("results.csv");
  out << "f,g\n";
  char buf[128];
  int rows = 0;
  while (std::getline(in, line)) {
    if (trim(line).empty()) continue;
    std::stringstream ss(line);
    std::string cell;
    double f = 0, g = 0;
    for (int i = 1; std::getline(ss, cell, ','); ++i) {
      const double x = std::strtod(cell.c_str(), nullptr);
      f += x * x;
      g += i * x;
    }
    std::snprintf(buf, sizeof buf, "%.17g,%.17g\n", f, g);
    out << buf;
    ++rows;
  }
  std::printf("smi-test-solver: batch of %d points\n", rows);
  return 0;
}

// The deck: "key = value" lines; x* keys are the inputs (numbers), mode/sleep/exit_code/log
// steer the solver's behaviour, any other value is echoed to echo.txt.
struct Deck {
  std::vector<std::pair<std::string, double>> xs;
  std::map<std::string, std::string> keys;
  std::string echo;
};

// 0, or the exit status for a malformed deck (after saying why on stderr).
int read_deck(const char* path, std::ifstream& in, Deck& d) {
  std::string line;
  int lineno = 0;
  while (std::getline(in, line)) {
    ++lineno;
    const auto hash = line.find('#');
    if (hash == 0) continue;
    const auto eq = line.find('=');
    if (trim(line).empty()) continue;
    if (eq == std::string::npos) {
      std::fprintf(stderr, "smi-test-solver: %s line %d: expected key = value\n", path, lineno);
      return 3;
    }
    const std::string k = trim(line.substr(0, eq)), v = trim(line.substr(eq + 1));
    d.keys[k] = v;
    if (!k.empty() && k[0] == 'x') {
      char* end = nullptr;
      const double x = std::strtod(v.c_str(), &end);
      if (end == v.c_str() || *end) {
        std::fprintf(stderr, "smi-test-solver: %s line %d: '%s' is not a number\n", path, lineno, v.c_str());
        return 3;
      }
      d.xs.emplace_back(k, x);
    } else if (k != "mode" && k != "sleep" && k != "exit_code" && k != "log") {
      d.echo += v + "\n";
    }
  }
  return 0;
}

// The failure modes tests ask for (crash, exit, flaky, hang*, no_output, stderr_only): the exit
// status to end with, or none to go on and write results. Hanging modes never return.
std::optional<int> misbehave(const std::string& mode, std::map<std::string, std::string>& keys) {
  if (mode == "crash") {
    std::fprintf(stderr, "smi-test-solver: crashing on purpose\n");
    std::fflush(stderr);
    std::abort();
  }
  if (mode == "exit") {
    std::fprintf(stderr, "smi-test-solver: fatal error 1234 (on purpose)\n");
    return keys.count("exit_code") ? std::atoi(keys["exit_code"].c_str()) : 1;
  }
  if (mode == "flaky") {
    const std::string dir = keys["log"].substr(0, keys["log"].rfind('/'));
    const std::string ok = dir + "/flaky.ok";
    if (access(ok.c_str(), F_OK) != 0) {
      std::ofstream(ok) << "ok\n";
      std::fprintf(stderr, "smi-test-solver: licence server busy (on purpose)\n");
      return 7;
    }
  }
  if (mode == "hang_setsid") {
    const pid_t child = fork();
    if (child == 0) {
      setsid();
      if (keys.count("log")) std::ofstream(keys["log"], std::ios::app) << getpid() << " escape\n";
      signal(SIGTERM, SIG_IGN);
      signal(SIGHUP, SIG_IGN);
      for (;;) pause();
    }
  }
  if (mode == "hang" || mode == "hang_group" || mode == "hang_setsid") {
    if (mode == "hang_group") {
      const pid_t child = fork();
      if (child == 0) {
        for (;;) pause();
      }
      std::ofstream("child.pid") << child << '\n';
    }
    signal(SIGTERM, SIG_IGN);  // a stubborn solver: only SIGKILL ends it
    for (;;) pause();
  }
  if (mode == "no_output") return 0;
  if (mode == "stderr_only") {  // a solver that exits 0 after a fatal error, saying so on stderr only
    std::fprintf(stderr, "smi-test-solver: reading deck\nsmi-test-solver: licence expired (on purpose)\n");
    return 0;
  }
  return std::nullopt;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc == 2 && std::strcmp(argv[1], "--version") == 0) {
    std::puts("smi-test-solver 1.0");
    return 0;
  }
  const double t0 = now();
  if (argc != 2 && !(argc == 4 && std::strcmp(argv[2], "-o") == 0)) {
    std::fprintf(stderr, "usage: smi-test-solver DECK [-o RESULTS]\n");
    return 2;
  }
  const std::string out_path = argc == 4 ? argv[3] : "results.txt";
  if (std::string(argv[1]).size() > 4 && std::string(argv[1]).substr(std::string(argv[1]).size() - 4) == ".csv")
    return batch(argv[1]);
  std::ifstream deck(argv[1]);
  if (!deck) {
    std::fprintf(stderr, "smi-test-solver: cannot read deck '%s'\n", argv[1]);
    return 2;
  }
  Deck d;
  if (const int rc = read_deck(argv[1], deck, d)) return rc;
  auto& xs = d.xs;
  auto& keys = d.keys;
  const std::string& echo = d.echo;
  if (keys.count("log")) {
    std::ofstream log(keys["log"], std::ios::app);
    log << getpid() << ' ' << (xs.empty() ? 0.0 : xs[0].second) << '\n';
  }
  if (!echo.empty()) std::ofstream("echo.txt") << echo;
  const std::string mode = keys.count("mode") ? keys["mode"] : "ok";
  if (keys.count("sleep")) nap(std::atof(keys["sleep"].c_str()));
  std::fprintf(stdout, "smi-test-solver: %zu inputs, mode %s\n", xs.size(), mode.c_str());
  std::fflush(stdout);
  if (const std::optional<int> rc = misbehave(mode, keys)) return *rc;
  std::ofstream out(out_path);
  if (mode == "garbage") {
    out << "f = banana\ng = ####\n";
    return 0;
  }
  double f = 0, g = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    f += xs[i].second * xs[i].second;
    g += static_cast<double>(i + 1) * xs[i].second;
  }
  char buf[256];
  std::snprintf(buf, sizeof buf, "f = %.17g\ng = %.17g\nstart = %.9f\nend = %.9f\n", f, g, t0, now());
  out << buf;
  std::ofstream csv("results.csv");
  std::snprintf(buf, sizeof buf, "f,g\n%.17g,%.17g\n", f, g);
  csv << buf;
  return 0;
}
