// SPDX-License-Identifier: MIT
#pragma once
// Reading Lua values from inside C++/NLopt frames. Unlike luax's to_vector, these never raise a
// Lua error (which would unwind through NLopt's callback); they throw smi::InvalidArgument with
// the culprit named, which the optimiser carries out of NLopt intact. Only Lua API functions that
// cannot raise (apart from memory errors) are used: lua_type, lua_rawgeti, lua_rawget, lua_next.
#include <lua.hpp>

#include <Eigen/Core>
#include <string>
#include <vector>

namespace smi::bind::improve {

/// A smi.vec, a 1-column/1-row smi.mat or a sequence table of numbers.
Eigen::VectorXd read_vector(lua_State* L, int idx, const std::string& what);
/// A number (integers accepted), else throws naming `what` and the type found.
double read_number(lua_State* L, int idx, const std::string& what);
/// The string keys of the table at idx, sorted (deterministic order for name-keyed tables).
std::vector<std::string> sorted_keys(lua_State* L, int idx);
/// Pushes t[key] without metamethods. Stack: [] -> [value].
int raw_field(lua_State* L, int idx, const char* key);

/// Restores the stack top on scope exit (callbacks may throw with values pushed).
class StackGuard {
 public:
  explicit StackGuard(lua_State* L) : L_(L), top_(lua_gettop(L)) {}
  ~StackGuard() { lua_settop(L_, top_); }
  StackGuard(const StackGuard&) = delete;
  StackGuard& operator=(const StackGuard&) = delete;

 private:
  lua_State* L_;
  int top_;
};

}  // namespace smi::bind::improve
