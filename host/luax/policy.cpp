#include "luax/policy.hpp"

#include <cstdlib>
#include <fmt/format.h>
#include <unistd.h>

namespace smi {
namespace fs = std::filesystem;

fs::path resolve_path(const std::string& path) {
  std::error_code ec;
  fs::path p = fs::absolute(fs::path(path), ec);
  if (ec) p = fs::path(path);
  // weakly_canonical follows symlinks of the existing prefix and normalises the rest lexically.
  fs::path r = fs::weakly_canonical(p, ec);
  if (ec) r = p.lexically_normal();
  return r;
}

bool path_within(const fs::path& path, const fs::path& root) {
  auto pi = path.begin(), ri = root.begin();
  for (; ri != root.end(); ++ri, ++pi) {
    if (ri->empty()) continue;  // trailing separator
    if (pi == path.end() || *pi != *ri) return false;
  }
  return true;
}

namespace {

std::string list_roots(const std::vector<fs::path>& roots) {
  std::string s;
  for (const auto& r : roots) s += (s.empty() ? "" : ", ") + r.string();
  return s.empty() ? "(none)" : s;
}

}  // namespace

fs::path Policy::check_read(const std::string& path, const char* function) const {
  const fs::path r = resolve_path(path);
  if (unrestricted) return r;
  for (const auto& root : read_roots)
    if (path_within(r, root)) return r;
  for (const auto& root : write_roots)
    if (path_within(r, root)) return r;
  // The message leaves out `function`: callers raise it through protect(L, function, ...),
  // which puts the function name in front.
  (void)function;
  throw SandboxDenied(fmt::format(
      "reading '{}' (resolved to '{}') is not allowed: scripts read only under their own folder, "
      "the library folders and --allow-read paths ({}); run with --allow-read {} to allow it",
      path, r.string(), list_roots(read_roots), r.parent_path().string()));
}

fs::path Policy::ensure_out_dir() const {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw Error(fmt::format("cannot create the output folder '{}': {}", out_dir.string(), ec.message()));
  return resolve_path(out_dir.string());
}

fs::path Policy::check_write(const std::string& path, const char* function) const {
  fs::path r = resolve_path(path);
  (void)function;  // named by the caller's protect(), see check_read
  if (!unrestricted) {
    bool ok = false;
    for (const auto& root : write_roots)
      if (path_within(r, root)) ok = true;
    if (!ok)
      throw SandboxDenied(fmt::format(
          "writing '{}' (resolved to '{}') is not allowed: scripts write only under the output folder "
          "(--out, now {}; smi.out(\"name\") gives a path there) and --allow-write paths ({}); run with "
          "--allow-write {} to allow it",
          path, r.string(), out_dir.string(), list_roots(write_roots), r.parent_path().string()));
  }
  // The output folder is created on demand: on the first write under it.
  if (!out_dir.empty() && path_within(r, resolve_path(out_dir.string())) && !fs::exists(out_dir)) {
    ensure_out_dir();
    r = resolve_path(path);
  }
  return r;
}

fs::path Policy::check_exec(const std::string& program, const char* function) const {
  (void)function;  // named by the caller's protect(), see check_read
  fs::path resolved;
  if (program.find('/') != std::string::npos) {
    resolved = resolve_path(program);
  } else if (const char* env = std::getenv("PATH")) {
    std::string dirs = env;
    std::size_t start = 0;
    while (start <= dirs.size()) {
      const std::size_t end = dirs.find(':', start);
      const std::string dir = dirs.substr(start, end == std::string::npos ? std::string::npos : end - start);
      const fs::path cand = fs::path(dir.empty() ? "." : dir) / program;
      if (::access(cand.c_str(), X_OK) == 0) {
        resolved = resolve_path(cand.string());
        break;
      }
      if (end == std::string::npos) break;
      start = end + 1;
    }
  }
  if (resolved.empty())
    throw SandboxDenied(fmt::format("program '{}' not found on PATH", program));
  if (unrestricted) return resolved;
  for (const auto& allowed : exec_allowed) {
    // By name: "--allow-exec column-fe" allows that program wherever PATH finds it.
    if (allowed.find('/') == std::string::npos && allowed == program) return resolved;
    if (allowed.find('/') != std::string::npos && resolve_path(allowed) == resolved) return resolved;
  }
  throw SandboxDenied(fmt::format(
      "running '{}' ({}) is not allowed: scripts run only programs named by --allow-exec; "
      "run with --allow-exec {} to allow it",
      program, resolved.string(), program));
}

namespace lua {
namespace {
const char kPolicyKey = 0;  // its address is the registry key
}

Policy& policy(lua_State* L) {
  lua_rawgetp(L, LUA_REGISTRYINDEX, &kPolicyKey);
  auto* p = static_cast<Policy*>(lua_touserdata(L, -1));
  lua_pop(L, 1);
  if (p) return *p;
  static Policy unrestricted_default = [] {
    Policy d;
    d.unrestricted = true;
    d.out_dir = "smi-out";
    return d;
  }();
  return unrestricted_default;
}

void set_policy(lua_State* L, Policy* p) {
  lua_pushlightuserdata(L, p);
  lua_rawsetp(L, LUA_REGISTRYINDEX, &kPolicyKey);
}
}  // namespace lua

}  // namespace smi
