-- SPDX-License-Identifier: MIT
-- An error raised deep in recursive smi calls names its cause first: a model that
-- calls smi.propagate again ended, 60 levels down, with a 2 KB message of nested prefixes and
-- the cause cut off. Now: the outermost prefix, the cause, and how deep it was raised.
local T = require "smi.testing"

local function recursive(limit)
  local depth = 0
  local function f(M)
    depth = depth + 1
    if depth > limit then error("the innermost cause", 0) end
    local out = smi.propagate{model = f, inputs = {{"a", 1.0}}, n = 2}
    return {y = out.y}
  end
  return pcall(smi.propagate, {model = f, inputs = {{"a", 1.0}}, n = 2})
end

T.case("the cause comes first whatever the depth", function()
  for _, limit in ipairs{1, 5, 60, 150} do
    local ok, err = recursive(limit)
    T.eq(ok, false)
    err = tostring(err)
    T.truthy(err:find("^smi%.propagate: the innermost cause %(raised " .. (limit + 1) .. " nested smi%.propagate calls deep%)")
             or err:find("smi%.propagate: the innermost cause %(raised " .. (limit + 1) .. " nested", 1),
             limit .. ": " .. err:sub(1, 300))
    T.truthy(#err < 400, "short: " .. #err)
  end
end)

T.case("a message without nesting is unchanged", function()
  local ok, err = pcall(smi.propagate, {model = function() error("plain", 0) end, inputs = {{"a", 1.0}}, n = 2})
  T.eq(ok, false)
  T.truthy(tostring(err):find("smi.propagate: plain", 1, true), tostring(err))
  T.truthy(not tostring(err):find("calls deep", 1, true), tostring(err))
end)

T.finish()
