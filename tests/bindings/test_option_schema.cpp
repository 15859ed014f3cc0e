// SPDX-License-Identifier: MIT
// The option schema (host/luax/option_schema.hpp) on a real lua_State: an unknown key
// names the key, the function and the closest key; a wrong type names the key, the expected and
// the given type; a value out of range names the range; every schema of the bindings reads an
// empty table into a struct equal to the default-constructed one, and its reference lines show
// the struct's defaults.
#include <catch2/catch.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>
#include <vector>

#include "bindings/doc.hpp"
#include "bindings/improve/calibrate_options.hpp"
#include "bindings/stats/kde_options.hpp"
#include "luax/doc_text.hpp"
#include "luax/option_schema.hpp"

namespace {

using namespace smi::lua;

enum class Mode { a, b };

struct TestOptions {
  double tol = 0.25;
  int n = 3;
  std::string rule = "x";
  Mode mode = Mode::a;
  bool flag = false;
  struct Inner {
    double step = 1e-3;
  } inner;
};

const Schema<TestOptions>& test_schema() {
  using S = TestOptions;
  static const Schema<S> s("test.fn", {
      number<S>("tol", &S::tol, open(0, 1), "a tolerance"),
      integer<S>("n", &S::n, between(1, 64), "a count"),
      string<S>("rule", &S::rule, {"x", "y"}, "a rule"),
      choice<S>("mode", &S::mode, Names<Mode>{{"a", Mode::a}, {"b", Mode::b}}, "a mode"),
      boolean<S>("flag", &S::flag, "a flag\nover two lines"),
      number<S>("step", [](auto& s) -> auto& { return s.inner.step; }, above(0), "a nested member"),
      by_hand<S>("data", "(required)", "read by the binding"),
  });
  return s;
}

TestOptions g_read;  // what the last read_lua() read

/// read(opts): reads the options table with the test schema (a Lua error on bad options).
int read_lua(lua_State* L) {
  g_read = test_schema().read(L, 1);
  return 0;
}

struct State {
  lua_State* L = luaL_newstate();
  ~State() { lua_close(L); }
  /// Runs read(<table>) from Lua source; returns "" or the error message.
  std::string read(const std::string& table) {
    lua_pushcfunction(L, read_lua);
    lua_setglobal(L, "read");
    if (luaL_dostring(L, ("read(" + table + ")").c_str()) == LUA_OK) return "";
    std::string msg = lua_tostring(L, -1);
    lua_pop(L, 1);
    // the position of the calling chunk comes first: [string "read(...)"]:1:
    if (const auto at = msg.find("]:1: "); at != std::string::npos) msg.erase(0, at + 5);
    return msg;
  }
};

bool has(const std::string& text, const std::string& part) { return text.find(part) != std::string::npos; }

}  // namespace

TEST_CASE("option schema: values are read into the struct's members, nested ones too") {
  State s;
  REQUIRE(s.read("{tol = 0.5, n = 7, rule = 'y', mode = 'b', flag = true, step = 0.01, data = {1}}").empty());
  CHECK(g_read.tol == 0.5);
  CHECK(g_read.n == 7);
  CHECK(g_read.rule == "y");
  CHECK(g_read.mode == Mode::b);
  CHECK(g_read.flag);
  CHECK(g_read.inner.step == 0.01);
  REQUIRE(s.read("nil").empty());
  CHECK(g_read.tol == TestOptions{}.tol);
}

TEST_CASE("option schema: an unknown key names the key, the function and the closest key") {
  State s;
  CHECK(s.read("{tool = 0.5}") == "test.fn: unknown option 'tool' (did you mean 'tol'?)");
  const std::string far = s.read("{zzzzzz = 1}");
  CHECK(has(far, "test.fn: unknown option 'zzzzzz'; known options: tol, n, rule, mode, flag, step, data"));
  // a real binding's schema: smi.kde
  lua_State* L = s.L;
  lua_newtable(L);
  lua_pushnumber(L, 0.2);
  lua_setfield(L, -2, "bandwith");
  lua_pushcfunction(L, [](lua_State* L) {
    smi::bind::stats::kde_schema().read(L, 1);
    return 0;
  });
  lua_insert(L, -2);
  REQUIRE(lua_pcall(L, 1, 0, 0) != LUA_OK);
  CHECK(std::string(lua_tostring(L, -1)) == "smi.kde: unknown option 'bandwith' (did you mean 'bandwidth'?)");
}

TEST_CASE("option schema: a wrong type names the key, the expected type and the given one") {
  State s;
  CHECK(s.read("{tol = 'small'}") == "test.fn: option 'tol' must be a number, got string");
  CHECK(s.read("{n = 2.5}") == "test.fn: option 'n' must be an integer, got number");
  CHECK(s.read("{rule = 1}") == "test.fn: option 'rule' must be a string, got number");
  CHECK(s.read("{flag = 'yes'}") == "test.fn: option 'flag' must be a boolean, got string");
  CHECK(s.read("7") == "test.fn: options must be a table, got number");
}

TEST_CASE("option schema: a value out of range or not among the choices names the range") {
  State s;
  CHECK(s.read("{tol = 1}") == "test.fn: tol must be in (0, 1), got 1");
  CHECK(has(s.read("{tol = 0/0}"), "test.fn: tol must be in (0, 1), got "));  // nan or -nan
  CHECK(s.read("{n = 0}") == "test.fn: n must be in 1..64, got 0");
  CHECK(s.read("{step = 0}") == "test.fn: step must be > 0, got 0");
  CHECK(s.read("{rule = 'z'}") == "test.fn: rule must be \"x\" or \"y\", got \"z\"");
  CHECK(s.read("{mode = 'c'}") == "test.fn: mode must be \"a\" or \"b\", got \"c\"");
}

TEST_CASE("option schema: finite ranges refuse NaN and the infinities, any_value takes them") {
  using smi::lua::Range;
  const double inf = std::numeric_limits<double>::infinity(), nan = std::nan("");
  CHECK(smi::lua::any_value().contains(nan));
  CHECK(smi::lua::any_value().contains(-inf));
  CHECK_FALSE(smi::lua::finite().contains(nan));
  CHECK_FALSE(smi::lua::finite().contains(inf));
  CHECK_FALSE(smi::lua::finite().contains(-inf));
  CHECK(smi::lua::finite().contains(-1e300));
  CHECK(smi::lua::finite().text(false) == "a finite number");
  CHECK_FALSE(smi::lua::finite_above(0).contains(0.0));
  CHECK_FALSE(smi::lua::finite_above(0).contains(inf));
  CHECK(smi::lua::finite_above(0).contains(1e-300));
  CHECK(smi::lua::finite_above(0).text(false) == "> 0");
  CHECK(smi::lua::finite_at_least(0).contains(0.0));
  CHECK_FALSE(smi::lua::finite_at_least(0).contains(inf));
  CHECK_FALSE(smi::lua::at_least(0).contains(nan));
}

TEST_CASE("option schema: the reference lines show the struct's defaults") {
  const std::string doc = test_schema().doc();
  CHECK(has(doc, "  tol = 0.25"));
  CHECK(has(doc, "  rule = \"x\""));
  CHECK(has(doc, "  mode = \"a\""));
  CHECK(has(doc, "  step = 0.001"));
  CHECK(has(doc, "  data = (required)"));
  CHECK(has(doc, "-- a flag\n"));
  CHECK(has(doc, "-- over two lines"));
  // a binding: smi.kde's tol and smi.calibrate's xtol_rel are their structs' defaults
  CHECK(has(smi::bind::stats::kde_schema().doc(), "  tol = " + num(smi::stats::KdeOptions{}.binned_tol) + " "));
  CHECK(has(smi::bind::improve::calibrate_schema().doc(), "  xtol_rel = " + num(smi::improve::OptimizerOptions{}.xtol_rel) + " "));
}

TEST_CASE("every binding schema reads an empty table into its default-constructed struct") {
  (void)smi::bind::binding_docs();  // builds every schema the reference lists
  const auto all = schemas();
  std::vector<std::string> names;
  for (const SchemaBase* sb : all) names.emplace_back(sb->name());
  INFO("schemas: " << names.size());
  CHECK(all.size() >= 6);
  // the loop below picks up each new schema that a reference entry lists, e.g. the solver models'
  for (const char* f : {"smi.model.command", "smi.model.batch", "smi.metric.pr", "smi.metric.intersection", "smi.metric.pr grid",
                        "smi.calibrate bootstrap", "smi.calibrate identifiability", "smi.calibrate intervals",
                        "smi.calibrate prior", "smi.dist.normal", "smi.dist.gamma"})
    CHECK(std::find(names.begin(), names.end(), f) != names.end());
  State s;
  for (const SchemaBase* sb : all) {
    INFO(sb->name());
    CHECK(sb->default_mismatches(s.L).empty());
    CHECK(!sb->keys().empty());
    for (const auto& k : sb->keys()) CHECK(has(sb->doc(), "  " + k + " = "));
  }
}
