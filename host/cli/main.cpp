// SPDX-License-Identifier: MIT
// smi-lua [options] [script [args]]: parses the command line, builds the runtime, runs -e/-l,
// the script and the REPL in lua.c's order. Exit status: 0 ok, 1 script error, 2 usage error,
// 128 + signal when SIGINT, SIGTERM or SIGHUP stopped the run (130, 143, 129), or the code given
// to os.exit.
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <filesystem>
#include <malloc.h>
#include <string>
#include <unistd.h>
#include <vector>

#include "app/runtime.hpp"
#include "cli/args.hpp"
#include "cli/bindings_root.hpp"
#include "cli/commands.hpp"
#include "platform/eval/process.hpp"
#include "repl/repl.hpp"
#include "vm/build_info.hpp"

namespace {

constexpr int kUsageError = 2;
constexpr int kHeapBlockBytes = 64 << 20;  ///< blocks up to this size come from the heap (glibc: 128 KiB to 32 MiB)
constexpr int kKeepFreeBytes = 128 << 20;  ///< freed heap kept before trimming

void print_version() {
  std::printf("smi-lua %s (%s), statistical model improvement in Lua\n", SMI_VERSION, LUA_RELEASE);
  std::fflush(stdout);
}

int run(smi::cli::Args& a, int argc, char** argv) {
  if (!a.ignore_env)
    if (const char* d = std::getenv("SMI_STDLIB_DIR"); d && a.cfg.stdlib_dir.empty()) a.cfg.stdlib_dir = d;
  if (a.ignore_env) ::setenv("SMI_PATH", "", 1);
  // Progress output only makes sense on a terminal.
  if (!::isatty(STDOUT_FILENO) || !::isatty(STDERR_FILENO)) a.cfg.quiet = true;

  smi::app::Runtime rt(a.cfg, smi::cli::all_bindings());
  rt.set_arg(argc, argv, a.script_index ? a.script_index : argc);
  if (a.warnings) lua_warning(rt.state(), "@on", 0);
  if (a.version) print_version();

  for (const auto& act : a.actions) {
    const int st = act.kind == smi::cli::Action::exec ? rt.run_string(act.text, "=(command line)")
                                                       : rt.require_global(act.text);
    if (st != 0 || rt.exit_requested()) return st;
  }
  if (a.script_index) {
    std::vector<std::string> args(argv + a.script_index + 1, argv + argc);
    const int st = rt.run_file(a.cfg.script, args);
    if (st != 0 || rt.exit_requested()) return st;
    if (a.cfg.pdf && !a.cfg.dry_run) {  // the study's report.html, printed (commands_report.cpp)
      const std::string html = (rt.policy().out_dir / "report.html").string();
      if (!std::filesystem::exists(html)) {
        std::fprintf(stderr, "smi-lua: --pdf: the script wrote no %s, so there is nothing to print\n", html.c_str());
        return 1;
      }
      if (const int pst = smi::cli::print_report_pdf(html); pst != 0) return pst;
    }
  }
  if (a.interactive) return smi::repl::run(rt);
  if (!a.script_index && a.actions.empty() && !a.version) {
    if (::isatty(STDIN_FILENO)) {
      print_version();
      return smi::repl::run(rt);
    }
    return rt.run_file("-", {});
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  // A study's vectors are large (2000 to a million rows) and short-lived (every operation of a
  // Lua model makes one). Above glibc's default threshold each is an mmap and its pages fault
  // in afresh, and a free at the heap's top is trimmed back to the system: measured on an
  // in-process study, a tenth of the run in page faults. Big blocks now come from the heap and
  // up to kKeepFreeBytes of freed memory is kept for the next (peak memory: +10 % there).
  mallopt(M_MMAP_THRESHOLD, kHeapBlockBytes);
  mallopt(M_TRIM_THRESHOLD, kKeepFreeBytes);
  // Orphans of the solvers we start (a setsid daemon) are reparented to us, not to init, so a
  // stop can find and kill them (eval/process.hpp).
  smi::eval::become_subreaper();
  smi::cli::Args a = smi::cli::parse(argc, argv);
  if (!a.error.empty()) {
    std::fprintf(stderr, "smi-lua: %s\n%s\n", a.error.c_str(), smi::cli::usage_line());
    return kUsageError;
  }
  if (a.version_build) {  // the build line results.json records as provenance.build
    std::printf("%s\n", smi::vm::build_line().c_str());
    return 0;
  }
  if (a.help) {
    std::fputs(smi::cli::help_text(), stdout);
    return 0;
  }
  // libs, new-lib, test, verify (cli/commands.hpp)
  if (a.script_index && smi::cli::is_command(argv[a.script_index])) return smi::cli::run_command(a, argc, argv);
  try {
    return run(a, argc, argv);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "smi-lua: %s\n", e.what());
    return 1;
  }
}
