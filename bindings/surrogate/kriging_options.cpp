// SPDX-License-Identifier: MIT
// The option schemas of the Kriging functions (kriging_options.hpp). Defaults: the structs'.
#include "bindings/surrogate/kriging_options.hpp"

#include <optional>

#include "kernels/surrogate/correlation.hpp"
#include "kernels/surrogate/regression.hpp"
#include "luax/doc_text.hpp"
#include "luax/luax.hpp"

namespace smi::bind::surrogate {

using namespace smi::lua;
namespace kr = smi::surrogate::kriging;

namespace {

/// A number (one value for every input) or a vec/table (one per input).
Eigen::VectorXd read_vector(lua_State* L, int v, const char* key) {
  if (lua_type(L, v) == LUA_TNUMBER) return Eigen::VectorXd::Constant(1, lua_tonumber(L, v));
  return lua::to_vector(L, v, key);
}

/// theta0, lower, upper: vectors, empty (automatic) unless given.
Option<KrigingFitArgs> vector_option(const char* key, Eigen::VectorXd kr::FitOptions::*m, const char* doc) {
  return {key, doc, [=](lua_State* L, int v, KrigingFitArgs& s) { s.*m = read_vector(L, v, key); },
          [](const KrigingFitArgs&) { return std::string("nil"); }, {}};
}

}  // namespace

// long: one table of 14 entries, one per option in the reference's order (data, no logic)
const Schema<KrigingFitArgs>& kriging_fit_schema() {
  using S = KrigingFitArgs;
  static const Schema<S> s("smi.kriging.fit", std::vector<Option<S>>{
      parsed<S>("trend", &S::trend, kr::parse_trend, kr::trend_name, "\"constant\", \"linear\" or \"quadratic\""),
      parsed<S>("corr", &S::corr, kr::parse_corr, kr::corr_name, "\"gauss\", \"exp\", \"matern32\" or \"matern52\""),
      Option<S>{"theta", "fixed correlation parameters (a number or one per input): no search",
                [](lua_State* L, int v, S& s) { s.theta = read_vector(L, v, "theta"); },
                [](const S&) { return std::string("nil"); }, {}},
      string<S>("method", &S::method, {}, "\"ml\" or \"boxmin\" (DACE's pattern search)"),
      vector_option("theta0", &kr::FitOptions::theta0, "boxmin's start (a number or one per input)"),
      vector_option("lower", &kr::FitOptions::lower, "bounds of theta (default: scaled to the data)"),
      vector_option("upper", &kr::FitOptions::upper, "upper bounds of theta"),
      Option<S>{"nugget", "a relative nugget, or true to estimate it (noisy responses)",
                [](lua_State* L, int v, S& s) {
                  if (lua_type(L, v) == LUA_TBOOLEAN) s.estimate_nugget = lua_toboolean(L, v);
                  else s.nugget = schema_detail::to_number(L, v, "nugget");
                },
                [](const S& s) { return s.estimate_nugget ? std::string("true") : num(s.nugget); }, {}},
      integer<S>("starts", &S::starts, at_least(0), "local searches of the multistart; 0 = automatic by size"),
      integer<S>("seed", &S::seed, any_value(), "the multistart's candidate points"),
      boolean<S>("normalize", &S::normalize, "DACE's normalisation of inputs and response"),
      Option<S>{"inputs", "input names (for smi.propagate, smi.screen and smi.calibrate)",
                [](lua_State* L, int v, S& s) { s.inputs = lua::to_strings(L, v, "inputs"); },
                [](const S&) { return std::string("nil"); }, {}},
      string<S>("output", &S::output, {}, "the response's name"),
      integer<S>("threads", &S::threads, at_least(1), "worker threads"),
  });
  return s;
}

const Schema<KrigingPredictArgs>& kriging_predict_schema() {
  using S = KrigingPredictArgs;
  static const Schema<S> s("predict", std::vector<Option<S>>{
      boolean<S>("mse", &S::mse, "also return the mean squared error (false: the mean only, faster)"),
      integer<S>("threads", &S::threads, at_least(1), "worker threads"),
  });
  return s;
}

}  // namespace smi::bind::surrogate
