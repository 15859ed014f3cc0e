// SPDX-License-Identifier: MIT
#include "bindings/improve/model_gradient.hpp"

#include <fmt/format.h>

#include <memory>

#include "bindings/improve/lua_values.hpp"
#include "bindings/surrogate/kriging_box.hpp"
#include "luax/luax.hpp"
#include "platform/core/errors.hpp"

namespace smi::bind::improve {

namespace {

/// One part's Jacobian source: a Kriging (closed form) or a Lua gradient method.
struct Source {
  const smi::surrogate::kriging::Model* kriging = nullptr;
  int grad_slot = 0;
  int self_slot = 0;
  std::string output;  ///< the part's response name ("" = the model of all responses)
};

/// Reads an N×k Jacobian for response r from the value at the top of the stack: a matrix, or a
/// table {r = mat} (a one-entry table whatever its name for a per-response part).
Eigen::MatrixXd read_jacobian(lua_State* L, const std::string& r, bool lenient, Eigen::Index rows, Eigen::Index cols) {
  Eigen::MatrixXd J;
  if (lua::test_mat(L, -1)) {
    J = *lua::test_mat(L, -1);
  } else if (lua_istable(L, -1)) {
    raw_field(L, -1, r.c_str());
    if (lua_isnil(L, -1) && lenient) {
      lua_pop(L, 1);
      const auto keys = sorted_keys(L, -1);
      if (keys.size() != 1) throw InvalidArgument(fmt::format("the model's gradient has no '{}' (return {{{} = mat}})", r, r));
      raw_field(L, -1, keys[0].c_str());
    }
    J = lua::to_matrix(L, -1, fmt::format("gradient of '{}'", r).c_str());
    lua_pop(L, 1);
  } else {
    throw InvalidArgument(fmt::format("the model's gradient must return an N×k smi.mat or {{{} = mat}}, got {}", r, luaL_typename(L, -1)));
  }
  if (J.rows() != rows || J.cols() != cols)
    throw DimensionMismatch(fmt::format("the model's gradient of '{}' is {}×{}, expected {}×{} (samples × inputs)", r, J.rows(), J.cols(), rows, cols));
  return J;
}

}  // namespace

smi::improve::Model kriging_model(lua_State* L, const CalibrateSpec& s, const std::vector<std::string>& responses, int threads) {
  std::vector<const smi::surrogate::kriging::Model*> per(responses.size(), nullptr);
  for (const ModelPart& p : s.model_parts) {
    const auto* k = p.self_slot ? surrogate::test_kriging(L, p.self_slot) : nullptr;
    if (!k) return {};
    if (p.output.empty()) {
      if (s.model_parts.size() != 1 || responses.size() != 1) return {};
      per[0] = &k->model;
    } else {
      for (std::size_t r = 0; r < responses.size(); ++r)
        if (responses[r] == p.output) per[r] = &k->model;
    }
  }
  for (const auto* m : per)
    if (!m) return {};  // a response without its Kriging: LuaModel says which
  // The boxes stay alive: the spec's slots hold them on the Lua stack for the whole call.
  return [per, threads](const Eigen::MatrixXd& X) {
    Eigen::MatrixXd Y(X.rows(), static_cast<Eigen::Index>(per.size()));
    for (std::size_t r = 0; r < per.size(); ++r) Y.col(static_cast<Eigen::Index>(r)) = smi::surrogate::kriging::predict_mean(*per[r], X, threads);
    return Y;
  };
}

smi::improve::StatisticalObjective::ModelJacobian model_jacobian(lua_State* L, const CalibrateSpec& s,
                                                                  const std::vector<std::string>& responses, const LuaGate& gate) {
  std::vector<Source> src;
  for (const ModelPart& p : s.model_parts) {
    Source x;
    x.output = p.output;
    x.self_slot = p.self_slot;
    if (p.self_slot) {
      if (auto* k = surrogate::test_kriging(L, p.self_slot)) x.kriging = &k->model;
      else x.grad_slot = p.grad_slot;
    }
    if (!x.kriging && !x.grad_slot) return {};
    src.push_back(x);
  }
  if (src.empty()) return {};
  // A single Kriging predicts one output: it can serve one response only.
  if (src.size() == 1 && src[0].output.empty() && src[0].kriging && responses.size() != 1) return {};
  return [L, src, responses, gate](const Eigen::MatrixXd& X) {
    std::vector<Eigen::MatrixXd> J(responses.size());
    // A part of all responses is called once and read for each.
    if (src.size() == 1 && src[0].output.empty()) {
      const Source& part = src[0];
      if (part.kriging) {
        J[0] = smi::surrogate::kriging::predict_gradient(*part.kriging, X, 2);
        return J;
      }
      gate.run([&] {
        StackGuard guard(L);
        lua_pushvalue(L, part.grad_slot);
        lua_pushvalue(L, part.self_slot);
        lua::push_mat(L, X);
        lua::call(L, 2, 1);
        if (responses.size() > 1 && lua::test_mat(L, -1))
          throw InvalidArgument(fmt::format("the model's gradient returned one matrix for {} responses: return {{response = mat, ...}}",
                                            responses.size()));
        for (std::size_t r = 0; r < responses.size(); ++r) J[r] = read_jacobian(L, responses[r], false, X.rows(), X.cols());
      });
      return J;
    }
    for (std::size_t r = 0; r < responses.size(); ++r) {
      const Source* part = nullptr;
      for (const Source& p : src)
        if (p.output == responses[r]) part = &p;
      if (!part) throw InvalidArgument(fmt::format("no model part predicts response '{}'", responses[r]));
      if (part->kriging) {
        J[r] = smi::surrogate::kriging::predict_gradient(*part->kriging, X, 2);
        continue;
      }
      gate.run([&] {
        StackGuard guard(L);
        lua_pushvalue(L, part->grad_slot);
        lua_pushvalue(L, part->self_slot);
        lua::push_mat(L, X);
        lua::call(L, 2, 1);
        J[r] = read_jacobian(L, responses[r], true, X.rows(), X.cols());
      });
    }
    return J;
  };
}

}  // namespace smi::bind::improve
