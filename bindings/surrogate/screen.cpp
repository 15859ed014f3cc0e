// smi.screen{model =, inputs =, n = 10000, seed =, fix = "mean"|"median", sobol = true,
//            bootstrap = 200, level = 0.95, output =, order =}
// -> a ranked table (one per output; with several outputs and no `output`, a table of them by
// name): rows {input, e, ne, rank, s1, s1_lo, s1_hi, st, st_lo, st_hi}, sorted by rank, plus
// fields output, n, variance, warnings; tostring() prints it as an aligned table.
#include <cstdio>
#include <string>

#include "luax/luax.hpp"
#include "luax/policy.hpp"
#include "surrogate/model_arg.hpp"
#include "surrogate/screen.hpp"

namespace smi::bind::surrogate {
namespace {

constexpr const char* kScreenMeta = "smi.ScreenResult";

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

void push_result(lua_State* L, const screen::Result& r, lua_Integer n) {
  lua_createtable(L, static_cast<int>(r.rows.size()), 5);
  for (std::size_t i = 0; i < r.rows.size(); ++i) {
    const screen::Row& w = r.rows[i];
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
    lua_rawseti(L, -2, static_cast<lua_Integer>(i + 1));
  }
  lua::set_string(L, "output", r.output);
  lua::set_integer(L, "n", n);
  lua::set_number(L, "variance", r.variance);
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
  lua::Options o(L, 1, fname);
  o.check_known({"model", "inputs", "n", "seed", "fix", "sobol", "bootstrap", "level", "output", "order", "grid"});
  auto [model, model_idx, inputs] = read_model_and_inputs(L, o, fname);
  screen::Options so;
  so.n = static_cast<Eigen::Index>(o.integer("n", 10000));
  so.seed = static_cast<std::uint64_t>(o.integer("seed", static_cast<lua_Integer>(lua::policy(L).seed)));
  so.fix = o.string("fix", "mean");
  so.sobol = o.boolean("sobol", true);
  so.bootstrap = static_cast<int>(o.integer("bootstrap", 200));
  so.level = o.number("level", 0.95);
  so.grid = static_cast<Eigen::Index>(o.integer("grid", 4001));
  const std::optional<std::string> want = o.string("output");
  return lua::protect(L, fname, [&] {
    const std::vector<screen::Result> res = screen::screen(inputs, model.fn, *model.outputs, so);
    if (want) {
      for (const auto& r : res)
        if (r.output == *want) {
          push_result(L, r, so.n);
          return 1;
        }
      throw InvalidArgument("the model has no output '" + *want + "'");
    }
    if (res.size() == 1) {
      push_result(L, res[0], so.n);
      return 1;
    }
    lua_createtable(L, 0, static_cast<int>(res.size()));
    for (const auto& r : res) {
      push_result(L, r, so.n);
      lua_setfield(L, -2, r.output.c_str());
    }
    return 1;
  });
}

}  // namespace

void open_screen(lua_State* L) {
  luaL_newmetatable(L, kScreenMeta);
  lua_pushcfunction(L, screen_tostring);
  lua_setfield(L, -2, "__tostring");
  lua::protect_metatable(L, -1, kScreenMeta);
  lua_pop(L, 1);
  lua_pushcfunction(L, screen_call);
  lua_setfield(L, -2, "screen");
}

}  // namespace smi::bind::surrogate
