-- SPDX-License-Identifier: MIT
-- smi.report.json (results.json's rule over smi.json): numbers read back bit for bit,
-- non-finite numbers survive as valid JSON, and what JSON cannot hold is named by its path.
local T = require "smi.testing"
local json = require "smi.report.json"

T.case("doubles round-trip exactly (shortest text)", function()
  local rng = smi.rng(11)
  local u, z = rng:uniform(500), rng:normal(500)
  local t = {}
  for i = 1, 500 do t[i] = z[i] * 10 ^ math.floor(u[i] * 40 - 20) end
  t[#t + 1] = 0.1 + 0.2
  t[#t + 1] = 2 ^ -1074 -- the smallest subnormal
  t[#t + 1] = 1.7976931348623157e308
  local back = json.decode(json.encode(t))
  T.eq(#back, #t, "length")
  for i = 1, #t do T.eq(back[i], t[i], "value " .. i) end
end)

T.case("integers stay integers, text keeps its characters", function()
  local v = { n = 42, big = 9007199254740993, s = 'quote " back \\ nl \n tab \t ctl \1 é ∞' }
  local back = json.decode(json.encode(v))
  T.eq(math.type(back.n), "integer", "integer type")
  T.eq(back.big, 9007199254740993, "64-bit integer")
  T.eq(back.s, v.s, "string")
  T.eq(json.decode('"\\u00e9\\ud83d\\ude00"'), "é😀", "unicode escapes and surrogate pairs")
end)

T.case("NaN -> null, inf -> 1e999, both read back", function()
  local text = json.encode({ 0 / 0, math.huge, -math.huge, 1 })
  T.eq(text, "[null,1e999,-1e999,1]", "text")
  local back = json.decode(text)
  T.truthy(back[1] ~= back[1], "NaN")
  T.eq(back[2], math.huge, "+inf")
  T.eq(back[3], -math.huge, "-inf")
end)

T.case("smi.vec and smi.mat become arrays; keys are sorted", function()
  T.eq(json.encode({ b = smi.vec{ 1.5, 2 }, a = smi.mat{ { 1, 2 }, { 3, 4 } } }), '{"a":[[1,2],[3,4]],"b":[1.5,2]}', "text")
  T.eq(json.encode({}), "[]", "empty table")
end)

T.case("values JSON cannot hold: an error with the path, or skipped and listed", function()
  T.raises(function() json.encode({ a = { b = { print } } }) end, "value.a.b[1] is a function")
  local skipped = {}
  local text = json.encode({ keep = 1, model = io.stdout, f = print }, { skip = true, skipped = skipped })
  T.eq(text, '{"keep":1}', "kept only the number")
  table.sort(skipped)
  T.eq(table.concat(skipped, ";"), "value.f (function);value.model (FILE*)", "skipped paths")
  T.raises(function() json.encode({ [true] = 1 }) end, "key of type boolean")
end)

T.case("decode errors name the line", function()
  T.raises(function() json.decode('{\n"a": [1, 2,\n}') end, "json:3:1: expected a value")
  T.raises(function() json.decode('{"a": 1} x') end, "unexpected text after the JSON value")
  T.raises(function() json.decode('"abc') end, "unterminated string")
end)

T.case("indented output parses to the same value", function()
  local v = { steps = { a = { result = { x = { 1, 2, 3 }, y = "z" } } }, order = { "a" } }
  local text = json.encode(v, { indent = "  " })
  T.truthy(text:find("\n    ", 1, true), "indented")
  local back = json.decode(text)
  T.eq(back.steps.a.result.x[3], 3, "nested value")
  T.eq(back.order[1], "a", "array")
end)

T.finish()
