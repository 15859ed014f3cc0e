-- SPDX-License-Identifier: MIT
-- smi.strict: a study's opt-in strict mode. Reading an undefined global is an error naming it and
-- the closest defined global; assigned globals (even nil) and the library's globals read as usual.
-- Run last in this file: strict mode stays on for the rest of the chunk.
local T = require "smi.testing"
local strict = require "smi.strict"

T.case("on a fresh table: an undefined read names the global and the closest one", function()
  local env = strict.on({ improve = 1 })
  T.eq(env.improve, 1)
  local ok, err = pcall(function() return env.improv end)
  T.truthy(not ok and err:find("undefined global 'improv'", 1, true) and err:find("did you mean 'improve'", 1, true),
    tostring(err))
  env.later = nil
  T.eq(env.later, nil) -- assigned, even to nil: declared
end)

T.case("a table with its own metatable is refused, naming why", function()
  local ok, err = pcall(strict.on, setmetatable({}, {}))
  T.truthy(not ok and err:find("already have a metatable", 1, true), tostring(err))
end)

T.case("the script's own globals: a misspelt global is an error where it is read", function()
  strict.on()
  T.eq(type(smi), "table")
  T.eq(type(print), "function")
  strict.on() -- twice is harmless
  counter = 0 -- luacheck: ignore (a global assigned on purpose)
  counter = counter + 1
  T.eq(counter, 1)
  local ok, err = pcall(function() return countr + 1 end)
  T.truthy(not ok and err:find("undefined global 'countr'", 1, true)
    and err:find("did you mean 'counter'", 1, true) and err:find("test_strict.lua", 1, true), tostring(err))
end)

T.finish()
