// SPDX-License-Identifier: MIT
// bench_boundary: what crossing the C++/Lua boundary costs.
//   1. the sum of 1e7 numbers: smi.vec:sum() (one call, Eigen inside) against a plain Lua loop
//      over a table, a Lua loop indexing the vec element by element (one boundary crossing per
//      element), and Eigen alone (no Lua at all)
//   2. the start-up time of `smi-lua -e ''` (fork + exec + state set-up + sandbox), against a
//      peer command given on the command line (run_boundary.sh passes python3)
// Prints markdown rows; run_boundary.sh assembles bench/results/boundary.md.
//
// usage: bench_boundary SMI_LUA [PEER_COMMAND...]
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <spawn.h>
#include <string>
#include <sys/wait.h>
#include <vector>
#include <Eigen/Core>

#include "app/runtime.hpp"

extern char** environ;

namespace {

using Clock = std::chrono::steady_clock;
constexpr int kRepeats = 5;
constexpr int kStartups = 40;

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

/// Median seconds of calling the global Lua function `fn` (no arguments, one result).
double time_lua(smi::app::Runtime& rt, const char* fn, double& result) {
  lua_State* L = rt.state();
  std::vector<double> t;
  for (int r = 0; r < kRepeats; ++r) {
    lua_getglobal(L, fn);
    const auto a = Clock::now();
    if (rt.docall(0, 1) != LUA_OK) {
      std::fprintf(stderr, "bench_boundary: %s failed: %s\n", fn, lua_tostring(L, -1));
      std::exit(1);
    }
    t.push_back(std::chrono::duration<double>(Clock::now() - a).count());
    result = lua_tonumber(L, -1);
    lua_pop(L, 1);
  }
  return median(t);
}

/// Median wall seconds of running argv to completion.
double time_spawn(const std::vector<std::string>& args) {
  std::vector<char*> argv;
  for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
  argv.push_back(nullptr);
  std::vector<double> t;
  for (int r = 0; r < kStartups; ++r) {
    const auto a = Clock::now();
    pid_t pid;
    if (posix_spawnp(&pid, argv[0], nullptr, nullptr, argv.data(), environ) != 0) {
      std::fprintf(stderr, "bench_boundary: cannot run %s\n", argv[0]);
      std::exit(1);
    }
    int status = 0;
    waitpid(pid, &status, 0);
    t.push_back(std::chrono::duration<double>(Clock::now() - a).count());
    if (!WIFEXITED(status) || WEXITSTATUS(status) != 0) {
      std::fprintf(stderr, "bench_boundary: %s failed\n", argv[0]);
      std::exit(1);
    }
  }
  return median(t);
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2) {
    std::fprintf(stderr, "usage: bench_boundary SMI_LUA [PEER_COMMAND...]\n");
    return 2;
  }
  constexpr long n = 10'000'000;
  smi::app::Config cfg;
  cfg.quiet = true;
  smi::app::Runtime rt(cfg);
  const std::string setup =
      "N = " + std::to_string(n) + "\n"
      "t = {} for i = 1, N do t[i] = i * 0.5 end\n"
      "v = smi.vec(t)\n"
      "function vec_sum() return v:sum() end\n"
      "function table_loop() local s = 0 for i = 1, #t do s = s + t[i] end return s end\n"
      "function vec_loop() local s = 0 for i = 1, #v do s = s + v[i] end return s end\n";
  if (rt.run_string(setup, "=bench") != 0) return 1;

  double r_vec = 0, r_table = 0, r_vloop = 0;
  const double t_vec = time_lua(rt, "vec_sum", r_vec);
  const double t_table = time_lua(rt, "table_loop", r_table);
  const double t_vloop = time_lua(rt, "vec_loop", r_vloop);
  Eigen::VectorXd x(n);
  for (long i = 0; i < n; ++i) x[i] = static_cast<double>(i + 1) * 0.5;
  std::vector<double> te;
  double r_eigen = 0;
  for (int r = 0; r < kRepeats; ++r) {
    const auto a = Clock::now();
    r_eigen = x.sum();
    te.push_back(std::chrono::duration<double>(Clock::now() - a).count());
  }
  const double t_eigen = median(te);
  const double exact = 0.5 * static_cast<double>(n) * static_cast<double>(n + 1) / 2;
  if (r_vec != r_eigen || std::abs(r_table - exact) > 1e-6 * exact || std::abs(r_vloop - r_table) > 1e-6 * exact) {
    std::fprintf(stderr, "bench_boundary: sums disagree: %.17g %.17g %.17g %.17g (exact %.17g)\n", r_vec, r_table,
                 r_vloop, r_eigen, exact);
    return 1;
  }

  std::printf("## Sum of 1e7 numbers (median of %d runs)\n\n", kRepeats);
  std::printf("| what | time (ms) | vs `v:sum()` |\n|---|---:|---:|\n");
  std::printf("| `v:sum()` on a smi.vec (one call into C++) | %.2f | 1.0 |\n", t_vec * 1e3);
  std::printf("| Eigen `x.sum()` from C++, no Lua | %.2f | %.2f |\n", t_eigen * 1e3, t_eigen / t_vec);
  std::printf("| plain Lua loop over a table | %.2f | %.1f |\n", t_table * 1e3, t_table / t_vec);
  std::printf("| Lua loop indexing the smi.vec (`v[i]`, a C call per element) | %.2f | %.1f |\n\n", t_vloop * 1e3,
              t_vloop / t_vec);

  const double t_start = time_spawn({argv[1], "-e", ""});
  std::printf("## Start-up (median of %d runs, fork+exec to exit)\n\n", kStartups);
  std::printf("| command | time (ms) | vs `smi-lua -e ''` |\n|---|---:|---:|\n");
  std::printf("| `smi-lua -e ''` | %.2f | 1.0 |\n", t_start * 1e3);
  if (argc > 2) {
    std::vector<std::string> peer(argv + 2, argv + argc);
    std::string shown;
    for (const auto& p : peer) shown += (shown.empty() ? "" : " ") + (p.empty() ? std::string("''") : p);
    const double t_peer = time_spawn(peer);
    std::printf("| `%s` | %.2f | %.2f |\n", shown.c_str(), t_peer * 1e3, t_peer / t_start);
  }
  return 0;
}
