-- SPDX-License-Identifier: MIT
--- smi.testing: a small test harness for Lua test files run by smi-lua itself.
--
--   local T = require "smi.testing"
--   T.case("kde pdf matches the closed form", function()
--     T.near(k:pdf(0), 0.3989422804, 1e-9)
--   end)
--   T.finish()   -- prints "N passed, N failed"; raises if any failed (exit status 1)
local doc = require "smi.doc"
doc.add[==[
@ module smi.testing
A small test harness for Lua test files run by smi-lua itself (smi-lua test DIR runs them):
T.case, checks (near, rel, eq, truthy, raises) and T.finish.
]==]
local M = {}

local passed, failed = 0, 0
local current = nil

local function fail(msg, level)
  error((current and ("[" .. current .. "] ") or "") .. msg, (level or 1) + 1)
end

doc.add[==[
@ smi.testing.near(actual, expected, tol [, what])
Checks |actual - expected| <= tol (absolute).
returns: nothing
errors: the check fails: "what: got ..., expected ... (|diff| ... > tol ...)"; actual not a number
example:
  local T = require "smi.testing"
  T.near(math.pi, 3.14159, 1e-5, "pi")
  print("ok")
]==]
--- |actual - expected| <= tol (absolute), or relative when opts.rel is true.
function M.near(actual, expected, tol, what)
  assert(type(tol) == "number", "T.near: tolerance required")
  if type(actual) ~= "number" then fail(("%s: expected a number, got %s"):format(what or "value", type(actual)), 2) end
  local err = math.abs(actual - expected)
  if not (err <= tol) then
    fail(("%s: got %.12g, expected %.12g (|diff| %.3g > tol %.3g)"):format(what or "value", actual, expected, err, tol), 2)
  end
end

doc.add[==[
@ smi.testing.rel(actual, expected, rtol [, what])
Checks |actual - expected| <= rtol * |expected| (relative closeness).
returns: nothing
errors: the check fails, with the relative difference
example:
  local T = require "smi.testing"
  T.rel(1001, 1000, 0.01, "count")
  print("ok")
]==]
--- Relative closeness: |a - e| <= rtol * |e|.
function M.rel(actual, expected, rtol, what)
  if type(actual) ~= "number" then fail(("%s: expected a number, got %s"):format(what or "value", type(actual)), 2) end
  local err = math.abs(actual - expected)
  if not (err <= rtol * math.abs(expected)) then
    fail(("%s: got %.12g, expected %.12g (rel diff %.3g > %.3g)"):format(what or "value", actual, expected,
      err / math.abs(expected), rtol), 2)
  end
end

doc.add[==[
@ smi.testing.eq(actual, expected [, what])
Checks actual == expected.
returns: nothing
errors: the values differ ("what: got a, expected b")
example:
  local T = require "smi.testing"
  T.eq(#smi.vec{1, 2}, 2, "length")
  print("ok")
]==]
function M.eq(actual, expected, what)
  if actual ~= expected then
    fail(("%s: got %s, expected %s"):format(what or "value", tostring(actual), tostring(expected)), 2)
  end
end

doc.add[==[
@ smi.testing.truthy(v [, what])
Checks that v is neither nil nor false.
returns: nothing
errors: "what is false"
example:
  local T = require "smi.testing"
  T.truthy(smi.vec{1}:sum() > 0, "positive sum")
  print("ok")
]==]
function M.truthy(v, what)
  if not v then fail((what or "condition") .. " is false", 2) end
end

doc.add[==[
@ smi.testing.raises(fn, text [, what]) -> message
Checks that fn() raises an error whose message contains text (plain text, not a pattern).
returns: the error message
errors: fn succeeds, or its message does not contain text
example:
  local T = require "smi.testing"
  print(T.raises(function() smi.vec{}:mean() end, "at least 1 value"))
]==]
--- fn() must raise an error whose message contains `pattern` (plain text match).
function M.raises(fn, pattern, what)
  local ok, err = pcall(fn)
  if ok then fail((what or "call") .. ": expected an error matching '" .. pattern .. "', got success", 2) end
  err = tostring(err)
  if not err:find(pattern, 1, true) then
    fail((what or "call") .. ": error '" .. err .. "' does not contain '" .. pattern .. "'", 2)
  end
  return err
end

doc.add[==[
@ smi.testing.case(name, fn)
Runs fn as a named test case: a failure is printed ("FAIL name") and counted, and the file goes on.
returns: nothing
errors: none (failures are counted for T.finish)
example:
  local T = require "smi.testing"
  T.case("sum of ones", function() T.eq(smi.vec.ones(3):sum(), 3.0) end)
  print("ran")
]==]
function M.case(name, fn)
  current = name
  local ok, err = xpcall(fn, debug and debug.traceback or tostring)
  current = nil
  if ok then
    passed = passed + 1
  else
    failed = failed + 1
    io.stderr:write("FAIL ", name, "\n  ", tostring(err), "\n")
  end
end

doc.add[==[
@ smi.testing.finish()
Prints "N passed, N failed" and raises when any case failed, so the exit status is 1.
returns: nothing
errors: "N test case(s) failed"
example:
  local T = require "smi.testing"
  print(pcall(T.finish))
]==]
--- Prints the closing line and raises when anything failed, so the exit status is 1.
function M.finish()
  print(("%d passed, %d failed"):format(passed, failed))
  if failed > 0 then error(("%d test case(s) failed"):format(failed), 0) end
end

return M
