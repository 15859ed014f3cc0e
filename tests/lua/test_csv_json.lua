-- SPDX-License-Identifier: MIT
-- smi.csv and smi.json: round trips that must be exact, the documented formats, errors that
-- name file/line/column, and the sandbox checks of both.
local T = require "smi.testing"

local function write_text(path, text)
  local f = assert(io.open(path, "wb"))
  f:write(text)
  f:close()
end

local function read_text(path)
  local f = assert(io.open(path, "rb"))
  local s = f:read("a")
  f:close()
  return s
end

T.case("csv: numeric columns become vecs, text columns string tables, header keeps file order", function()
  local p = smi.out("plain.csv")
  write_text(p, "load,name,stiffness\r\n1.5,\"a, b\",2e3\r\n-2,\"say \"\"hi\"\"\",0.25\r\n\r\n3,\"two\nlines\",-1e-300\r\n")
  local d, header = smi.csv.read(p)
  T.eq(#header, 3); T.eq(header[1], "load"); T.eq(header[2], "name"); T.eq(header[3], "stiffness")
  T.eq(getmetatable(d.load).__name, "smi.vec")
  T.eq(#d.load, 3); T.eq(d.load[1], 1.5); T.eq(d.load[2], -2); T.eq(d.load[3], 3)
  T.eq(d.stiffness[1], 2000); T.eq(d.stiffness[3], -1e-300)
  T.eq(type(d.name), "table")
  T.eq(d.name[1], "a, b"); T.eq(d.name[2], 'say "hi"'); T.eq(d.name[3], "two\nlines")
end)

T.case("csv: write then read gives back the same doubles, bit for bit", function()
  local x = smi.vec{0.1, 1 / 3, 2 ^ -1074, -2.5e10, 1e308, 123456789.123456789}
  local p = smi.out("roundtrip.csv")
  smi.csv.write(p, {x = x, tag = {"p", "q,r", "s\"t", "u", "v", "w"}, n = {1, 2, 3, 4, 5, 6}},
                {header = {"tag", "x", "n"}})
  local text = read_text(p)
  T.eq(text:sub(1, text:find("\n")), "tag,x,n\n")
  T.truthy(text:find('"q,r",0.3333333333333333,2', 1, true), "quoted text and shortest exact numbers: " .. text)
  local d, header = smi.csv.read(p)
  T.eq(header[1], "tag"); T.eq(header[2], "x"); T.eq(header[3], "n")
  for i = 1, #x do T.eq(d.x[i], x[i], "x[" .. i .. "]") end
  T.eq(d.tag[2], "q,r"); T.eq(d.tag[3], 's"t'); T.eq(d.n[6], 6)
  -- without a header option the columns are written in sorted order
  smi.csv.write(p, {b = {1}, a = {2}})
  T.eq(read_text(p), "a,b\n2,1\n")
end)

T.case("csv: a bad number names the file, line and column", function()
  local p = smi.out("bad.csv")
  write_text(p, "x,y\n1,2\n3,abc\n")
  local e = T.raises(function() smi.csv.read(p) end, "bad.csv: column 2 ('y'): bad number 'abc'")
  T.truthy(e:find("line 3 of " .. p, 1, true), "the row named by its line in the file: " .. e)
  -- the remedy in the message works
  local d = smi.csv.read(p, {strings = {"y"}})
  T.eq(d.y[2], "abc"); T.eq(d.x[2], 3)
  write_text(p, "x,y\n1,2\n3\n")
  T.raises(function() smi.csv.read(p) end, "bad.csv: 1 fields, but the header has 2 columns")
  write_text(p, "x,x\n1,2\n")
  T.raises(function() smi.csv.read(p) end, "column name 'x' appears twice")
  T.raises(function() smi.csv.write(p, {a = {1, 2}, b = {1}}) end, "column 'b' has 1 values but column 'a' has 2")
  T.raises(function() smi.csv.write(p, {a = {1, {}}}) end, "column 'a'[2] must be a number or a string, got table")
  T.raises(function() smi.csv.read(p, {sepp = ";"}) end, "did you mean 'sep'")
end)

T.case("csv: a quoted header with the separator reads as the solver-output parser reads it", function()
  -- the same text as tests/platform/eval/test_text_parsers.cpp's RFC 4180 case (csv_column)
  local p = smi.out("quoted_header.csv")
  local f = assert(io.open(p, "wb"))
  f:write('\xEF\xBB\xBF"load, N",freq\r\n1200,29.6\r\n"1500","33.6"\r\n')
  f:close()
  local d, header = smi.csv.read(p)
  T.eq(header[1], "load, N"); T.eq(header[2], "freq")
  T.eq(d["load, N"][1], 1200); T.eq(d["load, N"][2], 1500); T.eq(d.freq[2], 33.6)
end)

T.case("csv: the sandbox applies", function()
  T.raises(function() smi.csv.read("/etc/passwd") end, "smi.csv.read: reading '/etc/passwd'")
  T.raises(function() smi.csv.write(smi.script_dir .. "/x.csv", {a = {1}}) end, "--allow-write")
end)

T.case("json: encode follows RFC 8259 and is deterministic", function()
  T.eq(smi.json.encode({b = {1, 2, 3}, a = 1, c = "x\n\"y\"", d = true, e = smi.json.null}),
       '{"a":1,"b":[1,2,3],"c":"x\\n\\"y\\"","d":true,"e":null}')
  T.eq(smi.json.encode({}), "[]")
  T.eq(smi.json.encode(smi.vec{1, 0.5}), "[1,0.5]")
  T.eq(smi.json.encode(smi.mat{{1, 2}, {3, 4}}), "[[1,2],[3,4]]")
  T.eq(smi.json.encode({[1] = "a", [3] = "c"}), '{"1":"a","3":"c"}')
  T.eq(smi.json.encode("\1"), '"\\u0001"')
  T.eq(smi.json.encode({x = {y = 1}}, {indent = 2}), '{\n  "x": {\n    "y": 1\n  }\n}')
end)

T.case("json: numbers survive a round trip exactly", function()
  for _, v in ipairs{0.1 + 0.2, 1 / 3, 2 ^ -1074, 1.7976931348623157e308, -0.0, 123456789012345678} do
    T.eq(smi.json.decode(smi.json.encode(v)), v, tostring(v))
  end
  T.eq(math.type(smi.json.decode("42")), "integer")
  T.eq(math.type(smi.json.decode("42.0")), "float")
  T.eq(smi.json.decode("1e400"), math.huge)
end)

T.case("json: decode builds tables, keeps nulls, reads escapes", function()
  local v = smi.json.decode(' {"a": [1, 2, {"b": null}], "s": "\\u00e9\\ud83d\\ude00\\/", "t": false} ')
  T.eq(v.a[2], 2); T.eq(v.a[3].b, smi.json.null); T.eq(v.t, false)
  T.eq(v.s, "\xC3\xA9\xF0\x9F\x98\x80/")
  T.eq(tostring(smi.json.null), "null")
end)

T.case("json: errors say where", function()
  T.raises(function() smi.json.decode('{"a": 1,\n "b" 2}') end, "json:2:6: expected ':' after the object key")
  T.raises(function() smi.json.decode('[1, 2') end, "json:1:6: expected ',' or ']' in the array")
  T.raises(function() smi.json.decode('[1] x') end, "unexpected text after the JSON value")
  T.raises(function() smi.json.decode('"\\q"') end, "unknown escape")
  T.raises(function() smi.json.encode({x = {1, 0 / 0}}) end, "value at $.x[2] is")
  T.raises(function() smi.json.encode({f = print}) end, "value at $.f is a function")
  local t = {}; t.self = t
  T.raises(function() smi.json.encode(t) end, "a cycle")
end)

T.case("json: the one non-finite rule (refused, or encoded and read back on request)", function()
  T.raises(function() smi.json.encode({r = {x = math.huge}}, {root = "results"}) end, "value at results.r.x is inf")
  local text = smi.json.encode({0 / 0, math.huge, -math.huge}, {nonfinite = "encode"})
  T.eq(text, "[null,1e999,-1e999]")
  local back = smi.json.decode(text, {null = 0 / 0})
  T.truthy(back[1] ~= back[1], "null read as NaN on request")
  T.eq(back[2], math.huge); T.eq(back[3], -math.huge)
  T.eq(smi.json.decode(text)[1], smi.json.null, "null by default")
  local s, skipped = smi.json.encode({a = 1, f = print}, {skip = true})
  T.eq(s, '{"a":1}'); T.eq(skipped[1], "$.f (function)")
  T.raises(function() smi.json.encode(1, {nonfinite = "zero"}) end, "nonfinite must be")
end)

T.case("json: write and read files through the sandbox", function()
  local p = smi.out("results.json")
  smi.json.write(p, {seed = smi.seed, mean = 1 / 3, x = smi.vec{1, 2}})
  local r = smi.json.read(p)
  T.eq(r.seed, smi.seed); T.eq(r.mean, 1 / 3); T.eq(r.x[2], 2)
  write_text(p, '{"a": }')
  T.raises(function() smi.json.read(p) end, "results.json:1:7: expected a value")
  T.raises(function() smi.json.read("/etc/hostname") end, "smi.json.read: reading '/etc/hostname'")
  T.raises(function() smi.json.write("/tmp/smi-escape.json", {}) end, "--allow-write")
end)

T.finish()
