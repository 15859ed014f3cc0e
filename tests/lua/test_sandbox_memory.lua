-- SPDX-License-Identifier: MIT
-- A script cannot free what C++ is still using, and options it sets are capped by the machine
--. Each case crashed or corrupted memory on the build before the fix
-- (double free, use-after-free, segfault, SIGFPE) or gave a meaningless message.
local T = require "smi.testing"

local S1 = {{0}, {0.2}, {0.45}, {0.7}, {1.0}}
local Y1 = {}
for i, r in ipairs(S1) do Y1[i] = r[1] + math.sin(5 * r[1]) end

T.case("getmetatable hides every smi metatable and its finalizers", function()
  local k = smi.kriging.fit(S1, Y1, {theta = {1}})
  local objects = {smi.vec{1}, smi.mat{{1}}, smi.kde{1, 2, 3, 4}, smi.rng(1), k,
                   smi.model.lua{inputs = {"x"}, outputs = {"y"}, fn = function(X) return {y = X:col(1)} end}}
  for _, o in ipairs(objects) do
    local mt = getmetatable(o)
    T.eq(type(mt), "table")
    T.eq(mt.__gc, nil); T.eq(mt.__close, nil)
    T.truthy(type(mt.__name) == "string" and mt.__name:find("^smi%."), "the type name stays readable")
    mt.__index = function() return "hijacked" end  -- changes the copy only
  end
  T.eq(getmetatable(smi.vec{1}).__name, "smi.vec")
  T.eq(smi.vec{1, 2}:sum(), 3)
end)

T.case("one type's finalizer cannot be called on another (was a double free)", function()
  -- getmetatable gives a string, so there is no __gc to call
  T.raises(function() getmetatable(smi.vec{1}).__gc(smi.kde{1, 2, 3, 4}) end, "attempt to call a nil value")
end)

T.case("<close> on a vec inside its own map callback (was a use-after-free)", function()
  local v = smi.vec{1, 2, 3}
  local r = v:map(function(x)
    local c <close> = v
    return 10 * x
  end)
  T.eq(r[1], 10); T.eq(r[2], 20); T.eq(r[3], 30)  -- map read v to the end
  T.raises(function() return v:sum() end, "smi.vec is closed")
  T.raises(function() return smi.vec(v) end, "smi.vec is closed")
end)

T.case("an option table's __index that closes the Kriging during predict (was a use-after-free)", function()
  local m = smi.kriging.fit(S1, Y1, {trend = "constant", corr = "gauss", theta = {1}})
  local opts = setmetatable({}, {__index = function(_, key)
    local c <close> = m
    collectgarbage(); collectgarbage()
    return nil
  end})
  local mu = m:predict({{0.3}, {0.85}}, opts)
  T.near(mu[1], 1.3372431829, 1e-9)  -- spec 8.4, as in test_kriging.lua
  T.near(mu[2], 0.0607423314, 1e-9)
  T.raises(function() return m:predict({{0.3}}) end, "smi.kriging is closed")
end)

T.case("a model function that closes its own model while evaluate runs", function()
  local m
  m = smi.model.lua{inputs = {"x"}, outputs = {"y"}, fn = function(X)
    local c <close> = m
    collectgarbage()
    return {y = 2 * X:col(1)}
  end}
  local Y = m:evaluate({{1}, {2}})
  T.eq(Y.y[1], 2); T.eq(Y.y[2], 4)
  T.raises(function() return m:evaluate({{1}}) end, "is closed")
end)

T.case("<close> outside any callback still frees at once", function()
  local v = smi.vec{1, 2}
  do local c <close> = v end
  T.raises(function() return v:sum() end, "smi.vec is closed")
end)

T.case("smi.json.encode of a table nested 200,000 deep is an error, not a segfault", function()
  local t = {}
  local c = t
  for _ = 1, 200000 do c[1] = {}; c = c[1] end
  T.raises(function() smi.json.encode(t) end, "nested deeper than 200 levels")
  local s = {}; c = s
  for _ = 1, 150 do c[1] = {}; c = c[1] end
  T.truthy(#smi.json.encode(s) == 302, "150 levels still encode")
end)

T.case("smi.rng:integers over the full integer range (was SIGFPE)", function()
  local g = smi.rng(1)
  local v = g:integers(200, math.mininteger, math.maxinteger)
  local neg = 0
  for i = 1, #v do if v[i] < 0 then neg = neg + 1 end end
  T.truthy(neg > 60 and neg < 140, "about half negative: " .. neg)
end)

T.case("smi.vec(1e12) says what failed and why", function()
  local err = T.raises(function() return smi.vec(1e12) end, "smi.vec")
  T.truthy(err:find("1000000000000 numbers", 1, true), err)
  T.truthy(err:find("more than this machine has", 1, true), err)
  T.raises(function() return smi.mat.zeros(1e7, 1e7) end, "more than this machine's memory")
end)

T.case("threads = 100000 is capped by the machine (aborted the process)", function()
  local m = smi.kriging.fit(S1, Y1, {trend = "constant", corr = "gauss", theta = {1}, threads = 100000})
  local mu = m:predict({{0.3}, {0.85}}, {threads = 100000})
  T.near(mu[1], 1.3372431829, 1e-9)
end)

T.case("nested coroutine.close deeper than the C stack allows is an error (Lua 5.4.4 segfault)", function()
  local coro = false
  for _ = 1, 20000 do
    local previous = coro
    coro = coroutine.create(function()
      local cc <close> = setmetatable({}, {__close = function()
        if previous then assert(coroutine.close(previous)) end
      end})
      coroutine.yield()
    end)
    assert(coroutine.resume(coro))
  end
  local ok, err = coroutine.close(coro)
  T.eq(ok, false)
  T.truthy(tostring(err):find("nested too deep", 1, true), tostring(err))
  -- ordinary use is untouched
  local co = coroutine.create(function() coroutine.yield(1) end)
  coroutine.resume(co)
  T.eq(coroutine.close(co), true)
end)

T.finish()
