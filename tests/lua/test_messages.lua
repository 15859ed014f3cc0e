-- SPDX-License-Identifier: MIT
-- Messages for inputs a new user gets wrong: each names the culprit and the fix
-- instead of a wrong result, a silent acceptance or a number as an error.
local T = require "smi.testing"

local function write(name, text)
  local p = smi.out(name)
  local f = assert(io.open(p, "wb"))
  f:write(text)
  f:close()
  return p
end

T.case("csv: a header-only file says there are no data rows (not 'holds text')", function()
  local p = write("header_only.csv", "mode1_hz,mode2_hz\n")
  local err = T.raises(function() smi.csv.read(p) end, "only a header row (columns: mode1_hz, mode2_hz) and no data rows")
  T.truthy(not err:find("text", 1, true), err)
end)

T.case("csv: a UTF-8 byte-order mark is not part of the first column's name", function()
  local p = write("bom.csv", "\239\187\191mode1_hz,mass\n29.6,1\n30.1,2\n")
  local d, header = smi.csv.read(p)
  T.eq(header[1], "mode1_hz", "first name without the BOM")
  T.eq(d.mode1_hz[2], 30.1, "column found by its plain name")
end)

T.case("csv: duplicated data rows are reported (lines named), not accepted silently", function()
  local p = write("dup.csv", "a,b\n1,2\n3,4\n1, 2\n5,6\n3,4\n")
  local d, _, notes = smi.csv.read(p)
  T.eq(#d.a, 5, "the rows are all kept")
  T.eq(#notes.duplicates, 2, "two repeats")
  T.eq(notes.duplicates[1][1], 2) T.eq(notes.duplicates[1][2], 4)
  T.eq(notes.duplicates[2][1], 3) T.eq(notes.duplicates[2][2], 6)
  T.truthy(notes.warnings[1]:find("2 duplicated data rows (line 4 repeats line 2, line 6 repeats line 3)", 1, true), notes.warnings[1])
  local _, _, clean = smi.csv.read(write("nodup.csv", "a,b\n1,2\n2,1\n"))
  T.eq(#clean.warnings, 0, "no warning without duplicates")
end)

T.case("Kriging predict at NaN is an error naming the point, not a finite mean", function()
  local m = smi.kriging.fit({{0}, {0.25}, {0.5}, {0.75}, {1}}, {0, 1, 0, -1, 0}, {trend = "constant", corr = "gauss", theta = {5}})
  T.near(m:predict({{0.25}})[1], 1, 1e-8, "a finite point still predicts")
  T.raises(function() m:predict({{0.5}, {0 / 0}}) end, "point 2 input 1 is NaN: Kriging predicts at finite points only")
end)

T.case("smi.propagate refuses a model's NaN, naming the sample, its inputs and the output", function()
  local model = function(M)
    local y = smi.vec(M:rows())
    for i = 1, M:rows() do y[i] = M[i][1] > 0.9 and 0 / 0 or M[i][1] end
    return {y = y}
  end
  local err = T.raises(function()
    smi.propagate{model = model, inputs = {{"load", smi.dist.uniform{lower = 0, upper = 1}}}, n = 1000, seed = 3}
  end, "the model returned NaN for output 'y' at sample ")
  T.truthy(err:find("(load = 0.9", 1, true), err)
  T.truthy(err:find("non-finite values in all", 1, true), err)
end)

T.case("smi.vec(1e12) says what it would take and what was probably meant", function()
  T.raises(function() return smi.vec(1e12) end, "a vector of 1000000000000 numbers needs 8e+03 GB of memory")
  T.raises(function() return smi.vec(1e12) end, "write smi.vec{1000000000000}")
  T.raises(function() return smi.vec(2.5) end, "smi.vec(2.5): a length must be a whole number >= 0")
  T.raises(function() return smi.vec.zeros(-1) end, "a length must be a whole number >= 0")
  T.eq(#smi.vec(3), 3, "a plain length still works")
  T.eq(smi.vec.ones(2)[2], 1.0)
end)

T.case("data far outside the model's range: a units warning naming the likely factor", function()
  local sanity = require "smi.sanity"
  local model_lo, model_hi = 28.2, 32.9 -- Hz, over the input bounds
  local hz = {29.6, 30.1, 30.4, 29.9}
  local khz = {0.0296, 0.0301, 0.0304, 0.0299}
  T.eq(sanity.units("mode 1", hz, model_lo, model_hi), nil, "data in range: quiet")
  T.eq(sanity.units("mode 4", {71.0, 70.2}, 80.1, 95.3), nil, "a real model error (71 Hz vs 80..95 Hz) is not a units problem")
  local w = sanity.units("mode 1", khz, model_lo, model_hi)
  T.truthy(w and w:find("lie 940 times below", 1, true) and w:find("factor of 1000 (kHz vs Hz", 1, true), tostring(w))
  local rad = {}
  for i, v in ipairs(hz) do rad[i] = v * 2 * math.pi end
  w = sanity.units("mode 1", rad, model_lo, model_hi)
  T.truthy(w and w:find("2π (rad/s vs Hz?)", 1, true), tostring(w))
end)

T.case("smi.fail: a failure reads as its message (tostring, string methods, ..) and smi.failure tells it apart", function()
  local ok, e = pcall(smi.fail, "tests.csv: no column 'mode2_Hz'")
  T.eq(ok, false)
  T.eq(smi.failure(e), "tests.csv: no column 'mode2_Hz'")
  T.eq(tostring(e), "tests.csv: no column 'mode2_Hz'")
  T.eq(rawget(e, "traceback"), nil, "no traceback given, none carried")
  T.eq(e:match("column '(.-)'"), "mode2_Hz", "string methods act on the message")
  T.eq("study: " .. e, "study: tests.csv: no column 'mode2_Hz'")
  T.eq(("[%s]"):format(e), "[tests.csv: no column 'mode2_Hz']")
  local _, plain = pcall(error, "a plain error", 0)
  T.eq(smi.failure(plain), nil, "an error in code is not a failure")
end)

T.case("a smi function called by the stdlib fails without the stdlib's file:line in front", function()
  -- the host's check of the results path, called by smi.study.new, refuses it
  local ok, e = pcall(require("smi.study").new, {name = "refused", out = "/proc/no-such-place"})
  T.eq(ok, false)
  T.truthy(smi.failure(e), "a failure: " .. tostring(e))
  T.truthy(tostring(e):find("smi.study: the results file '/proc/no-such-place/results.json'", 1, true) == 1, tostring(e))
  T.truthy(not tostring(e):find("stdlib/", 1, true), tostring(e))
  -- called by the user's code, the same function's error names the user's line
  local ok2, e2 = pcall(smi.write_file, "/proc/no-such-place/x.txt", "x")
  T.eq(ok2, false)
  T.eq(smi.failure(e2), nil, "an error with the caller's file:line")
end)

T.case("a misspelt smi member asked by the user's code names the closest and the user's line", function()
  local ok, e = pcall(function() return smi.dist.gaussian end)
  T.eq(ok, false)
  T.eq(smi.failure(e), nil, "an error in the user's code")
  T.truthy(tostring(e):find("no smi.dist.gaussian", 1, true), tostring(e))
  T.truthy(tostring(e):find("test_messages.lua", 1, true), "the user's line is named: " .. tostring(e))
end)

T.finish()
