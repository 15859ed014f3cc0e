// smi.kriging.sequential{model, design, candidates, weights, batch, max, q2, rmse, trend, corr,
//                        seed, inputs}
//   -> {X = mat, Y = {<output> = vec}, kriging = {<output> = smi.kriging},
//       history = {{points, q2 = {<output> = x}, rmse = {...}}, ...}, reached, stop}
// The thin face of surrogate/sequential_design.hpp: the model (an smi.model, a Lua function or a
// table of the model interface) runs on `design`, then on one batch of candidate rows at a time
// (a parallel evaluator gets the whole batch) until every output's leave-one-out Q2 reaches `q2`
// and its LOO RMSE `rmse[<output>]` (when given), or the design holds `max` points.
#include <cmath>
#include <limits>

#include "bindings/surrogate/kriging_box.hpp"
#include "bindings/surrogate/model_arg.hpp"
#include "kernels/surrogate/sequential_design.hpp"
#include "luax/luax.hpp"
#include "luax/policy.hpp"

namespace smi::bind::surrogate {
namespace {

int sequential_call(lua_State* L) {
  constexpr const char* fname = "smi.kriging.sequential";
  luaL_checktype(L, 1, LUA_TTABLE);
  lua::Options o(L, 1, fname);
  o.check_known({"model", "design", "candidates", "weights", "batch", "max", "q2", "rmse", "trend", "corr", "seed", "inputs"});
  o.push("model");
  const int model_idx = lua_gettop(L);
  if (lua_isnil(L, model_idx)) return luaL_error(L, "%s: 'model' is required (an smi.model, a function or a model object)", fname);
  ModelArg model = to_model(L, model_idx, fname);
  auto matrix = [&](const char* key) {
    if (o.push(key) == LUA_TNIL) luaL_error(L, "%s: '%s' is required", fname, key);
    Eigen::MatrixXd m = lua::to_matrix(L, -1, key);
    lua_pop(L, 1);
    return m;
  };
  const Eigen::MatrixXd design = matrix("design"), candidates = matrix("candidates");
  Eigen::VectorXd weights;
  if (o.push("weights") == LUA_TNIL)
    weights = Eigen::VectorXd::Ones(candidates.rows());
  else
    weights = lua::to_vector(L, -1, "weights");
  lua_pop(L, 1);
  smi::surrogate::kriging::SequentialOptions so;
  so.batch = static_cast<Eigen::Index>(o.integer("batch", 10));
  so.max_points = static_cast<Eigen::Index>(o.integer("max", 100));
  so.q2_target = o.number("q2", 0.999);
  so.fit.seed = static_cast<std::uint64_t>(o.integer("seed", static_cast<lua_Integer>(lua::policy(L).seed)));
  const std::string trend = o.string("trend", "constant"), corr = o.string("corr", "gauss");
  std::vector<std::string> input_names;
  if (o.has("inputs")) {
    o.push("inputs");
    input_names = lua::to_strings(L, -1, "inputs");
    lua_pop(L, 1);
  } else {
    input_names = model.input_names;
  }
  const int rmse_t = o.push("rmse");
  const int rmse_idx = lua_gettop(L);
  if (rmse_t != LUA_TNIL && rmse_t != LUA_TTABLE) return luaL_error(L, "%s: 'rmse' must be a table {<output> = target}", fname);
  return lua::protect(L, fname, [&] {
    so.fit.trend = smi::surrogate::kriging::parse_trend(trend);
    so.fit.corr = smi::surrogate::kriging::parse_corr(corr);
    if (!input_names.empty() && static_cast<Eigen::Index>(input_names.size()) != design.cols())
      throw DimensionMismatch(std::to_string(input_names.size()) + " input names for " + std::to_string(design.cols()) +
                              " columns of the design");
    // The model's first call (the initial design) fills its output names, which the RMSE
    // targets are read by; the kernel then gets those outputs back on its own first call.
    const Eigen::MatrixXd Y0 = model.fn(design);
    if (rmse_t != LUA_TNIL) {
      so.rmse_target = Eigen::VectorXd::Constant(static_cast<Eigen::Index>(model.outputs->size()),
                                                 std::numeric_limits<double>::quiet_NaN());
      for (std::size_t j = 0; j < model.outputs->size(); ++j) {
        lua_getfield(L, rmse_idx, (*model.outputs)[j].c_str());
        if (lua_isnumber(L, -1)) so.rmse_target(static_cast<Eigen::Index>(j)) = lua_tonumber(L, -1);
        lua_pop(L, 1);
      }
    }
    bool served = false;
    const smi::surrogate::kriging::SequentialResult r = smi::surrogate::kriging::sequential_design(design, candidates, weights, [&](const Eigen::MatrixXd& X) {
      if (!served) {
        served = true;
        return Y0;
      }
      return model.fn(X);
    }, so);
    const auto& outs = *model.outputs;
    lua_createtable(L, 0, 6);
    lua::push_mat(L, r.X);
    lua_setfield(L, -2, "X");
    lua_createtable(L, 0, static_cast<int>(outs.size()));
    for (std::size_t j = 0; j < outs.size(); ++j) {
      lua::push_vec(L, r.Y.col(static_cast<Eigen::Index>(j)));
      lua_setfield(L, -2, outs[j].c_str());
    }
    lua_setfield(L, -2, "Y");
    lua_createtable(L, 0, static_cast<int>(outs.size()));
    for (std::size_t j = 0; j < outs.size(); ++j) {
      KrigingBox box;
      box.model = r.models[j];
      box.inputs = input_names;
      box.output = outs[j];
      lua::push_box(L, kKrigingType, std::move(box));
      lua_setfield(L, -2, outs[j].c_str());
    }
    lua_setfield(L, -2, "kriging");
    lua_createtable(L, static_cast<int>(r.history.size()), 0);
    for (std::size_t i = 0; i < r.history.size(); ++i) {
      const auto& h = r.history[i];
      lua_createtable(L, 0, 3);
      lua::set_integer(L, "points", static_cast<lua_Integer>(h.points));
      for (const char* key : {"q2", "rmse"}) {
        const Eigen::VectorXd& v = key[0] == 'q' ? h.q2 : h.rmse;
        lua_createtable(L, 0, static_cast<int>(outs.size()));
        for (std::size_t j = 0; j < outs.size(); ++j) lua::set_number(L, outs[j].c_str(), v(static_cast<Eigen::Index>(j)));
        lua_setfield(L, -2, key);
      }
      lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
    }
    lua_setfield(L, -2, "history");
    lua_pushboolean(L, r.reached);
    lua_setfield(L, -2, "reached");
    lua::set_string(L, "stop", r.stop);
    return 1;
  });
}

}  // namespace

void open_sequential(lua_State* L) {  // after open_kriging: a field of smi.kriging
  lua_getfield(L, -1, "kriging");
  lua_pushcfunction(L, sequential_call);
  lua_setfield(L, -2, "sequential");
  lua_pop(L, 1);
}

}  // namespace smi::bind::surrogate
