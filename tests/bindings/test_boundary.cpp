// SPDX-License-Identifier: MIT
// Errors across the C++/Lua boundary, on a real sandboxed
// runtime: a kernel exception becomes a Lua error with its message and the script's file:line;
// an error raised in a Lua callback called from C++ keeps its message; no C++ destructor is
// skipped while a Lua error unwinds C++ frames (we link Debian's C++ build of Lua).
#include <catch2/catch.hpp>

#include <string>

#include "app/runtime.hpp"
#include "bindings/doc.hpp"
#include "bindings/modules.hpp"
#include "luax/luax.hpp"
#include "platform/core/descriptive.hpp"

namespace {

int g_alive = 0;  // live Counted objects
struct Counted {
  Counted() { ++g_alive; }
  ~Counted() { --g_alive; }
  Counted(const Counted&) = delete;
  Counted& operator=(const Counted&) = delete;
};

/// kernel_quantile(p): a real kernel (type-7 quantile) that throws InvalidArgument for p > 1.
int kernel_quantile(lua_State* L) {
  const double p = luaL_checknumber(L, 1);
  return smi::lua::protect(L, "test.quantile", [&] {
    Counted guard;
    Eigen::VectorXd x(3);
    x << 1, 2, 3;
    lua_pushnumber(L, smi::quantile(x, p));
    return 1;
  });
}

/// check_after_guard(x): a Counted object is alive when luaL_checknumber raises.
int check_after_guard(lua_State* L) {
  Counted guard;
  std::string text = "a string that owns heap memory, to be freed on unwind too";
  lua_pushnumber(L, luaL_checknumber(L, 1) + static_cast<double>(text.size()));
  return 1;
}

/// apply(f, x): calls the Lua function f from C++ the way kernels call objectives
/// (smi::lua::call = pcall + traceback -> LuaError), with a Counted object alive.
int apply(lua_State* L) {
  luaL_checktype(L, 1, LUA_TFUNCTION);
  const double x = luaL_checknumber(L, 2);
  return smi::lua::protect(L, "test.apply", [&] {
    Counted guard;
    lua_pushvalue(L, 1);
    lua_pushnumber(L, x);
    smi::lua::call(L, 1, 1);
    const double y = lua_tonumber(L, -1);
    lua_pop(L, 1);
    lua_pushnumber(L, 2 * y);
    return 1;
  });
}

/// raw_call(f): calls f with lua_call (no pcall) while a Counted object is alive in this frame.
int raw_call(lua_State* L) {
  Counted guard;
  lua_pushvalue(L, 1);
  lua_call(L, 0, 0);
  return 0;
}

struct Fixture {
  smi::app::Runtime rt{smi::app::Config{}, {luaopen_smi, smi::bind::binding_docs}};
  lua_State* L = rt.state();
  Fixture() {
    lua_register(L, "kernel_quantile", kernel_quantile);
    lua_register(L, "check_after_guard", check_after_guard);
    lua_register(L, "apply", apply);
    lua_register(L, "raw_call", raw_call);
    g_alive = 0;
  }
  /// Runs `code` as chunk "@study.lua" in protected mode; returns "" or the error message.
  std::string run(const std::string& code) {
    const int top = lua_gettop(L);
    if (luaL_loadbufferx(L, code.data(), code.size(), "@study.lua", "t") != LUA_OK) FAIL(lua_tostring(L, -1));
    std::string err;
    if (lua_pcall(L, 0, 0, 0) != LUA_OK) err = lua_tostring(L, -1) ? lua_tostring(L, -1) : "(non-string)";
    lua_settop(L, top);
    return err;
  }
};

}  // namespace

TEST_CASE_METHOD(Fixture, "a kernel exception becomes a Lua error with its message and the script's file:line") {
  CHECK(run("assert(kernel_quantile(0.5) == 2)") == "");
  const std::string err = run("local a = 1\n\nlocal q = kernel_quantile(1.5)\n");
  CHECK(err == "study.lua:3: test.quantile: probability must be in [0, 1], got 1.5");
  CHECK(g_alive == 0);
  // the same through a real binding
  const std::string err2 = run("local v = smi.vec{1, 2, 3}\nreturn v:quantile(-0.5)");
  CHECK(err2.rfind("study.lua:2: ", 0) == 0);
  CHECK(err2.find("probability must be in [0, 1], got -0.5") != std::string::npos);
  // and the state is sound afterwards
  CHECK(run("assert(smi.vec{1, 2, 3}:quantile(0.5) == 2)") == "");
}

TEST_CASE_METHOD(Fixture, "an error raised in a Lua callback called from C++ keeps its message") {
  CHECK(run("assert(apply(function(x) return x + 1 end, 2) == 6)") == "");
  const std::string err = run(
      "local function objective(x)\n"
      "  error(('objective exploded at x=%g'):format(x))\n"
      "end\n"
      "apply(objective, 3)\n");
  INFO(err);
  CHECK(err.rfind("study.lua:4: test.apply: study.lua:2: objective exploded at x=3", 0) == 0);
  CHECK(err.find("stack traceback") != std::string::npos);  // smi::lua::call adds the callback's traceback
  CHECK(g_alive == 0);

  // directly: smi::lua::call throws LuaError carrying the message, and balances the stack
  const int top = lua_gettop(L);
  luaL_loadstring(L, "error({}) ");
  CHECK_THROWS_WITH(smi::lua::call(L, 0, 0), Catch::Contains("error object is a table value"));
  luaL_loadstring(L, "local t = nil; return t.field");
  CHECK_THROWS_AS(smi::lua::call(L, 0, 0), smi::lua::LuaError);
  CHECK(lua_gettop(L) == top);
}

TEST_CASE_METHOD(Fixture, "no C++ destructor is skipped when a Lua error unwinds C++ frames") {
  SECTION("luaL_checknumber raises while an object is alive in the bound function") {
    const std::string err = run("check_after_guard('not a number')");
    CHECK(err.find("bad argument #1 to 'check_after_guard' (number expected, got string)") != std::string::npos);
    CHECK(g_alive == 0);
  }
  SECTION("a kernel exception inside protect") {
    run("kernel_quantile(7)");
    CHECK(g_alive == 0);
  }
  SECTION("a Lua error from a callback called with lua_call (no pcall) through a C++ frame") {
    const std::string err = run("raw_call(function() error('deep failure') end)");
    CHECK(err == "study.lua:1: deep failure");
    CHECK(g_alive == 0);
  }
  SECTION("nested: Lua -> C++ -> Lua -> C++ raising, unwound to the outer pcall") {
    const std::string err = run("raw_call(function() raw_call(function() check_after_guard({}) end) end)");
    CHECK(err.find("number expected, got table") != std::string::npos);
    CHECK(g_alive == 0);
  }
  SECTION("many times over: no leak of live objects") {
    for (int i = 0; i < 1000; ++i) run("pcall(check_after_guard, nil); raw_call(function() error('x') end)");
    CHECK(g_alive == 0);
  }
}

TEST_CASE("the runtime reports a kernel error with the script's location and exits 1") {
  smi::app::Runtime rt{smi::app::Config{}, {luaopen_smi, smi::bind::binding_docs}};
  lua_register(rt.state(), "kernel_quantile", kernel_quantile);
  CHECK(rt.run_string("kernel_quantile(2)", "=study") == 1);
  CHECK(rt.run_string("kernel_quantile(1)", "=study") == 0);
  CHECK(rt.run_string("os.exit(7)", "=study") == 7);
  CHECK(rt.exit_requested());
}

TEST_CASE("a boxed C++ object is destroyed by __gc and by __close, exactly once") {
  g_alive = 0;
  {
    smi::app::Runtime rt{smi::app::Config{}, {luaopen_smi, smi::bind::binding_docs}};
    lua_State* L = rt.state();
    static const luaL_Reg no_methods[] = {{nullptr, nullptr}};
    smi::lua::register_type<Counted>(L, "test.Counted", no_methods);
    lua_pushcfunction(L, [](lua_State* L) -> int {
      smi::lua::new_box<Counted>(L, "test.Counted") = new Counted();
      return 1;
    });
    lua_setglobal(L, "new_counted");
    CHECK(rt.run_string("keep = new_counted(); local tmp = new_counted()", "=t") == 0);
    CHECK(g_alive == 2);
    CHECK(rt.run_string("collectgarbage(); collectgarbage()", "=t") == 0);
    CHECK(g_alive == 1);  // tmp collected, keep alive
    CHECK(rt.run_string("do local c <close> = new_counted() end", "=t") == 0);
    CHECK(g_alive == 1);  // closed at the end of the block
    // Scripts never see the metatable: getmetatable gives a copy without finalizers.
    CHECK(rt.run_string("local mt = getmetatable(new_counted()) assert(mt.__name == 'test.Counted' and not mt.__gc "
                        "and not mt.__close) collectgarbage() collectgarbage()",
                        "=t") == 0);
    CHECK(g_alive == 1);
    // Through the C API: __close then __gc deletes once; either on another type raises.
    REQUIRE(luaL_dostring(L, "return new_counted(), smi.vec{1}") == LUA_OK);  // [c, v]
    for (const char* mm : {"__close", "__gc"}) {
      luaL_getmetatable(L, "test.Counted");
      lua_getfield(L, -1, mm);
      lua_pushvalue(L, -4);  // c
      CHECK(lua_pcall(L, 1, 0, 0) == LUA_OK);
      lua_getfield(L, -1, mm);
      lua_pushvalue(L, -3);  // v: another type
      REQUIRE(lua_pcall(L, 1, 0, 0) != LUA_OK);
      CHECK(std::string(lua_tostring(L, -1)).find("test.Counted expected, got smi.vec") != std::string::npos);
      lua_pop(L, 2);  // message, metatable
    }
    lua_pop(L, 2);
    CHECK(g_alive == 1);  // closing twice deletes once
    // a wrong userdata names both types
    REQUIRE(luaL_dostring(L, "local v = smi.vec{1}; v.sum(keep)") != LUA_OK);
    CHECK(std::string(lua_tostring(L, -1)).find("bad argument #1 to 'sum' (smi.vec expected, got test.Counted)") !=
          std::string::npos);
    lua_pop(L, 1);
  }
  CHECK(g_alive == 0);  // lua_close collects the rest
}
