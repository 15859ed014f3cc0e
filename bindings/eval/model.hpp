// SPDX-License-Identifier: MIT
#pragma once
// smi.model: the one object type behind smi.model.command, smi.model.batch and smi.model.lua
// (see the interface comment in open.cpp). The Lua function a model calls (an output parser or
// the model function itself) lives in the box's user value 1, so the GC keeps it alive exactly
// as long as the model.
#include <Eigen/Core>
#include <functional>
#include <memory>
#include <optional>
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
/// Pushes a model box owning `m`, with the function at `fn_idx` as its user value 1.
/// Stack: [...] -> [..., model].
void push_model(lua_State* L, Model m, int fn_idx);

/// The evaluator's deck maker for the deck function at `idx` (deck_function.cpp): the function,
/// copied into a Lua state of its own, called with the point and `cfg`'s constants. Throws
/// smi::InvalidArgument naming `fname` and what the function captures that cannot be copied.
std::function<std::string(const Eigen::VectorXd&)> deck_renderer(lua_State* L, int idx,
                                                                  const smi::eval::CommandConfig& cfg,
                                                                  const char* fname);

/// The design matrix argument at `idx`: a smi.mat, a table of rows, or a table of named
/// columns {x1 = vec, ...} (a table of named numbers is one point). Raises naming what is wrong.
Eigen::MatrixXd design_of(lua_State* L, int idx, const Model& m);

/// Pushes the two results of m:evaluate: Y = {output = smi.vec, ...} and the info table
/// {status, ok, reason, duration, reused, failed, launched, stopped, failures}.
void push_results(lua_State* L, const Model& m, const smi::eval::EvalResult& r);

/// m:evaluate for each kind. Stack on entry: [model, X].
int evaluate_solver(lua_State* L, Model& m);
int evaluate_lua(lua_State* L, Model& m);

/// Raises naming the model's inputs when X has not one column per input.
void check_columns(lua_State* L, const Eigen::MatrixXd& X, const Model& m);

/// The model at idx, or nullptr when it is not an smi.model.
Model* test_model(lua_State* L, int idx);

/// What m:evaluate(X) computes for the smi.model.lua at idx, without its status tables: the
/// outputs (rows × `outputs`, set to the model's names), a row with a non-finite output all NaN.
/// Nothing when idx is not an in-process Lua model. For C++ callers that evaluate it thousands
/// of times (a calibration, the evidence's sampler); the status of 2000 rows as Lua strings
/// cost more than the model.
std::optional<Eigen::MatrixXd> lua_model_outputs(lua_State* L, int idx, const Eigen::MatrixXd& X, std::vector<std::string>& outputs);

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
