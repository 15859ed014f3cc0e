// SPDX-License-Identifier: MIT
// smi-lua test DIR: runs each DIR/tests/test_*.lua as its own sandboxed smi-lua process (so one
// test cannot disturb another), with DIR on the library path and, when the --lib folders do not
// meet its `requires`, the libraries its `sources` name (resolved and locked under the output
// folder, as libs add would), and prints one summary line,
// "N passed, N failed", counting cases (each file's own "N passed, N failed" from T.finish()),
// the form every test file prints too. A file that stops before its summary (a syntax error, a
// crash) counts as one failed case; a file exiting 0 without a summary as one passed case.
// A file passes when it exits with status 0 (T.finish() raises when a case failed).
#include <algorithm>
#include <cerrno>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <re2/re2.h>
#include <string>
#include <sys/wait.h>

#include "cli/commands.hpp"
#include "platform/core/errors.hpp"
#include "platform/eval/process.hpp"

namespace smi::cli {
namespace fs = std::filesystem;
namespace {

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// The last "N passed, N failed" line a test printed ("" if none), and its counts.
std::string case_summary(const std::string& out, long& passed, long& failed) {
  static const RE2 re(R"(((\d+) passed, (\d+) failed))");
  re2::StringPiece rest(out);
  std::string m, last;
  long p = 0, f = 0;
  while (RE2::FindAndConsume(&rest, re, &m, &p, &f)) {
    last = m;
    passed = p;
    failed = f;
  }
  return last;
}

std::string indent(const std::string& text) {
  std::string out = "    ";
  for (char c : text) {
    out += c;
    if (c == '\n') out += "    ";
  }
  while (!out.empty() && (out.back() == ' ' || out.back() == '\n')) out.pop_back();
  return out;
}

}  // namespace

int cmd_test(const Args& a, const std::vector<std::string>& args, const char* argv0) {
  if (args.size() != 1) {
    std::fprintf(stderr, "usage: smi-lua test DIR   (DIR is a library folder holding smi-lib.lua and tests/test_*.lua)\n");
    return 2;
  }
  const fs::path dir = args[0];
  std::error_code ec;
  const vm::Manifest m = vm::read_library_folder(dir);
  std::vector<fs::path> tests;
  if (fs::is_directory(dir / "tests", ec))
    for (const auto& e : fs::directory_iterator(dir / "tests", ec)) {
      const std::string f = e.path().filename().string();
      if (e.is_regular_file(ec) && f.rfind("test_", 0) == 0 && e.path().extension() == ".lua") tests.push_back(e.path());
    }
  std::sort(tests.begin(), tests.end());
  if (tests.empty())
    throw Error("library " + m.name + " has no tests: add files " + (dir / "tests" / "test_*.lua").string() +
                " (smi-lua new-lib makes an example)");

  fs::path self = fs::read_symlink("/proc/self/exe", ec);
  if (ec) self = argv0;
  const fs::path out_base = a.cfg.out_dir.empty() ? fs::path("smi-out") / ("test-" + m.name) : fs::path(a.cfg.out_dir);
  fs::create_directories(out_base, ec);
  if (ec) throw Error("cannot create the output folder '" + out_base.string() + "': " + ec.message());

  // The library's own requirements: from the --lib folders, else fetched from its `sources`.
  const std::string deps = test_dependencies(a, dir, out_base / "requires");
  std::printf("testing %s %s (%s)\n", m.name.c_str(), m.version.text.c_str(), dir.string().c_str());
  std::fflush(stdout);
  int passed = 0, failed = 0;  // files
  long cases_passed = 0, cases_failed = 0;
  for (const fs::path& t : tests) {
    const std::string stem = t.stem().string();
    std::vector<std::string> av = {self.string(), "--quiet"};
    if (a.ignore_env) av.push_back("-E");
    av.insert(av.end(), {"--lib", dir.string()});
    for (const auto& d : a.cfg.lib_dirs) av.insert(av.end(), {"--lib", d});
    if (!deps.empty()) av.insert(av.end(), {"--lib", deps});
    for (const auto& d : a.cfg.allow_read) av.insert(av.end(), {"--allow-read", d});
    for (const auto& d : a.cfg.allow_write) av.insert(av.end(), {"--allow-write", d});
    for (const auto& d : a.cfg.allow_exec) av.insert(av.end(), {"--allow-exec", d});
    for (const auto& d : a.cfg.allow_env) av.insert(av.end(), {"--allow-env", d});
    if (!a.cfg.stdlib_dir.empty()) av.insert(av.end(), {"--stdlib-dir", a.cfg.stdlib_dir});
    if (a.cfg.timeout_s > 0) av.insert(av.end(), {"--timeout", std::to_string(a.cfg.timeout_s)});
    if (a.cfg.max_memory_mb > 0) av.insert(av.end(), {"--max-memory", std::to_string(a.cfg.max_memory_mb)});
    av.insert(av.end(), {"--seed", std::to_string(a.cfg.seed), "--out", (out_base / stem).string(), "--", t.string()});
    eval::SpawnSpec spec;
    spec.program = self.string();
    spec.argv = av;
    spec.workdir = fs::current_path().string();
    spec.stdout_path = fs::absolute(out_base / (stem + ".stdout.txt")).string();
    spec.stderr_path = fs::absolute(out_base / (stem + ".stderr.txt")).string();
    const pid_t pid = eval::spawn_process(spec);
    int status = 0;
    while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
    }
    const bool ok = WIFEXITED(status) && WEXITSTATUS(status) == 0;
    const std::string out = read_all(spec.stdout_path), err = read_all(spec.stderr_path);
    long cp = 0, cf = 0;
    const std::string cases = case_summary(out, cp, cf);
    if (cases.empty()) (ok ? cp : cf) = 1;  // no count printed: the file is one case
    if (!ok && cf == 0) cf = 1;              // exited non-zero after a clean summary: still a failure
    cases_passed += cp;
    cases_failed += cf;
    const std::string rel = t.lexically_relative(dir).generic_string();
    if (ok) {
      ++passed;
      std::printf("ok    %s%s\n", rel.c_str(), cases.empty() ? "" : (" (" + cases + ")").c_str());
    } else {
      ++failed;
      std::printf("FAIL  %s (%s%s)\n", rel.c_str(), eval::describe_wait_status(status).c_str(),
                  cases.empty() ? "" : ("; " + cases).c_str());
      if (!err.empty()) std::printf("%s\n", indent(err).c_str());
    }
    std::fflush(stdout);
  }
  std::printf("%ld passed, %ld failed (%d test file%s, %d failed)\n", cases_passed, cases_failed, passed + failed,
              passed + failed == 1 ? "" : "s", failed);
  return failed == 0 ? 0 : 1;
}

}  // namespace smi::cli
