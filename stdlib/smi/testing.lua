--- smi.testing: a small test harness for Lua test files run by smi-lua itself.
--
--   local T = require "smi.testing"
--   T.case("kde pdf matches the closed form", function()
--     T.near(k:pdf(0), 0.3989422804, 1e-9)
--   end)
--   T.finish()   -- prints "N passed, N failed"; raises if any failed (exit status 1)
local M = {}

local passed, failed = 0, 0
local current = nil

local function fail(msg, level)
  error((current and ("[" .. current .. "] ") or "") .. msg, (level or 1) + 1)
end

--- |actual - expected| <= tol (absolute), or relative when opts.rel is true.
function M.near(actual, expected, tol, what)
  assert(type(tol) == "number", "T.near: tolerance required")
  if type(actual) ~= "number" then fail(("%s: expected a number, got %s"):format(what or "value", type(actual)), 2) end
  local err = math.abs(actual - expected)
  if not (err <= tol) then
    fail(("%s: got %.12g, expected %.12g (|diff| %.3g > tol %.3g)"):format(what or "value", actual, expected, err, tol), 2)
  end
end

--- Relative closeness: |a - e| <= rtol * |e|.
function M.rel(actual, expected, rtol, what)
  if type(actual) ~= "number" then fail(("%s: expected a number, got %s"):format(what or "value", type(actual)), 2) end
  local err = math.abs(actual - expected)
  if not (err <= rtol * math.abs(expected)) then
    fail(("%s: got %.12g, expected %.12g (rel diff %.3g > %.3g)"):format(what or "value", actual, expected,
      err / math.abs(expected), rtol), 2)
  end
end

function M.eq(actual, expected, what)
  if actual ~= expected then
    fail(("%s: got %s, expected %s"):format(what or "value", tostring(actual), tostring(expected)), 2)
  end
end

function M.truthy(v, what)
  if not v then fail((what or "condition") .. " is false", 2) end
end

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

--- Prints the closing line and raises when anything failed, so the exit status is 1.
function M.finish()
  print(("%d passed, %d failed"):format(passed, failed))
  if failed > 0 then error(("%d test case(s) failed"):format(failed), 0) end
end

return M
