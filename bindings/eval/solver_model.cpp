// SPDX-License-Identifier: MIT
// smi.model.command{...} and smi.model.batch{...}: models backed by an external solver run
// through the evaluator (host/platform/eval/evaluator.hpp). This file turns the option table
// into a CommandConfig (through the sandbox), calls the Lua output parser for each finished
// run, shows progress, and reports failures.
#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include "bindings/eval/model.hpp"
#include "bindings/eval/solver_options.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "luax/run_context.hpp"
#include "platform/core/sha256.hpp"
#include "platform/eval/folder_lock.hpp"
#include "platform/eval/process.hpp"
#include "platform/eval/progress_line.hpp"

namespace smi::bind::eval {
namespace {

namespace se = smi::eval;
namespace fs = std::filesystem;

const char kPlannedKey = 0;  // registry key of the dry-run totals table

bool valid_model_name(const std::string& s) {
  if (s.empty() || s == "." || s == "..") return false;
  for (char c : s)
    if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.')) return false;
  return true;
}

/// Runs under lua_pcall (through lua::call): [fn, dir, outputs, n|nil] -> [smi.vec]. Calls the
/// parser fn(dir, helpers [, n]) and checks what it returns: one number per output (command)
/// or one vector of n numbers per output (batch), flattened column by column.
int parse_trampoline(lua_State* L) {
  const bool batch = !lua_isnil(L, 4);
  const lua_Integer n = batch ? lua_tointeger(L, 4) : 1;
  lua_pushvalue(L, 1);
  lua_pushvalue(L, 2);
  push_parse_helpers(L, lua_tostring(L, 2));
  if (batch) lua_pushinteger(L, n);
  lua_call(L, batch ? 3 : 2, 1);
  if (!lua_istable(L, -1))
    return luaL_error(L, "the parser must return a table {output = value, ...}, got %s", luaL_typename(L, -1));
  const int res = lua_gettop(L);
  const lua_Integer m = luaL_len(L, 3);
  Eigen::VectorXd flat(n * m);
  for (lua_Integer j = 1; j <= m; ++j) {
    lua_rawgeti(L, 3, j);
    const char* name = lua_tostring(L, -1);
    const int t = lua_getfield(L, res, name);
    if (t == LUA_TNIL) return luaL_error(L, "the parser returned no value for output '%s'", name);
    if (!batch) {
      if (t != LUA_TNUMBER)
        return luaL_error(L, "the parser returned a %s for output '%s', expected a number", luaL_typename(L, -1), name);
      flat[j - 1] = lua_tonumber(L, -1);
    } else {
      const std::string what = std::string("output '") + name + "'";
      const Eigen::VectorXd v = lua::to_vector(L, -1, what.c_str());
      if (v.size() != n)
        return luaL_error(L, "the parser returned %d values for output '%s', the batch has %d points",
                          static_cast<int>(v.size()), name, static_cast<int>(n));
      flat.segment((j - 1) * n, n) = v;
    }
    lua_pop(L, 2);
  }
  lua::push_vec(L, std::move(flat));
  return 1;
}

// What solver_config reads from Lua by hand (the schema's SolverArgs holds the rest) before
// anything is checked against the sandbox policy.
struct SolverOptions {
  std::vector<std::string> argv, files, version_args;
  std::string store, template_file, template_text;
  std::vector<std::pair<std::string, std::string>> exec_opts;
};

// command = {program, arg, ...} (no shell) and parse = function: the argv.
std::vector<std::string> read_command(lua_State* L, lua::Options& o, bool batch, const char* fname) {
  if (o.push("command") != LUA_TTABLE)
    luaL_error(L, "%s: option 'command' must be the argv table {program, arg, ...} (no shell), got %s", fname,
               luaL_typename(L, -1));
  std::vector<std::string> argv = lua::to_strings(L, -1, "command");
  lua_pop(L, 1);
  if (argv.empty()) luaL_error(L, "%s: option 'command' is empty; its first element is the program", fname);
  if (o.push("parse") != LUA_TFUNCTION)
    luaL_error(L, "%s: option 'parse' must be a function(dir, h%s) returning {output = value, ...}, got %s", fname,
               batch ? ", n" : "", luaL_typename(L, -1));
  lua_pop(L, 1);
  return argv;
}

// The keys of the table at the top, which must all be strings (else the error "fname: what"),
// sorted: the entries are checked in name order, so that of several mistakes the one named is
// the same every run (a table's traversal order changes from process to process).
std::vector<std::string> sorted_names(lua_State* L, const char* fname, const char* what) {
  std::vector<std::string> keys;
  lua_pushnil(L);
  while (lua_next(L, -2)) {
    lua_pop(L, 1);
    if (lua_type(L, -1) != LUA_TSTRING) luaL_error(L, "%s: %s", fname, what);
    keys.emplace_back(lua_tostring(L, -1));
  }
  std::sort(keys.begin(), keys.end());
  return keys;
}

/// Pushes t[k] (raw) for the table at the top.
void push_entry(lua_State* L, const std::string& k) {
  lua_pushlstring(L, k.data(), k.size());
  lua_rawget(L, -2);
}

// executor = {kind = "local", throttle = 4, ...}: may only narrow --executor/--slurm-opt (apply_executor).
std::vector<std::pair<std::string, std::string>> read_executor_options(lua_State* L, lua::Options& o, const char* fname) {
  std::vector<std::pair<std::string, std::string>> exec_opts;
  if (const int t = o.push("executor"); t != LUA_TNIL) {
    if (t != LUA_TTABLE) luaL_error(L, "%s: option 'executor' must be a table {kind = \"slurm\", partition = ..., ...}, got %s", fname, luaL_typename(L, -1));
    for (const std::string& k : sorted_names(L, fname, "executor option keys must be names")) {
      push_entry(L, k);
      // Which programs run as the scheduler's tools is the user's call, not the study's.
      if (k == "bin_dir") luaL_error(L, "%s: executor option 'bin_dir' may only be given on the command line (--slurm-opt bin_dir=...)", fname);
      if (lua_type(L, -1) == LUA_TTABLE && k == "sbatch") {
        for (const auto& a : lua::to_strings(L, -1, "executor.sbatch")) exec_opts.emplace_back(k, a);
      } else if (lua_type(L, -1) == LUA_TSTRING || lua_type(L, -1) == LUA_TNUMBER) {
        exec_opts.emplace_back(k, lua_tostring(L, -1));
      } else if (lua_type(L, -1) == LUA_TBOOLEAN && k == "detach") {
        exec_opts.emplace_back(k, lua_toboolean(L, -1) ? "1" : "0");
      } else {
        luaL_error(L, "%s: executor option '%s' must be a string or a number, got %s", fname, k.c_str(), luaL_typename(L, -1));
      }
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  return exec_opts;
}

// env = {NAME = "value"}: variables the solver needs, set explicitly by the model (never taken
// from smi-lua's environment). The user decides which: only names given with --allow-env, and
// never those that make a program load or run other code (se::declared_env_refusal, a second
// guard). Sorted so the store key does not depend on the table's traversal order.
bool env_allowed(lua_State* L, const std::string& name) {
  const lua::Policy& pol = lua::policy(L);
  return pol.unrestricted || std::find(pol.allow_env.begin(), pol.allow_env.end(), name) != pol.allow_env.end();
}

std::vector<std::pair<std::string, std::string>> read_env(lua_State* L, lua::Options& o, const char* fname) {
  std::vector<std::pair<std::string, std::string>> env;
  if (const int t = o.push("env"); t != LUA_TNIL) {
    if (t != LUA_TTABLE) luaL_error(L, "%s: option 'env' must be a table {NAME = \"value\"}, got %s", fname, luaL_typename(L, -1));
    for (const std::string& k : sorted_names(L, fname, "env keys must be variable names")) {
      push_entry(L, k);
      if (lua_type(L, -1) != LUA_TSTRING && lua_type(L, -1) != LUA_TNUMBER)
        luaL_error(L, "%s: env.%s must be a string or a number, got %s", fname, k.c_str(), luaL_typename(L, -1));
      size_t n = 0;
      const char* v = lua_tolstring(L, -1, &n);
      if (std::string(v, n).find('\0') != std::string::npos) luaL_error(L, "%s: env.%s holds a NUL byte", fname, k.c_str());
      if (const std::string why = se::declared_env_refusal(k); !why.empty())
        luaL_error(L, "%s: env.%s cannot be set by a model: %s", fname, k.c_str(), why.c_str());
      if (!env_allowed(L, k))
        luaL_error(L, "%s: env.%s is set by the model, but the command line does not allow it: a model sets only "
                   "variables you allow, with --allow-env %s (allow only variables the solver reads as data, "
                   "see docs/sandbox.md)", fname, k.c_str(), k.c_str());
      env.emplace_back(k, std::string(v, n));
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
  std::sort(env.begin(), env.end());
  return env;
}

// constants = {name = number | string}: values the deck template sees besides the inputs.
void read_constants(lua_State* L, lua::Options& o, const char* fname, se::CommandConfig& c) {
  if (o.push("constants") != LUA_TNIL) {
    if (!lua_istable(L, -1)) luaL_error(L, "%s: option 'constants' must be a table {name = value}", fname);
    for (const std::string& k : sorted_names(L, fname, "constants must have string keys")) {
      push_entry(L, k);
      if (lua_type(L, -1) == LUA_TNUMBER) c.constants[k] = se::DeckValue::num(lua_tonumber(L, -1));
      else if (lua_type(L, -1) == LUA_TSTRING) c.constants[k] = se::DeckValue::str(lua_tostring(L, -1));
      else luaL_error(L, "%s: constant '%s' must be a number or a string, got %s", fname, k.c_str(), luaL_typename(L, -1));
      lua_pop(L, 1);
    }
  }
  lua_pop(L, 1);
}

// The deck: a template (file, text or function) and constants (command form; the deck's file
// name came with the schema), or the points file's name (batch form).
void read_deck(lua_State* L, lua::Options& o, bool batch, const char* fname, const SolverArgs& a, se::CommandConfig& c,
               SolverOptions& so) {
  if (!batch) {
    if (o.push("template") == LUA_TFUNCTION) {  // a deck function (deck_function.cpp)
      lua_pop(L, 1);
      c.deck_function = true;
      if (!a.template_string.empty())
        luaL_error(L, "%s: give exactly one of 'template' (a file or a function) or 'template_string' (the text)", fname);
      read_constants(L, o, fname, c);
      return;
    }
    lua_pop(L, 1);
    so.template_file = o.string("template", "");
    so.template_text = a.template_string;
    if (so.template_file.empty() == so.template_text.empty())
      luaL_error(L, "%s: give exactly one of 'template' (a file) or 'template_string' (the text)", fname);
    read_constants(L, o, fname, c);
  } else {
    c.deck_file = a.input_file;
  }
}

// The executor: the command line's choice (--executor, --slurm-opt, --detach). A study's
// executor = {...} may only narrow it: "local" instead of slurm, fewer tasks at once, smaller
// arrays, fewer requeues, slower polling, no --detach. Where runs go and what they ask of a
// cluster (partition, account, qos, time, mem, cpus, sbatch arguments) is the user's: the study
// may repeat a command-line value (to document it) but not add or change one.
void apply_executor(const RunContext& ctx, const SolverOptions& so, se::CommandConfig& c) {
  if (!ctx.executor.empty()) c.executor.kind = ctx.executor;
  for (const auto& kv : ctx.slurm_opts) c.executor.set(kv);
  c.executor.detach = ctx.detach;
  const se::ExecutorConfig cli = c.executor;
  const auto refuse = [](const std::string& k, const std::string& v, const std::string& why) {
    throw lua::SandboxDenied(fmt::format("executor option {} = '{}' comes from the study, but {}. A study's executor table "
                                    "may only narrow what the command line allows",
                                    k, v, why));
  };
  se::ExecutorConfig wish = cli;  // parses and range-checks the study's values
  for (const auto& [k, v] : so.exec_opts)  // the kind first, whatever the table's order
    if (k == "kind") {
      if (v != "local" && v != cli.kind)
        refuse(k, v, "where solver runs go is the user's choice: run with --executor " + v + " to allow it");
      if (v == "local") c.executor.kind = "local";
    }
  for (const auto& [k, v] : so.exec_opts) {
    if (k == "kind") {
      continue;
    } else if (k == "detach") {
      if (v == "1" && !cli.detach) refuse(k, "true", "leaving jobs running after a stop needs --detach");
      c.executor.detach = cli.detach && v == "1";
    } else if (k == "sbatch") {
      if (std::find(cli.sbatch_args.begin(), cli.sbatch_args.end(), v) == cli.sbatch_args.end())
        refuse(k, v, "sbatch arguments are the user's choice: give --slurm-opt sbatch=" + v);
    } else if (k == "partition" || k == "account" || k == "qos" || k == "time" || k == "mem" || k == "cpus") {
      wish.set(k, v);
      const bool same = k == "partition" ? wish.partition == cli.partition
                        : k == "account" ? wish.account == cli.account
                        : k == "qos"     ? wish.qos == cli.qos
                        : k == "time"    ? wish.time == cli.time
                        : k == "mem"     ? wish.mem == cli.mem
                                         : wish.cpus == cli.cpus;
      if (!same) refuse(k, v, "cluster resources are the user's choice: give --slurm-opt " + k + "=" + v);
    } else {
      wish.set(k, v);
      bool ok = true;  // the study's value asks for less than the command line's
      if (k == "throttle") ok = wish.throttle <= cli.throttle;
      else if (k == "max_array") ok = cli.max_array == 0 || (wish.max_array > 0 && wish.max_array <= cli.max_array);
      else if (k == "max_requeues") ok = wish.max_requeues <= cli.max_requeues;
      else if (k == "poll") ok = wish.poll_min >= cli.poll_min;
      else if (k == "poll_max") ok = wish.poll_max >= cli.poll_max;
      c.executor.set(k, v);  // cmd_timeout, down_after, exit_wait: how long smi-lua waits, nothing more
      if (!ok) refuse(k, v, fmt::format("it asks for more than the command line allows; give --slurm-opt {}={}", k, v));
    }
  }
  c.executor.validate();
}

// The program, extra files and template, checked by the sandbox. Extra files and the template
// are opened here and used through those descriptors (hashed and copied by the evaluator):
// never re-opened by name.
void open_solver_inputs(lua::Policy& pol, const SolverOptions& so, bool batch, const char* fname, se::CommandConfig& c) {
  c.program_name = so.argv[0];
  c.program = pol.check_exec(so.argv[0], fname).string();
  c.args.assign(so.argv.begin() + 1, so.argv.end());
  for (const auto& f : so.files) {
    lua::CheckedFile cf = pol.open_read(f);
    c.files.push_back(cf.path);
    c.file_fds.push_back(std::make_shared<const pathwalk::Fd>(std::move(cf.fd)));
  }
  if (!so.template_file.empty()) {
    const lua::CheckedFile tf = pol.open_read(so.template_file);
    c.deck = std::make_shared<se::DeckTemplate>(lua::read_checked(tf, so.template_file), tf.path);
  } else if (!batch && !c.deck_function) {
    c.deck = std::make_shared<se::DeckTemplate>(so.template_text, "(template_string)");
  }
}

// Where runs and records go: runs/<name> and the store under --out (locked: one process per
// output folder keeps the work folders unique), and the shared store of --store if any.
void place_solver_outputs(lua::Policy& pol, const RunContext& ctx, const SolverOptions& so, se::CommandConfig& c) {
  const fs::path out = pol.out_dir.empty() ? fs::path("smi-out") : pol.out_dir;
  c.runs_dir = pol.checked_write_dir((out / "runs" / c.name).string());
  se::lock_output_folder(pol.out_dir.empty() ? pol.checked_write_dir(out.string()) : pol.ensure_out_dir().string());
  // A store shared by several studies (store = "shared/plate.sqlite") may name a folder that no
  // run has made yet: make it, under a write root only (checked_write_dir refuses elsewhere and
  // names --allow-write).
  const std::string store = so.store.empty() ? (out / "evaluations.sqlite").string() : so.store;
  if (const fs::path folder = fs::path(store).parent_path(); !so.store.empty() && !folder.empty())
    pol.checked_write_dir(folder.string());
  c.store_path = pol.checked_write_file(store);
  if (!ctx.store_path.empty()) {
    const std::string shared = pol.checked_read_file(ctx.store_path);
    if (shared != c.store_path) c.shared_store_path = shared;
  }
}

// version_args = {"--version"}: the program run once with these arguments (no shell, in its runs
// folder, at most kVersionSeconds); the first non-empty line of its stdout is the version line
// the provenance records. Throws naming the program when it fails or prints nothing.
constexpr double kVersionSeconds = 10;  // literal: how long a --version probe may take
std::string version_line(const se::CommandConfig& c, const std::vector<std::string>& args) {
  se::SpawnSpec sp;
  sp.program = c.program;
  sp.argv.push_back(c.program_name);
  sp.argv.insert(sp.argv.end(), args.begin(), args.end());
  sp.workdir = c.runs_dir;
  sp.stdout_path = (fs::path(c.runs_dir) / "version.out").string();
  sp.stderr_path = (fs::path(c.runs_dir) / "version.err").string();
  const pid_t pid = se::spawn_process(sp);
  const double t0 = se::monotonic_seconds();
  int st = 0;
  for (;;) {
    const pid_t r = ::waitpid(pid, &st, WNOHANG);
    if (r == pid || (r < 0 && errno != EINTR)) break;
    if (se::monotonic_seconds() - t0 > kVersionSeconds) {
      se::signal_group(pid, SIGKILL);
      while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
      }
      throw Error(fmt::format("version_args: '{}' did not finish within {} s", c.program_name, kVersionSeconds));
    }
    ::usleep(5000);  // literal: poll interval (us)
  }
  const std::string out = se::file_tail(sp.stdout_path, 4096);  // literal: bytes of output a message quotes
  std::size_t at = 0;
  while (at < out.size()) {
    std::size_t end = out.find('\n', at);
    if (end == std::string::npos) end = out.size();
    std::string line = out.substr(at, end - at);
    while (!line.empty() && (line.back() == '\r' || line.back() == ' ' || line.back() == '\t')) line.pop_back();
    if (!line.empty()) return line;
    at = end + 1;
  }
  throw Error(fmt::format("version_args: '{}' printed nothing on stdout ({}); give the arguments that make it print its version",
                          c.program_name, se::describe_wait_status(st)));
}

// Provenance: the program this model runs, its hash, declared version and version line.
void record_program(const lua::Policy& pol, bool dry_run, const se::CommandConfig& c, const SolverOptions& so) {
  if (!pol.record) return;
  ProgramRun p;
  if (!so.version_args.empty())
    p.version_line = dry_run ? "(not asked: --dry-run launches nothing)" : version_line(c, so.version_args);
  p.name = c.program_name;
  p.path = c.program;
  try {
    p.digest = digest_path(c.program);
  } catch (const Error&) {
    p.digest.hash = "unreadable";  // the run fails when it starts, with the OS's reason
  }
  p.version = c.version;
  pol.record->program(std::move(p));
}

/// Builds the config common to both forms from the option table at index 1: the options are
/// read from Lua first (Lua errors: the scalars by the schema, the nested tables by hand), then
/// checked against the sandbox policy under protect().
se::CommandConfig solver_config(lua_State* L, bool batch, const char* fname) {
  const SolverArgs a = solver_schema(batch).read(L, 1);  // unknown keys, types, defaults
  lua::Options o(L, 1, fname);
  lua::Policy& pol = lua::policy(L);
  const RunContext& ctx = lua::run_context(L);
  se::CommandConfig c = a.config;
  SolverOptions so;
  c.batch = batch;
  if (!valid_model_name(c.name))
    luaL_error(L, "%s: name '%s' must be letters, digits, '_', '-' or '.' (it names the runs folder)", fname, c.name.c_str());
  o.push("inputs");
  c.inputs = lua::to_strings(L, -1, "inputs");
  o.push("outputs");
  c.outputs = lua::to_strings(L, -1, "outputs");
  lua_pop(L, 2);
  so.argv = read_command(L, o, batch, fname);
  if (o.push("files") != LUA_TNIL) so.files = lua::to_strings(L, -1, "files");
  lua_pop(L, 1);
  if (o.push("version_args") != LUA_TNIL) so.version_args = lua::to_strings(L, -1, "version_args");
  lua_pop(L, 1);
  so.exec_opts = read_executor_options(L, o, fname);
  c.env_set = read_env(L, o, fname);
  so.store = a.store;
  read_deck(L, o, batch, fname, a, c, so);
  lua::protect(L, fname, [&] {
    apply_executor(ctx, so, c);
    c.env_names = pol.allow_env;
    if (!ctx.script_path.empty()) c.script_hash = "sha256:" + sha256_file(ctx.script_path);
    open_solver_inputs(pol, so, batch, fname, c);
    place_solver_outputs(pol, ctx, so, c);
    record_program(pol, ctx.dry_run, c, so);
    return 0;
  });
  return c;
}

int make_solver_model(lua_State* L, bool batch) {
  const char* fname = batch ? "smi.model.batch" : "smi.model.command";
  luaL_checktype(L, 1, LUA_TTABLE);
  se::CommandConfig c = solver_config(L, batch, fname);
  lua_getfield(L, 1, "parse");
  const int fn = lua_gettop(L);
  int deck_fn = 0;
  if (c.deck_function) {
    lua_getfield(L, 1, "template");
    deck_fn = lua_gettop(L);
  }
  Model m;
  m.kind = batch ? Model::Batch : Model::Command;
  m.name = c.name;
  m.inputs = c.inputs;
  m.outputs = c.outputs;
  lua::protect(L, fname, [&] {
    m.ev = std::make_unique<se::Evaluator>(std::move(c));
    if (deck_fn) m.ev->set_deck_function(deck_renderer(L, deck_fn, m.ev->config(), fname));
    return 0;
  });
  push_model(L, std::move(m), fn);
  return 1;
}

/// Adds a dry run's plan to the totals in the registry (smi.model.planned()).
void add_planned(lua_State* L, const se::Plan& p) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &kPlannedKey) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_newtable(L);
    lua_pushvalue(L, -1);
    lua_rawsetp(L, LUA_REGISTRYINDEX, &kPlannedKey);
  }
  for (auto [key, v] : {std::pair<const char*, double>{"runs", static_cast<double>(p.runs)},
                        {"points", static_cast<double>(p.points)}, {"reused", static_cast<double>(p.reused)},
                        {"eta", p.eta_seconds}}) {
    lua_getfield(L, -1, key);
    const double before = lua_tonumber(L, -1);
    lua_pop(L, 1);
    if (std::string(key) == "eta" && (v < 0 || before < 0)) v = -1;  // unknown stays unknown
    else v += before;
    lua_pushnumber(L, v);
    lua_setfield(L, -2, key);
  }
  lua_pop(L, 1);
}

}  // namespace

int model_command(lua_State* L) { return make_solver_model(L, false); }
int model_batch(lua_State* L) { return make_solver_model(L, true); }

int model_planned(lua_State* L) {
  if (lua_rawgetp(L, LUA_REGISTRYINDEX, &kPlannedKey) != LUA_TTABLE) {
    lua_pop(L, 1);
    lua_createtable(L, 0, 4);
    lua::set_integer(L, "runs", 0);
    lua::set_integer(L, "points", 0);
    lua::set_integer(L, "reused", 0);
    lua::set_number(L, "eta", 0);
  }
  return 1;
}

namespace {

// A progress line on the terminal (none when quiet or piped), redrawn at most ten times a second.
se::ProgressFn terminal_progress(const Model& m, const RunContext& ctx) {
  if (!ctx.progress.live) return {};
  return [&m, prefix = ctx.progress.prefix(), shown_at = -1.0](const se::Progress& p, bool final) mutable {
    const double now = se::monotonic_seconds();
    if (!final && now - shown_at < 0.1) return;  // literal: a terminal line ten times a second is plenty
    shown_at = now;
    se::show_progress(stderr, prefix + se::format_progress(m.name, p), final);
  };
}

// --dry-run: prints the plan of this evaluation and adds it to the totals; returns the runs it
// needs that are not stored.
std::size_t print_dry_plan(lua_State* L, Model& m, const Eigen::MatrixXd& X) {
  const se::Plan plan = m.ev->plan(X);
  std::printf("%s\n", se::format_plan(m.name, plan, m.ev->config().concurrency).c_str());
  if (const std::string ex = m.ev->executor_plan(plan); !ex.empty()) std::printf("%s", ex.c_str());
  std::fflush(stdout);
  add_planned(L, plan);
  return plan.runs;
}

// The failed points (the first ten) and where their records are; "" when none failed.
std::string failure_summary(const Model& m, const Eigen::MatrixXd& X, const se::EvalResult& r) {
  if (r.failed == 0) return "";
  std::string summary = fmt::format("model '{}': {} of {} point{} failed{}:", m.name, r.failed, X.rows(), X.rows() == 1 ? "" : "s",
                                    r.stopped ? " (on_failure = 'stop')" : " (skipped)");
  int shown = 0;
  for (std::size_t i = 0; i < r.status.size(); ++i)
    if (r.status[i] == se::Status::Failed && shown++ < 10) summary += fmt::format("\n  row {}: {}", i + 1, r.reason[i]);  // literal: failures a message lists
  if (shown > 10) summary += fmt::format("\n  ... and {} more (see info.failures)", shown - 10);  // literal: failures a message lists
  summary += fmt::format("\n  records in {}", m.ev->config().store_path);
  return summary;
}

// A dry run that lacks dry_missing runs of this evaluation stops the study here: what comes next
// is computed from these outputs, which a dry run does not have, so planning further would feed
// NaN to the next step. Prints the plan so far and asks the runtime to exit cleanly (status 0).
void stop_dry_run(lua_State* L, const Model& m, std::size_t dry_missing) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kPlannedKey);
  auto total = [&](const char* k) {
    lua_getfield(L, -1, k);
    const double v = lua_tonumber(L, -1);
    lua_pop(L, 1);
    return v;
  };
  const double runs = total("runs"), points = total("points"), reused = total("reused"), eta = total("eta");
  lua_pop(L, 1);
  std::printf("dry run: stopped at model '%s': %zu of its runs are not in the store, and what the study does next "
              "depends on their results.\ndry run: plan so far: %.0f solver run%s for %.0f point%s (%.0f already "
              "stored), ETA %s; run without --dry-run to make them, then --dry-run again plans the rest.\n",
              m.name.c_str(), dry_missing, runs, runs == 1 ? "" : "s", points, points == 1 ? "" : "s", reused,
              eta < 0 ? "unknown (no stored timing)" : se::format_duration(eta).c_str());
  std::fflush(stdout);
  lua::stop_run(L, cancel::Reason::exit, 0);  // the next Lua instruction ends the run quietly, exit status 0
}

}  // namespace

int evaluate_solver(lua_State* L, Model& m) {
  const Eigen::MatrixXd X = design_of(L, 2, m);
  const RunContext& ctx = lua::run_context(L);
  const bool batch = m.kind == Model::Batch;
  const char* fname = "smi.model:evaluate";
  lua_getiuservalue(L, 1, 1);  // the parser
  const int fn = lua_gettop(L);
  lua_createtable(L, static_cast<int>(m.outputs.size()), 0);
  for (std::size_t j = 0; j < m.outputs.size(); ++j) {
    lua_pushstring(L, m.outputs[j].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(j + 1));
  }
  const int outs = lua_gettop(L);

  // The parser runs under pcall; a Lua error in it becomes LuaError, which the evaluator turns
  // into a failed record ("unparsable output: ...").
  auto call_parser = [&](const std::string& dir, std::size_t n) {
    lua_pushcfunction(L, parse_trampoline);
    lua_pushvalue(L, fn);
    lua_pushstring(L, dir.c_str());
    lua_pushvalue(L, outs);
    if (batch) lua_pushinteger(L, static_cast<lua_Integer>(n));
    else lua_pushnil(L);
    lua::call(L, 4, 1);
    Eigen::VectorXd flat = *lua::test_vec(L, -1);
    lua_pop(L, 1);
    return flat;
  };
  se::ParseFn parse = [&](const std::string& dir) {
    const Eigen::VectorXd v = call_parser(dir, 1);
    se::NamedValues out;
    for (std::size_t j = 0; j < m.outputs.size(); ++j) out.emplace_back(m.outputs[j], v[static_cast<Eigen::Index>(j)]);
    return out;
  };
  se::ParseBatchFn parse_batch = [&](const std::string& dir, std::size_t n) {
    const Eigen::VectorXd v = call_parser(dir, n);
    return Eigen::MatrixXd(Eigen::Map<const Eigen::MatrixXd>(v.data(), static_cast<Eigen::Index>(n),
                                                             static_cast<Eigen::Index>(m.outputs.size())));
  };
  const se::ProgressFn progress = terminal_progress(m, ctx);

  // While we wait on solvers no Lua runs, so the runtime's hook cannot see Ctrl-C, --timeout,
  // the memory ceiling or os.exit: the evaluator reads the run's token itself between runs.
  m.ev->set_cancel(ctx.cancel);

  se::EvalResult r;
  std::string summary;
  std::size_t dry_missing = 0;  // --dry-run: runs this evaluation needs that are not stored
  lua::protect(L, fname, [&] {
    if (ctx.dry_run) dry_missing = print_dry_plan(L, m, X);
    try {
      r = m.ev->evaluate(X, parse, parse_batch, progress, !ctx.dry_run);
    } catch (const Interrupted&) {
      lua::check_stop_now(L);  // the hook raises the token's reason again at the next instruction
      throw;
    }
    summary = failure_summary(m, X, r);
    return 0;
  });
  if (r.stopped) {
    std::string msg = summary + "\n  the remaining points were not run; pass on_failure = 'skip' or 'retry' to go on past failures";
    return luaL_error(L, "%s: %s", fname, msg.c_str());
  }
  if (!summary.empty() && !ctx.quiet) std::fprintf(stderr, "smi.model: %s\n", summary.c_str());
  push_results(L, m, r);
  if (dry_missing > 0 && ctx.cancel) stop_dry_run(L, m, dry_missing);
  return 2;
}

}  // namespace smi::bind::eval
