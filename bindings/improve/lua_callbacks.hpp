// SPDX-License-Identifier: MIT
#pragma once
// C++ callables that call back into Lua during a calibration: the objective function, the model
// (a function or an object with :evaluate) and a custom metric. Each keeps its Lua values at
// fixed absolute stack slots of the running smi.calibrate call, calls through lua::call
// (pcall + traceback; a Lua error becomes smi::lua::LuaError) and restores the stack. One Lua
// call per parameter vector, never one per sample.
#include <lua.hpp>

#include <string>
#include <vector>

#include "bindings/improve/lua_gate.hpp"
#include "kernels/improve/bounded_optimizer.hpp"
#include "kernels/improve/statistical_objective.hpp"

namespace smi::bind::improve {

/// objective(theta) with theta = {name = value}; returns a number, optionally followed by a table
/// {response = value} of parts (keys taken in sorted order at the first call).
class LuaObjective {
 public:
  /// `who` names the function in error messages ("objective", "penalty").
  LuaObjective(lua_State* L, int fn_slot, std::vector<std::string> names, const char* who = "objective");
  smi::improve::Evaluation operator()(const Eigen::VectorXd& theta);
  const std::vector<std::string>& part_names() const { return *parts_; }

 private:
  lua_State* L_;
  int fn_;
  std::vector<std::string> names_;
  const char* who_;
  std::shared_ptr<std::vector<std::string>> parts_ = std::make_shared<std::vector<std::string>>();
  std::shared_ptr<bool> first_ = std::make_shared<bool>(true);
};

/// One callable model: fn(X, input_names) when `self_slot` is 0, else method(self, X).
/// `output` is empty for a model of all responses, or the one response this part predicts
/// (model = {mode1 = kriging1, mode4 = kriging4}).
struct ModelPart {
  std::string output;
  int fn_slot = 0;
  int self_slot = 0;
  int grad_slot = 0;  ///< the object's gradient method (self, X) -> N×k, or 0
};

/// The model: one part returning {output = vec} (extra outputs ignored; a bare vec for a single
/// response), or one part per response, each returning its output by that name or as its only
/// vector. Calls go through `gate`, so the kernels may call it from several threads.
class LuaModel {
 public:
  LuaModel(lua_State* L, std::vector<ModelPart> parts, int names_slot, std::vector<std::string> responses, LuaGate gate);
  Eigen::MatrixXd operator()(const Eigen::MatrixXd& X) const;

 private:
  /// Calls part p; leaves its result on the stack.
  void call_part(const ModelPart& p, const Eigen::MatrixXd& X) const;
  /// Reads response r from the result at the top of the stack: a table, or a bare vec when
  /// `single`; when `lenient`, a table with one output is taken whatever its name (a per-response
  /// surrogate names its output its own way).
  Eigen::VectorXd read_output(const std::string& r, bool single, bool lenient, Eigen::Index rows) const;

  /// The outputs for X; runs inside the gate.
  Eigen::MatrixXd evaluate(const Eigen::MatrixXd& X) const;

  lua_State* L_;
  std::vector<ModelPart> parts_;
  int names_;
  std::vector<std::string> responses_;
  LuaGate gate_;
};

/// metric(predicted, data) with predicted = {response = vec}, data = the spec's data table;
/// returns a number, optionally followed by {response = value}.
class LuaMetric {
 public:
  LuaMetric(lua_State* L, int fn_slot, int data_slot, std::vector<std::string> responses);
  smi::improve::Evaluation operator()(const Eigen::MatrixXd& Y) const;

 private:
  lua_State* L_;
  int fn_, data_;
  std::vector<std::string> responses_;
};

}  // namespace smi::bind::improve
