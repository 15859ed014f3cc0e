// SPDX-License-Identifier: MIT
// smi.screen{model =, inputs =, n = 10000, seed =, fix = "mean"|"median", sobol = true,
//            bootstrap = 200, level = 0.95, output =, order =,
//            method = "full"|"surrogate", runs = 300, basis = "quadratic"|"linear", q2_min = 0.9,
//            delta = true, classes = 0}
// method = "surrogate" runs the model `runs` times only, fits a ridge polynomial per
// output and screens that: the result adds method, runs (model runs), q2, r2, lambda, terms,
// delta_floor, delta_classes and a `delta` (Borgonovo, from the runs) in every row.
// -> a ranked table (one per output; with several outputs and no `output`, a table of them by
// name): rows {input, e, ne, rank, s1, s1_lo, s1_hi, st, st_lo, st_hi}, sorted by rank, plus
// fields output, n, variance, warnings; tostring() prints it as an aligned table.
#include <cstdio>
#include <string>

#include "bindings/surrogate/model_arg.hpp"
#include "bindings/surrogate/open_parts.hpp"
#include "bindings/surrogate/screen_options.hpp"
#include "kernels/surrogate/screen.hpp"
#include "kernels/surrogate/screen_surrogate.hpp"
#include "luax/luax.hpp"
#include "luax/run_context.hpp"
#include "luax/policy.hpp"

namespace smi::bind::surrogate {
namespace {

constexpr const char* kScreenMeta = "smi.screen_result";

int screen_tostring(lua_State* L) {
  luaL_checktype(L, 1, LUA_TTABLE);
  std::string out;
  char line[256];
  lua_getfield(L, 1, "output");
  lua_getfield(L, 1, "n");
  std::snprintf(line, sizeof line, "screening of '%s' (n = %lld, PDF-area index N_e; Sobol' S1/ST with CIs)\n",
                lua_tostring(L, -2) ? lua_tostring(L, -2) : "?", static_cast<long long>(lua_tointeger(L, -1)));
  lua_pop(L, 2);
  out += line;
  lua_getfield(L, 1, "q2");
  lua_getfield(L, 1, "runs");
  if (lua_isnumber(L, -2)) {  // method = "surrogate": say what the indices were computed on
    std::snprintf(line, sizeof line, "on a ridge polynomial of %lld model runs, leave-one-out Q2 = %.4f\n",
                  static_cast<long long>(lua_tointeger(L, -1)), lua_tonumber(L, -2));
    out += line;
  }
  lua_pop(L, 2);
  std::snprintf(line, sizeof line, "%4s  %-16s %9s %8s %22s %22s\n", "rank", "input", "e", "N_e", "S1 [CI]", "ST [CI]");
  out += line;
  const lua_Integer len = static_cast<lua_Integer>(lua_rawlen(L, 1));
  for (lua_Integer i = 1; i <= len; ++i) {
    lua_rawgeti(L, 1, i);
    auto num = [&](const char* k) {
      lua_getfield(L, -1, k);
      const double v = lua_tonumber(L, -1);
      lua_pop(L, 1);
      return v;
    };
    lua_getfield(L, -1, "input");
    const std::string name = lua_tostring(L, -1) ? lua_tostring(L, -1) : "?";
    lua_pop(L, 1);
    char s1[64], st[64];
    std::snprintf(s1, sizeof s1, "%.3f [%.3f, %.3f]", num("s1"), num("s1_lo"), num("s1_hi"));
    std::snprintf(st, sizeof st, "%.3f [%.3f, %.3f]", num("st"), num("st_lo"), num("st_hi"));
    std::snprintf(line, sizeof line, "%4d  %-16s %9.5f %8.4f %22s %22s\n", static_cast<int>(num("rank")),
                  name.c_str(), num("e"), num("ne"), s1, st);
    out += line;
    lua_pop(L, 1);
  }
  lua_pushstring(L, out.c_str());
  return 1;
}

void push_result(lua_State* L, const smi::surrogate::screen::Result& r, lua_Integer n,
                 const smi::surrogate::screen::SurrogateFitInfo* fit = nullptr, const std::vector<smi::surrogate::propagate::Input>* inputs = nullptr,
                 lua_Integer runs = 0) {
  lua_createtable(L, static_cast<int>(r.rows.size()), 5);
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const smi::surrogate::screen::Row& w = r.rows[i];
    lua_createtable(L, 0, 10);
    lua::set_string(L, "input", w.input);
    lua::set_number(L, "e", w.e);
    lua::set_number(L, "ne", w.ne);
    lua::set_integer(L, "rank", w.rank);
    lua::set_number(L, "s1", w.s1);
    lua::set_number(L, "s1_lo", w.s1_lo);
    lua::set_number(L, "s1_hi", w.s1_hi);
    lua::set_number(L, "st", w.st);
    lua::set_number(L, "st_lo", w.st_lo);
    lua::set_number(L, "st_hi", w.st_hi);
    if (fit && inputs && fit->delta.size() == static_cast<Eigen::Index>(inputs->size()))
      for (std::size_t j = 0; j < inputs->size(); ++j)
        if ((*inputs)[j].name == w.input) lua::set_number(L, "delta", fit->delta(static_cast<Eigen::Index>(j)));
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua::set_string(L, "output", r.output);
  lua::set_integer(L, "n", n);
  lua::set_number(L, "variance", r.variance);
  lua::set_string(L, "method", fit ? "surrogate" : "full");
  if (fit) {
    lua::set_integer(L, "runs", runs);
    lua::set_number(L, "q2", fit->q2);
    lua::set_number(L, "r2", fit->r2);
    lua::set_number(L, "lambda", fit->lambda);
    lua::set_integer(L, "terms", static_cast<lua_Integer>(fit->terms));
    if (fit->delta.size() > 0) {
      lua::set_number(L, "delta_floor", fit->delta_floor);
      lua::set_integer(L, "delta_classes", static_cast<lua_Integer>(fit->delta_classes));
    }
  }
  lua_createtable(L, static_cast<int>(r.warnings.size()), 0);
  for (std::size_t i = 0; i < r.warnings.size(); ++i) {
    lua_pushstring(L, r.warnings[i].c_str());
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua_setfield(L, -2, "warnings");
  // by_input[name] = row, for lookups without scanning
  lua_createtable(L, 0, static_cast<int>(r.rows.size()));
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    lua_rawgeti(L, -2, static_cast<lua_Integer>(i + 1));
    lua_setfield(L, -2, r.rows[i].input.c_str());
  }
  lua_setfield(L, -2, "by_input");
  luaL_setmetatable(L, kScreenMeta);
}

int screen_call(lua_State* L) {
  constexpr const char* fname = "smi.screen";
  luaL_checktype(L, 1, LUA_TTABLE);
  // The model first: it stays on the stack while the options are read (their __index may run
  // any Lua code, tests/lua/test_lifetimes.lua).
  const lua::Options o(L, 1, fname);  // model, inputs, order: read_model_and_inputs
  auto [model, model_idx, inputs] = read_model_and_inputs(L, o, fname);
  ScreenArgs args;
  args.full.seed = lua::run_context(L).seed;
  screen_schema().read(L, 1, args);
  const smi::surrogate::screen::Options& so = args.full;
  const smi::surrogate::screen::SurrogateOptions& sso = args.surrogate;
  const std::optional<std::string>& want = args.output;
  const std::string& method = args.method;
  const bool surrogate = method == "surrogate";
  std::string misplaced;  // a surrogate-only option given to the full screening
  if (!surrogate)
    for (const char* k : {"runs", "basis", "q2_min", "delta", "classes"}) {
      lua_getfield(L, 1, k);
      if (!lua_isnil(L, -1) && misplaced.empty()) misplaced = k;
      lua_pop(L, 1);
    }
  return lua::protect(L, fname, [&] {
    if (method != "full" && method != "surrogate")
      throw InvalidArgument("method must be \"full\" or \"surrogate\", got '" + method + "'");
    if (!misplaced.empty())
      throw InvalidArgument("'" + misplaced + "' applies to method = \"surrogate\" only");
    std::vector<smi::surrogate::screen::Result> res;
    std::vector<smi::surrogate::screen::SurrogateFitInfo> fits;
    if (surrogate) {
      smi::surrogate::screen::SurrogateResult sr = smi::surrogate::screen::screen_surrogate(inputs, model.fn, *model.outputs, so, sso);
      res = std::move(sr.screening);
      fits = std::move(sr.fits);
    } else {
      res = smi::surrogate::screen::screen(inputs, model.fn, *model.outputs, so);
    }
    auto push = [&](std::size_t i) {
      if (surrogate)
        push_result(L, res[i], so.n, &fits[i], &inputs, static_cast<lua_Integer>(sso.runs));
      else
        push_result(L, res[i], so.n);
    };
    if (want) {
      for (std::size_t i = 0; i < res.size(); ++i)
        if (res[i].output == *want) {
          push(i);
          return 1;
        }
      throw InvalidArgument("the model has no output '" + *want + "'");
    }
    if (res.size() == 1) {
      push(0);
      return 1;
    }
    lua_createtable(L, 0, static_cast<int>(res.size()));
    for (std::size_t i = 0; i < res.size(); ++i) {
      push(i);
      lua_setfield(L, -2, res[i].output.c_str());
    }
    return 1;
  });
}

}  // namespace

void open_screen(lua_State* L) {
  const luaL_Reg meta[] = {{"__tostring", screen_tostring}, {nullptr, nullptr}};
  lua::register_table_type(L, kScreenMeta, nullptr, meta);
  lua_pushcfunction(L, screen_call);
  lua_setfield(L, -2, "screen");
}

}  // namespace smi::bind::surrogate
