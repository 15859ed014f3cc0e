#pragma once
// The Lua VM of one smi-lua run: state, standard libraries, the smi module, embedded stdlib.
#include <cstdint>
#include <string>
#include <vector>
#include <lua.hpp>

namespace smi::vm {

struct Config {
  std::uint64_t seed = 20200214;  // fixed default, recorded in results
  bool quiet = false;
  std::string stdlib_dir;         // load stdlib from disk (development); empty = embedded
};

class Runtime {
 public:
  explicit Runtime(Config cfg);
  ~Runtime();
  Runtime(const Runtime&) = delete;
  Runtime& operator=(const Runtime&) = delete;

  lua_State* state() const { return L_; }
  const Config& config() const { return cfg_; }

  /// Runs a script file with `args` as arg[1..n] and `...`; returns true on success, false after
  /// printing "smi-lua: <message>\n<traceback>" to stderr.
  bool run_file(const std::string& path, const std::vector<std::string>& args);
  /// Runs a chunk of code (-e).
  bool run_string(const std::string& code, const std::string& chunkname);

 private:
  bool report(int status);
  Config cfg_;
  lua_State* L_;
};

}  // namespace smi::vm
