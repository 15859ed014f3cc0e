// SPDX-License-Identifier: MIT
#include "bindings/improve/lua_callbacks.hpp"

#include <fmt/format.h>

#include <algorithm>

#include "bindings/eval/model.hpp"
#include "bindings/improve/lua_values.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

using smi::improve::Evaluation;

namespace {

/// Reads `value [, parts]` left by a call (stack: [..., value, parts]); `names` fixes the parts'
/// order (filled from the first call's sorted keys when empty and `learn` is set).
Evaluation read_evaluation(lua_State* L, const char* who, std::vector<std::string>& names, bool learn, bool strict) {
  Evaluation e;
  e.value = read_number(L, -2, fmt::format("the value returned by the {}", who));
  if (lua_type(L, -1) == LUA_TTABLE) {
    if (learn) names = sorted_keys(L, -1);
    e.parts.resize(static_cast<Eigen::Index>(names.size()));
    for (std::size_t i = 0; i < names.size(); ++i) {
      raw_field(L, -1, names[i].c_str());
      e.parts[static_cast<Eigen::Index>(i)] = read_number(L, -1, fmt::format("part '{}' returned by the {}", names[i], who));
      lua_pop(L, 1);
    }
  } else if (strict && !names.empty() && !learn) {
    throw InvalidArgument(fmt::format("the {} returned parts before but not now (return the same table every time)", who));
  }
  return e;
}

/// The error for a model whose outputs (`have`, in name order) lack response r.
InvalidArgument missing_output(const std::string& who, const std::string& r, const std::vector<std::string>& have) {
  std::string list;
  for (const auto& k : have) list += (list.empty() ? "" : ", ") + k;
  return InvalidArgument(fmt::format("{}'s outputs have no '{}' (it returned: {}); the data names the responses", who, r,
                                     list.empty() ? "nothing by name" : list));
}

}  // namespace

LuaObjective::LuaObjective(lua_State* L, int fn_slot, std::vector<std::string> names, const char* who)
    : L_(L), fn_(fn_slot), names_(std::move(names)), who_(who) {}

Evaluation LuaObjective::operator()(const Eigen::VectorXd& theta) {
  StackGuard guard(L_);
  lua_pushvalue(L_, fn_);
  lua_createtable(L_, 0, static_cast<int>(names_.size()));
  for (std::size_t i = 0; i < names_.size(); ++i) {
    lua_pushnumber(L_, theta[static_cast<Eigen::Index>(i)]);
    lua_setfield(L_, -2, names_[i].c_str());
  }
  lua::call(L_, 1, 2);
  const bool learn = *first_;
  *first_ = false;
  return read_evaluation(L_, who_, *parts_, learn, true);
}

LuaModel::LuaModel(lua_State* L, std::vector<ModelPart> parts, int names_slot, std::vector<std::string> responses, LuaGate gate)
    : L_(L), parts_(std::move(parts)), names_(names_slot), responses_(std::move(responses)), gate_(std::move(gate)) {}

void LuaModel::call_part(const ModelPart& p, const Eigen::MatrixXd& X) const {
  lua_pushvalue(L_, p.fn_slot);
  if (p.self_slot) {
    lua_pushvalue(L_, p.self_slot);
    lua::push_mat(L_, X);
  } else {
    lua::push_mat(L_, X);
    lua_pushvalue(L_, names_);
  }
  lua::call(L_, 2, 1);
}

Eigen::VectorXd LuaModel::read_output(const std::string& r, bool single, bool lenient, Eigen::Index rows) const {
  Eigen::VectorXd y;
  const std::string who = parts_.size() > 1 ? fmt::format("the model of '{}'", r) : std::string("the model");
  if (lua::test_vec(L_, -1)) {
    if (!single)
      throw InvalidArgument(fmt::format("{} returned one vector but {} responses are calibrated: return {{name = vec, ...}}", who,
                                        responses_.size()));
    y = *lua::test_vec(L_, -1);
  } else if (lua_type(L_, -1) != LUA_TTABLE) {
    throw InvalidArgument(fmt::format("{} must return a table {{output = vec}}, got {}", who, lua_typename(L_, lua_type(L_, -1))));
  } else {
    raw_field(L_, -1, r.c_str());
    if (lua_isnil(L_, -1)) {
      lua_pop(L_, 1);
      const auto have = sorted_keys(L_, -1);
      if (!(lenient && have.size() == 1)) throw missing_output(who, r, have);
      raw_field(L_, -1, have[0].c_str());  // a one-output part predicts its response whatever it calls it
    }
    y = read_vector(L_, -1, fmt::format("model output '{}'", r));
    lua_pop(L_, 1);
  }
  if (y.size() != rows) throw DimensionMismatch(fmt::format("model output '{}' has {} values for {} input rows", r, y.size(), rows));
  return y;
}

Eigen::MatrixXd LuaModel::operator()(const Eigen::MatrixXd& X) const {
  Eigen::MatrixXd Y;
  gate_.run([&] { Y = evaluate(X); });
  return Y;
}

Eigen::MatrixXd LuaModel::evaluate(const Eigen::MatrixXd& X) const {
  StackGuard guard(L_);
  Eigen::MatrixXd Y(X.rows(), static_cast<Eigen::Index>(responses_.size()));
  if (parts_.size() == 1 && parts_[0].output.empty() && parts_[0].self_slot) {
    std::vector<std::string> outputs;
    if (const auto all = eval::lua_model_outputs(L_, parts_[0].self_slot, X, outputs)) {  // an smi.model.lua, without its status tables
      for (std::size_t j = 0; j < responses_.size(); ++j) {
        const auto at = std::find(outputs.begin(), outputs.end(), responses_[j]);
        if (at == outputs.end()) {
          std::sort(outputs.begin(), outputs.end());
          throw missing_output("the model", responses_[j], outputs);
        }
        Y.col(static_cast<Eigen::Index>(j)) = all->col(at - outputs.begin());
      }
      return Y;
    }
  }
  if (parts_.size() == 1 && parts_[0].output.empty()) {
    call_part(parts_[0], X);
    for (std::size_t j = 0; j < responses_.size(); ++j) Y.col(static_cast<Eigen::Index>(j)) = read_output(responses_[j], responses_.size() == 1, false, X.rows());
    return Y;
  }
  for (std::size_t j = 0; j < responses_.size(); ++j) {
    const ModelPart* part = nullptr;
    for (const auto& p : parts_)
      if (p.output == responses_[j]) part = &p;
    if (!part) throw InvalidArgument(fmt::format("the model table has no entry for response '{}' (the data names the responses)", responses_[j]));
    call_part(*part, X);
    Y.col(static_cast<Eigen::Index>(j)) = read_output(responses_[j], true, true, X.rows());
    lua_pop(L_, 1);
  }
  return Y;
}

LuaMetric::LuaMetric(lua_State* L, int fn_slot, int data_slot, std::vector<std::string> responses)
    : L_(L), fn_(fn_slot), data_(data_slot), responses_(std::move(responses)) {}

Evaluation LuaMetric::operator()(const Eigen::MatrixXd& Y) const {
  StackGuard guard(L_);
  lua_pushvalue(L_, fn_);
  lua::push_named_vectors(L_, responses_, Y);
  lua_pushvalue(L_, data_);
  lua::call(L_, 2, 2);
  std::vector<std::string> names = responses_;
  return read_evaluation(L_, "metric", names, false, false);
}

}  // namespace smi::bind::improve
