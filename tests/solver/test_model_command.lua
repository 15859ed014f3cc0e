-- SPDX-License-Identifier: MIT
-- smi.model.command and smi.model.batch from a study, driving the in-tree test solver.
-- arg[1] = path of smi-test-solver, arg[2] = fixtures folder.
local T = require "smi.testing"
local solver, fixtures = arg[1], arg[2]

local n = 0
local function model(extra, opts)
  n = n + 1
  local o = {
    name = "t" .. n, inputs = {"x1", "x2"}, outputs = {"f", "g"},
    template_string = "x1 = {{x1}}\nx2 = {{x2:%.17g}}\n" .. (extra or ""),
    deck = "run.deck",
    command = {solver, "{deck}", "-o", "out.txt"},
    version = "lua-test-" .. n,
    parse = function(dir, h)
      return {f = h.regex("out.txt", "f = (\\S+)"), g = h.regex("out.txt", "g = (\\S+)")}
    end,
  }
  for k, v in pairs(opts or {}) do o[k] = v end
  if o.template then o.template_string = nil end
  return smi.model.command(o)
end

local X = smi.mat{{0.1, 1}, {0.6, 0.75}, {1.1, 0.5}, {1.6, 0.25}}

T.case("command model: outputs in row order, equal to the closed form; second call reuses", function()
  local m = model()
  T.eq(m.kind, "command")
  local Y, info = m:evaluate(X)
  for i = 1, 4 do
    local a, b = X[i][1], X[i][2]
    T.eq(Y.f[i], a * a + b * b, "f" .. i); T.eq(Y.g[i], a + 2 * b, "g" .. i)
  end
  T.eq(info.launched, 4); T.eq(info.reused[1], 0)
  local Y2, info2 = m:evaluate(X)
  T.eq(info2.launched, 0); T.eq(info2.reused[4], 1); T.eq(Y2.f[4], Y.f[4])
  local plan = m:plan(smi.mat{{0.1, 1}, {9, 9}})
  T.eq(plan.reused, 1); T.eq(plan.runs, 1)
  -- the stored mean run time (a study's cost plan): the mean of the four runs' durations
  local d = 0
  for i = 1, 4 do d = d + info.duration[i] / 4 end
  T.near(plan.mean_seconds, d, 1e-6, "mean_seconds")
end)

T.case("concurrency 2 gives identical numbers to concurrency 1", function()
  local a = model("sleep = 0.05\n", {concurrency = 1}):evaluate(X)
  local b = model("sleep = 0.05\n", {concurrency = 2}):evaluate(X)
  for i = 1, 4 do T.eq(a.f[i], b.f[i]); T.eq(a.g[i], b.g[i]) end
end)

T.case("failures are data with skip, an error with stop", function()
  local m = model("mode = exit\n", {on_failure = "skip"})
  local Y, info = m:evaluate(X)
  T.eq(info.failed, 4); T.eq(info.status[1], "failed")
  T.truthy(info.reason[1]:find("exit status 1: smi-test-solver: fatal error 1234", 1, true), info.reason[1])
  T.truthy(Y.f[1] ~= Y.f[1], "NaN")
  T.raises(function() model("mode = crash\n"):evaluate(X) end, "killed by signal 6")
  local _, ginfo = model("mode = garbage\n", {on_failure = "skip"}):evaluate(X)
  T.truthy(ginfo.reason[2]:find("unparsable output", 1, true), ginfo.reason[2])
  local _, tinfo = model("mode = hang\n", {on_failure = "skip", timeout = 0.2}):evaluate(smi.mat{{1, 2}})
  T.truthy(tinfo.reason[1]:find("timeout after 0.2 s", 1, true), tinfo.reason[1])
  -- a parser error is a failed record too, not a crash of the study
  local _, pinfo = model("", {on_failure = "skip", parse = function() error("no convergence marker") end}):evaluate(smi.mat{{1, 2}})
  T.truthy(pinfo.reason[1]:find("no convergence marker", 1, true), pinfo.reason[1])
end)

T.case("hostile values and templates", function()
  local hostile = "$(touch pwned); rm -rf / `id`"
  local m = model("label = {{label}}\n", {constants = {label = hostile}, parse = function(dir, h)
    return {f = h.regex("out.txt", "f = (\\S+)"), g = #h.read("echo.txt")}
  end})
  local Y = m:evaluate(smi.mat{{1, 2}})
  T.eq(Y.g[1], #hostile + 1)
  T.raises(function() model("E = {{E}}\n") end, "(template_string)' line 3: placeholder {{E}} has no value")
  T.raises(function() model("", {inputs = {"x1", "x2", "x3"}}) end, "input 'x3' does not appear in template")
  T.raises(function() model("", {comand = {}}) end, "comand")
  T.raises(function() model("", {command = "smi-test-solver run.deck"}) end, "argv table")
  T.raises(function() model("", {template = "/nonexistent/deck.tpl"}) end, "/nonexistent/deck.tpl")
end)

T.case("option mistakes are named by the schema: key, function, expected type or values", function()
  T.raises(function() model("", {timout = 5}) end, "smi.model.command: unknown option 'timout' (did you mean 'timeout'?)")
  T.raises(function() model("", {timeout = "5"}) end, "smi.model.command: option 'timeout' must be a number, got string")
  T.raises(function() model("", {retries = 1.5}) end, "smi.model.command: option 'retries' must be an integer, got number")
  T.raises(function() model("", {reuse_failed = 1}) end, "smi.model.command: option 'reuse_failed' must be a boolean, got number")
  T.raises(function() model("", {on_failure = "ignore"}) end,
    "smi.model.command: on_failure must be 'stop', 'skip' or 'retry', got 'ignore'")
  -- the batch form has its own keys: a deck is the command form's
  T.raises(function()
    smi.model.batch{name = "bk", inputs = {"x1"}, outputs = {"f"}, command = {solver, "{deck}"}, deck = "run.deck",
      parse = function() return {} end}
  end, "smi.model.batch: unknown option 'deck'")
end)

T.case("batch model: one run per batch, per-point results", function()
  local m = smi.model.batch{
    name = "b", inputs = {"x1", "x2"}, outputs = {"f", "g"}, input_file = "points.csv",
    command = {solver, "{deck}"}, version = "lua-batch", batch_size = 3, concurrency = 2,
    parse = function(dir, h, n) return {f = h.csv("results.csv", "f"), g = h.csv("results.csv", "g")} end,
  }
  local Y, info = m:evaluate(X)
  T.eq(info.launched, 2)
  for i = 1, 4 do T.eq(Y.g[i], X[i][1] + 2 * X[i][2]) end
end)

T.case("extra files are copied into every work directory", function()
  local m = model("", {files = {fixtures .. "/column_rigid.f06"}, outputs = {"f", "f3"}, parse = function(dir, h)
    return {f = h.regex("out.txt", "f = (\\S+)"), f3 = h.f06("column_rigid.f06").paper_hz[3]}
  end})
  local Y = m:evaluate(X)
  T.eq(Y.f3[2], 38.26345); T.eq(Y.f[2], 0.6 * 0.6 + 0.75 * 0.75)
end)

T.case("f06 helper reads the spec's example results file", function()
  local r = smi.model.parse.f06(fixtures .. "/column_rigid.f06")
  T.eq(#r.cycles, 10); T.eq(r.cycles[1], 29.63724); T.eq(r.paper[4].mode, 4)
  T.eq(r.paper_hz[3], 38.26345); T.eq(r.direction[3], "TORSION"); T.eq(r.labels[5].paper, nil)
end)

T.finish()
