// SPDX-License-Identifier: MIT
#include "cli/args.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

#include "platform/core/closest.hpp"
#include "platform/core/defaults.hpp"

namespace smi::cli {
namespace {

/// Options that take a value: "--name VALUE" or "--name=VALUE".
const char* const kValued[] = {"--allow-read", "--allow-write", "--allow-exec", "--allow-env", "--lib",
                               "--out",        "--seed",        "--max-memory", "--timeout",   "--store",
                               "--stdlib-dir", "--executor",    "--slurm-opt"};

/// Options that take no value, for the "did you mean" of an unrecognized one.
const char* const kFlags[] = {"--version", "--help",   "--quiet",  "--dry-run",
                              "--detach",  "--traceback", "--pdf"};

/// "unrecognized option '--alow-exec' (did you mean --allow-exec?)".
std::string unrecognized(const std::string& s) {
  const std::string name = s.substr(0, s.find('='));
  std::vector<std::string> names;
  for (const char* k : kValued) names.emplace_back(k);
  for (const char* k : kFlags) names.emplace_back(k);
  const std::vector<std::string> near = closest(name, names, 1);
  return "unrecognized option '" + s + "'" + (near.empty() ? "" : " (did you mean " + near.front() + "?)");
}

bool parse_u64(const std::string& s, std::uint64_t& out) {
  if (s.empty() || s[0] == '-') return false;
  char* end = nullptr;
  errno = 0;
  const unsigned long long v = std::strtoull(s.c_str(), &end, 10);
  if (errno || *end) return false;
  out = v;
  return true;
}

bool parse_positive(const std::string& s, double& out) {
  char* end = nullptr;
  const double v = std::strtod(s.c_str(), &end);
  if (s.empty() || *end || !std::isfinite(v) || v <= 0) return false;
  out = v;
  return true;
}

/// Applies one valued option; returns a usage error or "".
std::string apply(Args& a, const std::string& name, const std::string& v) {
  app::Config& c = a.cfg;
  if (name == "--allow-read") c.allow_read.push_back(v);
  else if (name == "--allow-write") c.allow_write.push_back(v);
  else if (name == "--allow-exec") c.allow_exec.push_back(v);
  else if (name == "--allow-env") c.allow_env.push_back(v);
  else if (name == "--lib") c.lib_dirs.push_back(v);
  else if (name == "--out") c.out_dir = v;
  else if (name == "--store") c.store_path = v;
  else if (name == "--stdlib-dir") c.stdlib_dir = v;
  else if (name == "--executor") {
    if (v != "local" && v != "slurm") return "--executor needs 'local' or 'slurm', got '" + v + "'";
    c.executor = v;
  } else if (name == "--slurm-opt") {
    if (v.find('=') == std::string::npos || v[0] == '=')
      return "--slurm-opt needs KEY=VALUE (partition, account, qos, time, mem, cpus, sbatch, throttle, ...), got '" + v + "'";
    c.slurm_opts.push_back(v);
  }
  else if (name == "--seed") {
    if (!parse_u64(v, c.seed)) return "--seed needs a non-negative integer, got '" + v + "'";
  } else if (name == "--timeout") {
    if (!parse_positive(v, c.timeout_s)) return "--timeout needs a positive number of seconds, got '" + v + "'";
  } else if (name == "--max-memory") {
    std::uint64_t mb = 0;
    if (!parse_u64(v, mb) || mb == 0 || mb > (1u << 22))
      return "--max-memory needs a whole number of megabytes (1 to 4194304), got '" + v + "'";
    c.max_memory_mb = mb;
  }
  if (v.empty()) return name + " needs a non-empty value";
  return "";
}

}  // namespace

Args parse(int argc, char** argv) {
  Args a;
  int i = 1;
  for (; i < argc; ++i) {
    const std::string s = argv[i];
    if (s.empty() || s[0] != '-') break;  // the script
    if (s == "-") break;                  // the script is stdin
    if (s == "--") {
      ++i;
      break;
    }
    if (s == "-i") {
      a.interactive = true;
    } else if (s == "-v") {
      a.version = true;
    } else if (s == "-W") {
      a.warnings = true;
    } else if (s == "-E") {
      a.ignore_env = true;
    } else if (s == "--version") {
      a.version_build = true;
    } else if (s == "-h" || s == "--help") {
      a.help = true;
    } else if (s == "--quiet" || s == "-q") {
      a.quiet_given = true;
      a.cfg.quiet = true;
    } else if (s == "--dry-run") {
      a.cfg.dry_run = true;
    } else if (s == "--detach") {
      a.cfg.detach = true;
    } else if (s == "--traceback") {
      a.cfg.traceback = true;
    } else if (s == "--pdf") {
      a.cfg.pdf = true;
    } else if (s.rfind("-e", 0) == 0 || s.rfind("-l", 0) == 0) {
      // -e chunk, -echunk, -l mod, -lmod (as lua.c)
      std::string v = s.substr(2);
      if (v.empty()) {
        if (i + 1 >= argc) {
          a.error = "'" + s + "' needs an argument";
          return a;
        }
        v = argv[++i];
      }
      a.actions.push_back({s[1] == 'e' ? Action::exec : Action::require, v});
    } else if (s.rfind("--", 0) == 0) {
      const std::size_t eq = s.find('=');
      const std::string name = s.substr(0, eq);
      bool known = false;
      for (const char* k : kValued) known = known || name == k;
      if (!known) {
        a.error = unrecognized(s);
        return a;
      }
      std::string v;
      if (eq != std::string::npos) {
        v = s.substr(eq + 1);
      } else {
        if (i + 1 >= argc) {
          a.error = "'" + name + "' needs an argument";
          return a;
        }
        v = argv[++i];
      }
      a.error = apply(a, name, v);
      if (!a.error.empty()) return a;
    } else {
      a.error = unrecognized(s);
      return a;
    }
  }
  if (i < argc) {
    a.script_index = i;
    a.cfg.script = argv[i];
  }
  return a;
}

const char* usage_line() { return "usage: smi-lua [options] [script [args]]   (smi-lua --help lists the options)"; }

/// The help text with ${seed} replaced by the default seed.
static std::string fill_defaults(std::string s) {
  const std::string key = "${seed}";
  for (std::size_t at = s.find(key); at != std::string::npos; at = s.find(key, at))
    s.replace(at, key.size(), std::to_string(kDefaultSeed));
  return s;
}

// long: one raw string literal, the help exactly as it prints (the man page is made from it)
const char* help_text() {
  // The defaults named in the text come from where they are defined (core/defaults.hpp).
  static const std::string text = fill_defaults(R"(usage: smi-lua [options] [script [args]]

Runs a study script (or stdin with '-') in a sandbox; with no script, starts the REPL on a
terminal and runs stdin otherwise. The script gets its arguments as arg[1..n] and as '...'.
The options below go before the script: everything after it is the script's own (a study's
--help lists them), so `smi-lua study.lua --out DIR` is refused by smi.options with
"smi-lua's own option --out goes before the script: smi-lua --out DIR study.lua ...".
A study (smi.study, smi.improve) run again reuses the steps whose inputs are unchanged (data,
options, code, earlier results, this binary); its own options --only NAME and --from NAME run
some steps, --force runs them all (smi-lua study.lua --force).

Lua options (as the lua program):
  -e chunk            run the string 'chunk' (in order with -l, before the script)
  -l mod              require 'mod' into the global 'mod'; -l g=mod names the global g
  -i                  enter the REPL after running the script
  -v                  print version information
  --version           print the version and the build (compiler, Lua, Eigen, NLopt, SQLite,
                      RE2, nettle, fmt versions) and exit
  -W                  turn warnings on
  -E                  ignore the environment variables SMI_PATH and SMI_STDLIB_DIR
  --                  stop handling options (the next argument is the script)
  -                   run stdin as the script and stop handling options

Sandbox (each option may be repeated):
  --allow-read PATH   let the script read under PATH (it always may read its own folder and
                      the library folders)
  --allow-write PATH  let the script write under PATH (it always may write under --out)
  --allow-exec PROG   let the script run the program PROG (a name found on PATH, or a path)
  --allow-env NAME    let os.getenv read the environment variable NAME, pass your NAME to
                      solvers, and let a model's env = {NAME = ...} set it (no other name);
                      allow only names a solver reads as data (OMP_NUM_THREADS), never
                      ones its interpreter reads at start-up (docs/sandbox.md)

Modules:
  --lib DIR           also search DIR for require'd Lua modules (SMI_PATH: a ':' list, too);
                      a folder holding smi-lib.lua is a library, and so is each such subfolder:
                      require "name.module" loads <library folder>/module.lua
  --stdlib-dir DIR    load the smi stdlib from DIR instead of the copy built in (SMI_STDLIB_DIR)

Run:
  --out DIR           output folder, created when first written (default smi-out/<script>/)
  --seed N            seed of smi's and math.random's generators (default ${seed}); smi.seed
  --quiet, -q         no progress output (automatic when stdout or stderr is not a terminal)
  --max-memory MB     stop the script when the Lua heap plus the data of smi.vec, smi.mat and
                      Kriging models would exceed MB megabytes
  --timeout SECONDS   stop the script (and each -e chunk, each REPL entry) after SECONDS of
                      running; pcall cannot catch it
  --store PATH        evaluation store (database of solver runs) to use
  --dry-run           count the solver runs a study would launch; launch none (with
                      --executor slurm: print the job script, the sbatch lines, the cost plan)
  --pdf               a study also prints its report.html to report.pdf (headless Chromium)
  --traceback         print the Lua traceback under an error in the data, options or
                      declaration too (errors in the script's own code always have one)

Cluster (solver runs of smi.model.command / smi.model.batch):
  --executor KIND     where solver runs execute: local (default) or slurm (job arrays through
                      sbatch, squeue, sacct, scancel); a model's executor = {...} overrides it
  --slurm-opt K=V     a Slurm option, repeated: partition, account, qos, time (minutes or
                      H:M:S; default: the model's timeout plus a margin), mem, cpus, sbatch
                      (extra sbatch arguments), throttle (array %N, default 50), max_array,
                      poll / poll_max (squeue interval, default 5 and 60 s), cmd_timeout,
                      down_after (s of scheduler errors before stopping, default 300),
                      exit_wait, max_requeues, bin_dir
  --detach            an interrupted study (Ctrl-C, SIGTERM, --timeout) leaves its Slurm jobs
                      running; running it again reattaches to them (default: one scancel)
  -h, --help          print this help and exit

Commands (sharing libraries; options such as --lib go before or after them):
  doc [NAME]          the reference of a function or module (smi-lua doc smi.kde); doc --html
                      DIR writes the reference and the guides as HTML pages
  report --pdf HTML   print a report.html to PDF beside it (headless Chromium)
  libs                the libraries a study would see: name, version, git commit, path
  libs add SRC[@REF]  install a library (git URL, folder or .tar.gz; REF a tag, branch or
                      commit) and what it requires into ./smi-libs (--into DIR); records
                      name, version, source, commit and every file's SHA-256 in smi-lock.json
                      and the range asked for (^VERSION) in smi-project.json
  libs add NAME[@RANGE]  the same by name: from the source recorded for NAME, else from the
                      registries of smi-project.json (RANGE: 1.2.0, ^1.2, '>= 1.2, < 2')
  libs update [NAME]  move libraries to the highest version their ranges allow; rewrites
                      smi-lock.json
  libs sync [--check] install exactly what smi-lock.json says, checking every file, and
                      restore changed libraries (--check: only check)
  libs tree           what requires what, with versions
  libs outdated       newer version tags at each locked library's source
  libs remove NAME[@VERSION]   uninstall (and drop from smi-lock.json)
  libs pack DIR       DIR's library as NAME-VERSION.tar.gz with a checksum file
  libs registry [NAME URL]     record a team registry (a git repository) in smi-project.json
  libs publish REGISTRY SRC@TAG  add a released version to a registry's index (never replaces)
  libs search WORD    libraries of the project's registries whose name or description has WORD
  new-lib NAME [DIR]  make a library folder with a manifest, a module and a test
  test DIR            run DIR/tests/test_*.lua; prints "N passed, N failed" (test cases)
  verify RESULTS      re-hash everything RESULTS (a results.json) records: script, modules, data,
                      solvers, libraries, build; lists each difference; exit 0 all match, 1 a
                      difference, 2 not a results file or not done within --timeout (default
                      600 s); only regular files are read (--json: the same as JSON)
  (a script file named like a command runs as ./NAME)

Exit status: 0 success, 1 error (an error in the data, options or declaration: one line
naming the culprit; an error in the script's code: its message with file:line and a Lua
traceback), 2 usage error; os.exit(n) exits with n.
)");
  return text.c_str();
}

}  // namespace smi::cli
