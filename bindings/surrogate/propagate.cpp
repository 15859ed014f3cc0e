// SPDX-License-Identifier: MIT
// smi.propagate{model =, inputs =, n =, seed = [, order =]} -> {output = vec, ...}, X
// Common random numbers: each input's column is its quantile of a fixed uniform column
// (surrogate/propagate.hpp), and the model gets the whole sample in one call.
#include "bindings/surrogate/model_arg.hpp"
#include "bindings/surrogate/open_parts.hpp"
#include "bindings/surrogate/propagate_options.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/memory.hpp"
#include "luax/policy.hpp"

#include <cmath>
#include <fmt/format.h>

namespace smi::bind::surrogate {
namespace {

int propagate_call(lua_State* L) {
  constexpr const char* fname = "smi.propagate";
  luaL_checktype(L, 1, LUA_TTABLE);
  // The model first: it stays on the stack while the options are read (their __index may run
  // any Lua code, tests/lua/test_lifetimes.lua).
  const lua::Options o(L, 1, fname);  // model, inputs, order: read_model_and_inputs
  auto [model, model_idx, inputs] = read_model_and_inputs(L, o, fname);
  PropagateArgs args;
  args.seed = lua::run_context(L).seed;
  propagate_schema().read(L, 1, args);
  const lua_Integer n = args.n;
  const std::uint64_t seed = args.seed;
  return lua::protect(L, fname, [&] {
    // The sample (and its uniforms while drawn) and the outputs, before any of it exists.
    lua::require_room(L, static_cast<double>(n) * (2.0 * static_cast<double>(inputs.size()) + 1), sizeof(double),
                      "the sample");
    Eigen::MatrixXd X = smi::surrogate::propagate::crn_sample(inputs, n, seed);
    const Eigen::MatrixXd Y = model.fn(X);
    if (Y.rows() != X.rows()) throw DimensionMismatch("the model returned " + std::to_string(Y.rows()) + " rows for " + std::to_string(X.rows()) + " points");
    // A NaN passed on would make every statistic of the output NaN, or be dropped silently by
    // a KDE: name the first bad sample, its inputs, and how many there are.
    Eigen::Index bad = 0, first_i = -1, first_j = -1;
    for (Eigen::Index i = 0; i < Y.rows(); ++i)
      for (Eigen::Index j = 0; j < Y.cols(); ++j)
        if (!std::isfinite(Y(i, j)) && bad++ == 0) first_i = i, first_j = j;
    if (bad > 0) {
      std::string at;
      for (std::size_t c = 0; c < inputs.size(); ++c)
        at += fmt::format("{}{} = {}", c ? ", " : "", inputs[c].name, X(first_i, static_cast<Eigen::Index>(c)));
      const auto& outs = *model.outputs;
      const std::string out = static_cast<std::size_t>(first_j) < outs.size() ? outs[static_cast<std::size_t>(first_j)]
                                                                              : std::to_string(first_j + 1);
      throw InvalidArgument(fmt::format("the model returned {} for output '{}' at sample {} ({}); {} non-finite "
                                        "value{} in all. Fix the model there (or its inputs' ranges): propagation "
                                        "does not pass NaN or infinity on",
                                        std::isnan(Y(first_i, first_j)) ? "NaN" : fmt::format("{}", Y(first_i, first_j)),
                                        out, first_i + 1, at, bad, bad == 1 ? "" : "s"));
    }
    lua::push_named_vectors(L, *model.outputs, Y);
    lua::push_mat(L, std::move(X));
    return 2;
  });
}

}  // namespace

void open_propagate(lua_State* L) {
  lua_pushcfunction(L, propagate_call);
  lua_setfield(L, -2, "propagate");
}

}  // namespace smi::bind::surrogate
