-- SPDX-License-Identifier: MIT
-- Lua 5.4.4's known bugs (Debian 12 ships it), each met by a host guard:
--  * string.gmatch's iterator called again after "pattern too complex" recursed without limit
--    (upstream fix: lua/lua efddc230): the wrapped iterator refuses to run after an error;
--  * nested coroutine.close with pcalls inside __close overflowed the C stack under the old
--    cap of 100 levels (upstream fix: 1e64c139): the guard measures C stack, not levels;
--  * `1 ~ (2 or 3)` returned 0 in a function with more than 256 constants (upstream fix:
--    c764ca71): such chunks are refused at load, through every loading path.
-- On the old build the first two crashed smi-lua (SIGSEGV) and the third returned 0.
local T = require "smi.testing"

T.case("a gmatch iterator that failed does not run again", function()
  local N = 20000
  for _, pat in ipairs{string.rep("a?", N), "(" .. string.rep("a?", N) .. ")"} do
    local iter = string.gmatch(string.rep("a", N), pat)
    local ok1, e1 = pcall(iter)
    T.eq(ok1, false)
    T.truthy(tostring(e1):find("pattern too complex", 1, true), tostring(e1))
    for _ = 1, 3 do
      local ok2, e2 = pcall(iter)
      T.eq(ok2, false)
      T.truthy(tostring(e2):find("already failed", 1, true), tostring(e2))
    end
  end
  -- as a method, and ordinary use untouched
  local iter = ("x"):rep(N):gmatch(("x?"):rep(N))
  T.eq(pcall(iter), false); T.eq(pcall(iter), false)
  local words = {}
  for w in ("alpha beta gamma"):gmatch("%a+") do words[#words + 1] = w end
  T.eq(table.concat(words, ","), "alpha,beta,gamma")
  local pairs_seen = {}
  for k, v in string.gmatch("a=1, b=2", "(%w+)=(%w+)") do pairs_seen[#pairs_seen + 1] = k .. v end
  T.eq(table.concat(pairs_seen, ","), "a1,b2")
end)

-- closes: levels of nested coroutine.close, each __close running `depth` nested pcalls first
local function chain(levels, depth)
  local coro = false
  for _ = 1, levels do
    local previous = coro
    coro = coroutine.create(function()
      local cc <close> = setmetatable({}, {__close = function()
        local function nest(k)
          if k == 0 then
            if previous then assert(coroutine.close(previous)) end
            return true
          end
          local ok, r = pcall(nest, k - 1)
          if not ok then error(r, 0) end  -- passed on: the chain must end with the error
          return r
        end
        assert(nest(depth))
      end})
      coroutine.yield()
    end)
    assert(coroutine.resume(coro))
  end
  return coroutine.close(coro)
end

T.case("nested coroutine.close is bounded by C stack, not by a count", function()
  for _, shape in ipairs{{99, 190}, {60, 190}, {2000, 0}, {400, 40}} do
    local ok, err = chain(shape[1], shape[2])
    T.eq(ok, false, shape[1] .. "x" .. shape[2])
    T.truthy(tostring(err):find("nested too deep", 1, true) or tostring(err):find("stack overflow", 1, true),
             tostring(err))
  end
  T.eq(chain(5, 10), true, "shallow nesting still works")
end)

-- The constant-folding bug: a table of 300 constants, then a bitwise operation.
local function big(ret)
  local code = {"local x = {"}
  for i = 1, 300 do code[#code + 1] = i .. ".1," end
  code[#code + 1] = "};"
  return table.concat(code) .. ret
end

T.case("a chunk the 5.4.4 code generator miscompiles is refused by load, with the line and the fix", function()
  for _, ret in ipairs{"return (1 ~ (2 or 3))", "return (1 | (2 or 3))", "return (1 & (2 or 3))",
                       "return (1 << (2 or 3))", "local K <const> = 1\nreturn K ~ (2 or 3)", "return 5 >> (1 or 2)"} do
    local f, err = load(big(ret))
    T.eq(f, nil, ret)
    T.truthy(tostring(err):find("c764ca71", 1, true), tostring(err))
    -- a reader function goes through the same check
    local done = false
    local g, err2 = load(function() if done then return nil end done = true return big(ret) end)
    T.eq(g, nil, ret)
    T.truthy(tostring(err2):find("5.4.4", 1, true), tostring(err2))
  end
  -- unaffected: the same arithmetic in small chunks, and big chunks without bitwise operators
  T.eq(load("return (1 ~ (2 or 3))")(), 3)
  T.eq(load(big("return (1 + (2 or 3))"))(), 3)
  T.eq(load(big("return 1 ~= 2"))(), true)
end)

T.case("the same refusal through require and dofile", function()
  local dir = smi.out("lua544")
  local f = assert(io.open(dir .. ".lua", "w"))
  f:write(big("return (1 ~ (2 or 3))"))
  f:close()
  local ok, err = pcall(dofile, dir .. ".lua")
  T.eq(ok, false)
  T.truthy(tostring(err):find("c764ca71", 1, true), tostring(err))
  local fn, err2 = loadfile(dir .. ".lua")
  T.eq(fn, nil)
  T.truthy(tostring(err2):find("c764ca71", 1, true), tostring(err2))
end)

T.finish()
