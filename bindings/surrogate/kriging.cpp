// SPDX-License-Identifier: MIT
// smi.kriging.fit(X, y, opts) -> smi.kriging;  smi.kriging.load(path) -> smi.kriging
//   m:predict(X [, {mse = false}]) -> mean vec, mse vec   (whole matrix, both cores)
//   m:loo() -> {residuals = vec, variance = vec, q2, rmse}
//   m:save(path)                                           (sandbox: check_write)
//   m:evaluate(X) -> {<output> = vec}                      (the model interface)
//   fields: theta, psi, sigma2, beta, evaluations, method, trend, corr, nugget, n, inputs,
//           output, warnings, lower, upper
#include <cerrno>
#include <cmath>
#include <cstring>
#include <fcntl.h>
#include <fmt/format.h>
#include <sstream>

#include "bindings/surrogate/kriging_box.hpp"
#include "bindings/surrogate/kriging_options.hpp"
#include "bindings/surrogate/open_parts.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"

namespace smi::bind::surrogate {
namespace {

KrigingBox& self(lua_State* L) { return lua::check_box<KrigingBox>(L, 1, kKrigingType); }

void push_strings(lua_State* L, const std::vector<std::string>& v) {
  lua_createtable(L, static_cast<int>(v.size()), 0);
  for (std::size_t i = 0; i < v.size(); ++i) {
    lua_pushstring(L, v[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
}

int k_fit(lua_State* L) {
  const Eigen::MatrixXd X = lua::to_matrix(L, 1, "X");
  const Eigen::VectorXd y = lua::to_vector(L, 2, "y");
  KrigingFitArgs fo = kriging_fit_schema().read(L, 3);
  KrigingBox box;
  box.inputs = std::move(fo.inputs);
  box.output = fo.output;
  return lua::protect(L, "smi.kriging.fit", [&] {
    if (!box.inputs.empty() && static_cast<Eigen::Index>(box.inputs.size()) != X.cols())
      throw DimensionMismatch("inputs names " + std::to_string(box.inputs.size()) + " names for " +
                              std::to_string(X.cols()) + " columns of X");
    box.model = smi::surrogate::kriging::fit(X, y, fo);
    lua::push_box(L, kKrigingType, std::move(box));
    return 1;
  });
}

int k_predict(lua_State* L) {
  KrigingBox& k = self(L);
  const Eigen::MatrixXd X = lua::to_matrix(L, 2, "X");
  const KrigingPredictArgs po = kriging_predict_schema().read(L, 3);
  const bool want_mse = po.mse;
  const int threads = po.threads;
  return lua::protect(L, "predict", [&] {
    if (!want_mse) {
      lua::push_vec(L, smi::surrogate::kriging::predict_mean(k.model, X, threads));
      return 1;
    }
    smi::surrogate::kriging::Prediction p = smi::surrogate::kriging::predict(k.model, X, threads);
    lua::push_vec(L, std::move(p.mean));
    lua::push_vec(L, std::move(p.mse));
    return 2;
  });
}

int k_evaluate(lua_State* L) {
  KrigingBox& k = self(L);
  const Eigen::MatrixXd X = lua::to_matrix(L, 2, "X");
  return lua::protect(L, "evaluate", [&] {
    lua_createtable(L, 0, 1);
    lua::push_vec(L, smi::surrogate::kriging::predict_mean(k.model, X));
    lua_setfield(L, -2, k.output.c_str());
    return 1;
  });
}

int k_loo(lua_State* L) {
  KrigingBox& k = self(L);
  return lua::protect(L, "loo", [&] {
    smi::surrogate::kriging::LooResult r = smi::surrogate::kriging::loo(k.model);
    lua_createtable(L, 0, 4);
    lua::set_vec(L, "residuals", std::move(r.residuals));
    lua::set_vec(L, "variance", std::move(r.variance));
    lua::set_number(L, "q2", r.q2);
    lua::set_number(L, "rmse", r.rmse);
    return 1;
  });
}

int k_save(lua_State* L) {
  KrigingBox& k = self(L);
  const std::string path = luaL_checkstring(L, 2);
  return lua::protect(L, "save", [&] {
    std::ostringstream text;
    smi::surrogate::kriging::save(k.model, text, path, {k.inputs, k.output});  // rendered before the file is opened
    const lua::CheckedFile f = lua::policy(L).open_write(path, O_WRONLY | O_CREAT | O_TRUNC);
    if (!pathwalk::write_all(f.fd.get(), text.str()))
      throw Error(fmt::format("writing '{}' failed: {}", path, std::strerror(errno)));
    return 0;
  });
}

int k_load(lua_State* L) {
  const std::string path = luaL_checkstring(L, 1);
  return lua::protect(L, "smi.kriging.load", [&] {
    const lua::CheckedFile f = lua::policy(L).open_read(path);
    std::istringstream text(lua::read_checked(f, path));
    KrigingBox box;
    smi::surrogate::kriging::ModelNames names;
    box.model = smi::surrogate::kriging::load(text, path, &names);
    box.inputs = std::move(names.inputs);
    if (!names.output.empty()) box.output = std::move(names.output);
    lua::push_box(L, kKrigingType, std::move(box));
    return 1;
  });
}

int k_tostring(lua_State* L) {
  KrigingBox& k = self(L);
  std::ostringstream os;
  os.precision(4);
  const auto& m = k.model;
  os << "smi.kriging(" << m.size() << " points, " << m.inputs() << " inputs, trend=" << smi::surrogate::kriging::trend_name(m.trend)
     << ", corr=" << smi::surrogate::kriging::corr_name(m.corr) << ", theta=[";
  for (Eigen::Index j = 0; j < m.theta.size(); ++j) os << (j ? ", " : "") << m.theta[j];
  os << "], sigma2=" << m.process_variance() << ", method=" << m.method << ")";
  lua_pushstring(L, os.str().c_str());
  return 1;
}

int k_field(lua_State* L) {
  KrigingBox& k = self(L);
  const std::string key = lua_tostring(L, 2) ? lua_tostring(L, 2) : "";
  const auto& m = k.model;
  if (key == "theta") lua::push_vec(L, m.theta);
  else if (key == "psi") lua_pushnumber(L, m.psi);
  else if (key == "sigma2") lua_pushnumber(L, m.process_variance());
  else if (key == "beta") lua::push_vec(L, m.beta);
  else if (key == "evaluations") lua_pushinteger(L, m.evaluations);
  else if (key == "method") lua_pushstring(L, m.method.c_str());
  else if (key == "trend") lua_pushstring(L, smi::surrogate::kriging::trend_name(m.trend));
  else if (key == "corr") lua_pushstring(L, smi::surrogate::kriging::corr_name(m.corr));
  else if (key == "nugget") lua_pushnumber(L, m.nugget);
  else if (key == "n") lua_pushinteger(L, m.size());
  else if (key == "output") lua_pushstring(L, k.output.c_str());
  else if (key == "inputs") push_strings(L, k.inputs);
  else if (key == "outputs") push_strings(L, {k.output});
  else if (key == "warnings") push_strings(L, m.warnings);
  else if (key == "lower" && m.lower.size()) lua::push_vec(L, m.lower);
  else if (key == "upper" && m.upper.size()) lua::push_vec(L, m.upper);
  else return 0;
  return 1;
}

const luaL_Reg kMethods[] = {{"predict", k_predict}, {"loo", k_loo},           {"save", k_save},
                             {"evaluate", k_evaluate}, {nullptr, nullptr}};
const luaL_Reg kMeta[] = {{"__tostring", k_tostring}, {nullptr, nullptr}};
const luaL_Reg kKrigingFuncs[] = {{"fit", k_fit}, {"load", k_load}, {nullptr, nullptr}};

}  // namespace

KrigingBox* test_kriging(lua_State* L, int idx) { return lua::test_box<KrigingBox>(L, idx, kKrigingType); }

void open_kriging(lua_State* L) {
  lua::register_type<KrigingBox>(L, kKrigingType, kMethods, kMeta, k_field);
  lua_newtable(L);
  lua::set_funcs(L, kKrigingFuncs);
  lua_setfield(L, -2, "kriging");
}

}  // namespace smi::bind::surrogate
