// SPDX-License-Identifier: MIT
#include "app/runtime.hpp"
#include "app/docs.hpp"

#include <cctype>
#include <cstdio>
#include <cstring>
#include <stdexcept>
#include <unistd.h>

#include "luax/load_guard.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "luax/run_context.hpp"
#include "luax/user_error.hpp"
#include "platform/core/cancel.hpp"
#include "platform/core/printable.hpp"
#include "sandbox/sandbox.hpp"
#include "vm/internal_functions.hpp"
#include "vm/library_lua.hpp"

namespace smi::app {
using namespace vm;  // the VM parts (limits, watchdog, searchers, libraries) the Runtime assembles
namespace fs = std::filesystem;

namespace {

/// Why a function a script tried to call is missing: the sandbox removed it.
const char* removed_hint(const char* msg) {
  static const struct {
    const char* field;
    const char* hint;
  } kRemoved[] = {
      {"(field 'popen')", "io.popen is removed by the sandbox: studies run programs through smi.model with --allow-exec"},
      {"(field 'execute')", "os.execute is removed by the sandbox: studies run programs through smi.model with --allow-exec"},
      {"(field 'dump')", "string.dump is removed by the sandbox: binary chunks are not allowed"},
      {"(field 'loadlib')", "package.loadlib is removed by the sandbox: C modules are not allowed"},
      {"(field 'tmpname')", "os.tmpname is removed by the sandbox: write under smi.out(...)"},
      {"(field 'tmpfile')", "io.tmpfile is removed by the sandbox: write under smi.out(...)"},
      {"(field 'getinfo')", "the debug library is removed by the sandbox (debug.traceback remains)"},
      {"(field 'sethook')", "the debug library is removed by the sandbox (debug.traceback remains)"},
  };
  if (!std::strstr(msg, "attempt to call a nil value")) return nullptr;
  for (const auto& r : kRemoved)
    if (std::strstr(msg, r.field)) return r.hint;
  return nullptr;
}

/// Message handler of every chunk (upvalue: the Runtime). An os.exit request passes through
/// untouched. A failure (an error in the user's data, options or declaration: luax/user_error)
/// passes through too and prints as one line; --traceback turns it into its message plus the
/// traceback. An error in code gets the traceback (in the REPL, one line unless --traceback); a
/// non-string error is described; a call of a removed function says why.
int msghandler(lua_State* L) {
  if (lua_touserdata(L, 1) == lua::exit_sentinel()) return 1;
  const auto* rt = static_cast<const Runtime*>(lua_touserdata(L, lua_upvalueindex(1)));
  const bool always = rt->config().traceback;
  if (lua::is_failure(L, 1)) {
    if (!always) return 1;
    const std::string msg = lua::failure_message(L, 1);
    const std::string tb = lua::failure_traceback(L, 1);
    if (!tb.empty()) {
      lua_pushfstring(L, "%s\n%s", msg.c_str(), tb.c_str());
      return 1;
    }
    luaL_traceback(L, L, msg.c_str(), 1);
    return 1;
  }
  if (lua::push_stdlib_failure(L, 1, 1)) {  // the stdlib's error(message, 0): a failure
    if (!always) return 1;
    luaL_traceback(L, L, lua_tostring(L, 1), 1);
    return 1;
  }
  const char* msg = lua_tostring(L, 1);
  if (!msg) {
    if (luaL_callmeta(L, 1, "__tostring") && lua_type(L, -1) == LUA_TSTRING) return 1;
    msg = lua_pushfstring(L, "(error object is a %s value)", luaL_typename(L, 1));
  } else if (const char* hint = removed_hint(msg)) {
    msg = lua_pushfstring(L, "%s\n(%s)", msg, hint);
  }
  if (rt->one_line_errors() && !always) {
    lua_pushstring(L, msg);
    return 1;
  }
  luaL_traceback(L, L, msg, 1);
  return 1;
}

/// warn(): "@on"/"@off" switch warnings, as in lua.c; off by default. ud = bool* state.
void warnf(void* ud, const char* msg, int tocont) {
  static bool continuing = false;
  bool& on = *static_cast<bool*>(ud);
  if (!continuing && !tocont && msg[0] == '@') {
    if (std::strcmp(msg, "@on") == 0) on = true;
    if (std::strcmp(msg, "@off") == 0) on = false;
    return;
  }
  if (on) {
    if (!continuing) std::fputs("smi-lua: warning: ", stderr);
    std::fputs(msg, stderr);
    if (!tocont) std::fputs("\n", stderr);
  }
  continuing = tocont != 0;
}
bool g_warnings_on = false;

int panic(lua_State* L) {
  const char* msg = lua_tostring(L, -1);
  std::fprintf(stderr, "smi-lua: unprotected error: %s\n", msg ? msg : "(not a string)");
  return 0;  // lua aborts
}

/// Runs in protected mode (lua.c's pmain idea): libraries, smi, sandbox, searchers.
int init_state(lua_State* L) {
  auto* rt = static_cast<Runtime*>(lua_touserdata(L, 1));
  const Config& cfg = rt->config();
  const lua::Policy& pol = rt->policy();
  const RunContext& ctx = rt->context();
  luaL_openlibs(L);
  luaL_requiref(L, "smi", rt->bindings().open_smi, 1);  // stack: [rt, smi]
  lua_pushinteger(L, static_cast<lua_Integer>(ctx.seed));
  lua_setfield(L, -2, "seed");
  lua_pushboolean(L, ctx.quiet);
  lua_setfield(L, -2, "quiet");
  lua_pushstring(L, pol.out_dir.c_str());
  lua_setfield(L, -2, "out_dir");
  lua_pushstring(L, pol.read_roots.empty() ? "." : pol.read_roots.front().c_str());
  lua_setfield(L, -2, "script_dir");
  // marks the stdlib's own error(message, 0) as a failure: for smi.study's step handler only
  vm::set_internal_function(L, "as_failure", lua::l_as_failure);
  lua_pushboolean(L, cfg.pdf);  // --pdf: a study prints its report to PDF too
  lua_setfield(L, -2, "pdf");
  lua_pushboolean(L, ctx.dry_run);  // a study neither saves results nor writes a report then
  lua_setfield(L, -2, "dry_run");
  lua_pushstring(L, host_version());
  lua_setfield(L, -2, "version");
  install_docs(L, rt->bindings().docs);  // smi._docs: the reference texts (help, smi-lua doc)
  lua_pop(L, 1);
  if (cfg.sandbox) sandbox::install(L);
  return 0;
}

std::vector<std::string> split_env_path(const char* env) {
  std::vector<std::string> out;
  if (!env) return out;
  std::string s = env;
  std::size_t start = 0;
  while (start <= s.size()) {
    const std::size_t end = s.find(':', start);
    const std::string part = s.substr(start, end == std::string::npos ? std::string::npos : end - start);
    if (!part.empty()) out.push_back(part);
    if (end == std::string::npos) break;
    start = end + 1;
  }
  return out;
}

}  // namespace

std::string default_out_dir(const std::string& script) {
  std::string name;
  if (script.empty())
    name = "interactive";
  else if (script == "-")
    name = "stdin";
  else
    name = fs::path(script).stem().string();
  // The stem is one folder name below smi-out whatever the script is called: "...lua" has the
  // stem "..", "..lua" the stem ".", ".lua" the stem ".lua". A leading dot becomes '_' (so no
  // name climbs out of smi-out or hides), as does anything but letters, digits, '_', '-', '.'.
  for (char& c : name)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) c = '_';
  for (char& c : name) {
    if (c != '.') break;
    c = '_';
  }
  if (name.empty()) name = "script";
  return (fs::path("smi-out") / name).string();
}

void Runtime::build_policy() {
  // The script's folder (the working directory for -e, stdin and the REPL) comes first: it is
  // smi.script_dir and the first place require looks.
  fs::path script_dir = ".";
  if (!cfg_.script.empty() && cfg_.script != "-") {
    script_dir = fs::path(cfg_.script).parent_path();
    if (script_dir.empty()) script_dir = ".";
  }
  std::vector<std::string> libs = cfg_.lib_dirs;
  for (const auto& d : split_env_path(std::getenv("SMI_PATH"))) libs.push_back(d);

  policy_.read_roots.push_back(lua::resolve_path(script_dir.string()));
  modules_.roots.push_back(script_dir);
  for (const auto& d : libs) {
    policy_.read_roots.push_back(lua::resolve_path(d));
    modules_.roots.emplace_back(d);
  }
  // The stdlib folder is a root of the stdlib searcher only (searchers.cpp): scripts may not
  // read it with io.open & co., so SMI_STDLIB_DIR does not widen what a script reads.
  if (!cfg_.stdlib_dir.empty()) modules_.stdlib_dir = cfg_.stdlib_dir;
  for (const auto& d : cfg_.allow_read) policy_.read_roots.push_back(lua::resolve_path(d));

  policy_.out_dir = cfg_.out_dir.empty() ? default_out_dir(cfg_.script) : cfg_.out_dir;
  policy_.out_root = lua::output_root(policy_.out_dir.string());
  policy_.write_roots.push_back(policy_.out_root);
  for (const auto& d : cfg_.allow_write) policy_.write_roots.push_back(lua::resolve_path(d));
  // --store is read-only: the evaluator opens it read-only and immutable, and a script may read
  // it but not write it.
  if (!cfg_.store_path.empty()) policy_.read_roots.push_back(lua::resolve_path(cfg_.store_path));
  policy_.exec_allowed = cfg_.allow_exec;

  policy_.unrestricted = !cfg_.sandbox;
  policy_.allow_env = cfg_.allow_env;

  // Provenance: the options of smi-lua that change results, and where reads are
  // outputs of the run rather than inputs (the output folder: results.json, the runs' folders).
  policy_.record = &record_;
  record_.exclude_roots.push_back(policy_.out_root.string());
  std::error_code ec;
  record_.cwd = fs::current_path(ec).string();
  auto opt = [&](const char* k, std::string v) { record_.options.emplace_back(k, std::move(v)); };
  opt("seed", std::to_string(cfg_.seed));
  opt("executor", cfg_.executor.empty() ? "local" : cfg_.executor);
  for (const auto& s : cfg_.slurm_opts) opt("slurm-opt", s);
  if (cfg_.timeout_s > 0) opt("timeout", std::to_string(cfg_.timeout_s));
  if (cfg_.max_memory_mb > 0) opt("max-memory", std::to_string(cfg_.max_memory_mb));
  if (!cfg_.store_path.empty()) opt("store", lua::resolve_path(cfg_.store_path).string());
  if (cfg_.dry_run) opt("dry-run", "true");
  if (!cfg_.stdlib_dir.empty()) opt("stdlib-dir", lua::resolve_path(cfg_.stdlib_dir).string());
}

void Runtime::build_context() {
  context_.seed = cfg_.seed;
  context_.quiet = cfg_.quiet;
  context_.dry_run = cfg_.dry_run;
  context_.timeout_s = cfg_.timeout_s;
  context_.memory_bytes = cfg_.max_memory_mb << 20;
  context_.store_path = cfg_.store_path;
  context_.script_path = cfg_.script == "-" ? "" : cfg_.script;
  context_.executor = cfg_.executor;
  context_.slurm_opts = cfg_.slurm_opts;
  context_.detach = cfg_.detach;
  context_.progress.live = !cfg_.quiet && ::isatty(STDERR_FILENO);
  context_.warnings = WarningSink(!cfg_.quiet);
  context_.cancel = &cancel::process_token();  // the one the signal handler reaches (vm/limits)
}

Runtime::Runtime(Config cfg, Bindings bindings) : cfg_(std::move(cfg)), bindings_(bindings), L_(nullptr) {
  if (!bindings_.open_smi || !bindings_.docs) throw Error("Runtime: no bindings handed in (cli/bindings_root.cpp)");
  build_policy();
  build_context();
  // Two versions of a library or an unmet requirement stop the run before any code runs.
  // The project folder's smi-libs/ and smi-lock.json (libs add/sync) count too; a tree the
  // lockfile places outside the project is no read root (only --lib or SMI_PATH make it one).
  const ProjectLibraries project = project_libraries(fs::current_path());
  if (!project.tree.empty() && !project.tree_outside)
    policy_.read_roots.push_back(lua::resolve_path(project.tree.string()));
  libs_ = LibrarySet::discover(library_roots(cfg_.lib_dirs, std::getenv("SMI_PATH")), &project);
  libs_.check();
  limits_.token = context_.cancel;
  limits_.timeout_s = context_.timeout_s;
  limits_.mem_limit = context_.memory_bytes;
  memory_.limit = limits_.mem_limit;
  memory_.lua_used = &limits_.mem_used;
  limits_.external = &memory_.external;
  L_ = lua_newstate(limited_alloc, &limits_);
  if (!L_) throw std::runtime_error("cannot create a Lua state (out of memory)");
  lua::set_memory_budget(L_, &memory_);
  lua_atpanic(L_, panic);
  lua_setwarnf(L_, warnf, &g_warnings_on);
  install_limits(L_, &limits_);
  lua::set_policy(L_, &policy_);
  lua::set_run_context(L_, &context_);
  lua_pushcfunction(L_, init_state);
  lua_pushlightuserdata(L_, this);
  if (lua_pcall(L_, 1, 0, 0) != LUA_OK) {
    std::string msg = lua_tostring(L_, -1) ? lua_tostring(L_, -1) : "unknown error";
    lua_close(L_);
    throw std::runtime_error("cannot set up the Lua state: " + msg);
  }
  install_searchers(L_, &modules_);
  if (!modules_.stdlib_dir.empty()) lua::set_stdlib_source(L_, modules_.stdlib_dir.string());
  install_libraries(L_, &libs_);
  if (cfg_.sandbox) {
    // Last: the globals become a table built from the allow-list (sandbox/sandbox_environment.cpp).
    lua_pushcfunction(L_, [](lua_State* L) -> int {
      sandbox::restrict_globals(L, *static_cast<const std::vector<std::string>*>(lua_touserdata(L, 1)));
      return 0;
    });
    lua_pushlightuserdata(L_, &cfg_.allow_env);
    if (lua_pcall(L_, 1, 0, 0) != LUA_OK) {
      std::string msg = lua_tostring(L_, -1) ? lua_tostring(L_, -1) : "unknown error";
      lua_close(L_);
      throw std::runtime_error("cannot set up the Lua state: " + msg);
    }
  }
}

Runtime::~Runtime() {
  // Finalizers run here, with Lua's hooks off: a __gc that never returns is ended by the
  // watchdog once a fresh --timeout has passed (or after Ctrl-C).
  context_.cancel->reset();
  if (limits_.timeout_s > 0) context_.cancel->arm_deadline(limits_.timeout_s);
  watchdog_.arm();
  lua_close(L_);
  watchdog_.disarm();
  context_.cancel->reset();
}

void Runtime::set_arg(int argc, char** argv, int script_index) {
  if (script_index >= argc) script_index = 0;  // no script: the interpreter is arg[0]
  lua_createtable(L_, argc - script_index - 1 > 0 ? argc - script_index - 1 : 0, script_index + 1);
  for (int i = 0; i < argc; ++i) {
    lua_pushstring(L_, argv[i]);
    lua_rawseti(L_, -2, i - script_index);
  }
  lua_setglobal(L_, "arg");
  record_.command_line.assign(argv, argv + argc);
  record_.script_args.clear();
  if (script_index > 0)
    for (int i = script_index + 1; i < argc; ++i) record_.script_args.emplace_back(argv[i]);
}

int Runtime::docall(int nargs, int nresults) {
  const int base = lua_gettop(L_) - nargs;  // the function
  lua_pushlightuserdata(L_, this);
  lua_pushcclosure(L_, msghandler, 1);
  lua_insert(L_, base);
  begin_chunk(L_);
  catch_sigint(L_);
  watchdog_.arm();
  const int status = lua_pcall(L_, nargs, nresults, base);
  watchdog_.disarm();
  release_sigint();
  end_chunk(L_);
  lua_remove(L_, base);
  return status;
}

int Runtime::report(int status) {
  if (status == LUA_OK) return 0;
  const cancel::Token& token = *context_.cancel;
  if (exit_requested()) {
    lua_pop(L_, 1);
    return token.detail();
  }
  char buf[256];
  const bool failure = lua::is_failure(L_, -1);
  if (failure) {  // one line (and the traceback of the user's code it carries)
    const std::string m = lua::failure_message(L_, -1), tb = lua::failure_traceback(L_, -1);
    std::fprintf(stderr, "smi-lua: %s\n", printable(m).c_str());
    if (!tb.empty() && !one_line_) std::fprintf(stderr, "%s\n", printable(tb).c_str());
  }
  const char* msg = failure ? nullptr : lua_tostring(L_, -1);
  if (!failure && status < 0) {
    // Lua's C++ build turns a foreign C++ exception that left a bound function into status -1
    // with whatever value was on top of the stack as the "message" (it printed a bare number).
    std::fprintf(stderr,
                 "smi-lua: a smi function failed with a C++ exception that carried no message (most often an "
                 "allocation that could not be made: a size too large for this machine)\n");
    std::fflush(stderr);
    lua_pop(L_, 1);
    return 1;
  }
  if (failure) {
    // printed above
  } else if (token.raised() == cancel::Reason::memory && !(msg && std::strstr(msg, "memory limit exceeded"))) {
    // "not enough memory" comes from the allocator refusing: say which limit and how to raise it
    std::fprintf(stderr, "smi-lua: %s\n", abort_message(token, buf, sizeof buf));
    if (msg && std::strcmp(msg, "not enough memory") != 0) std::fprintf(stderr, "%s\n", printable(msg).c_str());
  } else {
    // Messages carry data (file contents, a solver's log, names from a results file): escaped.
    std::fprintf(stderr, "smi-lua: %s\n", msg ? printable(msg).c_str() : "(error object is not a string)");
  }
  lua_pop(L_, 1);
  if (token.raised() == cancel::Reason::signal && token.detail() > 0) {
    const int sig = token.detail();
    // Stopped by a signal: say what survives (only what exists) and how to go on; exit 128 +
    // signal, as a shell does.
    std::error_code ec;
    const fs::path store = policy_.out_dir / "evaluations.sqlite";  // the local store of the runs
    const fs::path results = policy_.out_dir / "results.json";
    const bool has_store = fs::exists(store, ec), has_results = fs::exists(results, ec);
    std::string kept;
    if (has_store) kept += "every finished solver run (in " + store.string() + ")";
    if (has_results) kept += std::string(has_store ? " and " : "") + "the study steps that finished (in " + results.string() + ")";
    if (kept.empty()) {
      std::fprintf(stderr, "smi-lua: stopped by %s.\n", signal_name(sig));
    } else {
      std::fprintf(stderr, "smi-lua: stopped by %s. Kept: %s. To resume, %s again: stored runs are reused, not rerun.\n",
                   signal_name(sig), kept.c_str(), one_line_ ? "enter the same line" : "run the same command");
    }
    std::fflush(stderr);
    return 128 + sig;
  }
  std::fflush(stderr);
  return 1;
}

int Runtime::run_file(const std::string& path, const std::vector<std::string>& args) {
  const bool stdin_script = path == "-";
  if (!stdin_script) {
    try {  // provenance: the script itself (a file that cannot be read fails in the load below)
      record_.path("script", lua::resolve_path(path).string());
    } catch (const std::exception&) {
    }
  }
  // Read whole, then loaded through the guard against Lua 5.4.4's code-generation bug
  // (luax/load_guard.hpp); a file that cannot be read gets luaL_loadfilex's own message.
  std::string text;
  bool read_ok = false;
  if (std::FILE* f = stdin_script ? stdin : std::fopen(path.c_str(), "rb")) {
    char buf[65536];
    for (std::size_t n; (n = std::fread(buf, 1, sizeof buf, f)) > 0;) text.append(buf, n);
    read_ok = !std::ferror(f);
    if (!stdin_script) std::fclose(f);
  }
  int status = read_ok ? lua::load_text(L_, text, stdin_script ? "=stdin" : "@" + path)
                       : luaL_loadfilex(L_, stdin_script ? nullptr : path.c_str(), "t");
  if (status == LUA_OK) {
    for (const auto& a : args) lua_pushstring(L_, a.c_str());
    status = docall(static_cast<int>(args.size()), 0);
  }
  return report(status);
}

int Runtime::run_string(const std::string& code, const std::string& chunkname) {
  int status = lua::load_buffer(L_, code.data(), code.size(), chunkname.c_str());
  if (status == LUA_OK) status = docall(0, 0);
  return report(status);
}

int Runtime::require_global(const std::string& spec) {
  const std::size_t eq = spec.find('=');
  const std::string global = eq == std::string::npos ? spec : spec.substr(0, eq);
  const std::string mod = eq == std::string::npos ? spec : spec.substr(eq + 1);
  lua_getglobal(L_, "require");
  lua_pushstring(L_, mod.c_str());
  const int status = docall(1, 1);
  if (status == LUA_OK) lua_setglobal(L_, global.c_str());
  return report(status);
}

}  // namespace smi::app
