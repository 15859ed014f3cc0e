#pragma once
// smi.model: the one object type behind smi.model.command, smi.model.batch and smi.model.lua
// (see the interface comment in open.cpp). The Lua function a model calls (an output parser or
// the model function itself) lives in the box's user value 1, so the GC keeps it alive exactly
// as long as the model.
#include <Eigen/Core>
#include <memory>
#include <string>
#include <vector>
#include <lua.hpp>

#include "platform/eval/evaluator.hpp"

namespace smi::bind::eval {

inline constexpr const char* kModelType = "smi.model";

struct Model {
  enum Kind { Command, Batch, LuaFn } kind = LuaFn;
  std::string name;
  std::vector<std::string> inputs, outputs;
  std::unique_ptr<smi::eval::Evaluator> ev;  // Command and Batch
};

/// Creates the smi.model metatable.
void register_model_type(lua_State* L);
/// Pushes a model box owning `m`, with the function at `fn_idx` as its user value 1 and the deck
/// function at `deck_idx` (0 = none) as user value 2. Stack: [...] -> [..., model].
void push_model(lua_State* L, Model m, int fn_idx, int deck_idx = 0);

/// Pushes a copy of the Lua function at `idx` that runs without I/O (deck_function.cpp): its
/// _ENV is a table of the pure globals only, its other upvalues copied. Raises naming `fname`.
void push_pure_function(lua_State* L, int idx, const char* fname);

/// While alive, the model's evaluator makes its decks by calling the model's deck function (user
/// value 2 of the model box at `model_idx`) with the point {input = value, constant = value},
/// I/O barred. Does nothing for a model without one. The function stays on the Lua stack.
class DeckFunctionScope {
 public:
  DeckFunctionScope(lua_State* L, int model_idx, Model& m);
  ~DeckFunctionScope();
  DeckFunctionScope(const DeckFunctionScope&) = delete;
  DeckFunctionScope& operator=(const DeckFunctionScope&) = delete;

 private:
  Model& m_;
  bool active_ = false;
};

/// The design matrix argument at `idx`: a smi.mat, a table of rows, or a table of named
/// columns {x1 = vec, ...} (a table of named numbers is one point). Raises naming what is wrong.
Eigen::MatrixXd design_of(lua_State* L, int idx, const Model& m);

/// Pushes the two results of m:evaluate: Y = {output = smi.vec, ...} and the info table
/// {status, ok, reason, duration, reused, failed, launched, stopped, failures}.
void push_results(lua_State* L, const Model& m, const smi::eval::EvalResult& r);

/// m:evaluate for each kind. Stack on entry: [model, X].
int evaluate_solver(lua_State* L, Model& m);
int evaluate_lua(lua_State* L, Model& m);

/// Constructors (smi.model.command, smi.model.batch, smi.model.lua).
int model_command(lua_State* L);
int model_batch(lua_State* L);
int model_lua(lua_State* L);
/// smi.model.planned(): totals of the dry run so far {runs, points, reused, eta}.
int model_planned(lua_State* L);

/// Pushes the parse helper table bound to work directory `dir` (relative names resolve there);
/// an empty dir gives the free-standing smi.model.parse table (paths as given).
void push_parse_helpers(lua_State* L, const std::string& dir);

}  // namespace smi::bind::eval
