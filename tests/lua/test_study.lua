-- SPDX-License-Identifier: MIT
-- smi.study: steps run in order and see earlier results; results.json keeps them so that a
-- step can run alone later; failures keep what was done and name the step.
local T = require "smi.testing"
local study = require "smi.study"
local json = require "smi.report.json"

local dir = smi.out_dir or "."
local function results_path(name) return dir .. "/" .. name .. ".json" end
-- ctest run again on the same build must not find this file's studies done: every step would be
-- reused (same code, same binary) and the cases that count calls would see none.
for _, name in ipairs{ "study_alone", "study_annotate", "study_fail", "study_fail_unsaved", "study_missing", "study_misuse",
                       "study_misuse2", "study_not_saved_order", "study_order", "study_report", "study_stale",
                       "study_volatile", "study_volatile_deep" } do
  os.remove(results_path(name))
end

local function read_json(path)
  local f = assert(io.open(path, "rb"))
  local d = json.decode(f:read("a"))
  f:close()
  return d
end

-- A three-step study whose steps count their calls.
local function make(name, calls)
  local s = study.new{ name = name, out = dir, results = results_path(name), quiet = true }
  s:step("data", function(ctx)
    calls.data = (calls.data or 0) + 1
    return { x = { 1.5, 2.5, 3.5 }, n = 3, vec = smi.vec{ 0.1, 0.2 } }
  end)
  s:step("mean", function(ctx)
    calls.mean = (calls.mean or 0) + 1
    local d = ctx.results.data
    local m = 0
    for i = 1, d.n do m = m + d.x[i] end
    ctx:set("mean", m / d.n)
    ctx:set("model", function() return 1 end) -- not JSON: kept in memory only
  end)
  s:step("scaled", function(ctx)
    calls.scaled = (calls.scaled or 0) + 1
    return { value = 10 * ctx.results.mean.mean, vec_sum = ctx.results.data.vec[1] + ctx.results.data.vec[2] }
  end)
  return s
end

T.case("steps run in order and results.json holds every number", function()
  local calls = {}
  local s = make("study_order", calls)
  local r = s:run()
  T.eq(r.mean.mean, 2.5, "mean")
  T.eq(r.scaled.value, 25.0, "scaled")
  T.near(r.scaled.vec_sum, 0.3, 1e-15, "smi.vec result usable by the next step")
  T.eq(type(r.mean.model), "function", "in-memory value available in the same run")
  local d = read_json(results_path("study_order"))
  T.eq(d.study, "study_order", "study name")
  T.eq(table.concat(d.order, ","), "data,mean,scaled", "order")
  T.eq(d.steps.data.result.x[2], 2.5, "saved number")
  T.eq(d.steps.data.result.vec[2], 0.2, "saved vec")
  T.eq(d.steps.scaled.result.value, 25.0, "saved result")
  T.eq(d.steps.mean.result.model, nil, "function left out")
  T.eq(d.steps.mean.not_saved[1], "mean.model (function)", "and listed")
  T.eq(d.steps.mean.status, "ok", "status")
  T.truthy(type(d.steps.mean.seconds) == "number" and d.steps.mean.seconds >= 0, "timed")
end)

T.case("a step runs alone from the saved results", function()
  local first = {}
  make("study_alone", first):run()
  local calls = {}
  local s = make("study_alone", calls) -- a fresh study object, as in a new smi-lua process
  local r = s:run{ only = "scaled" }
  T.eq(calls.data, nil, "data not re-run")
  T.eq(calls.mean, nil, "mean not re-run")
  T.eq(calls.scaled, 1, "scaled ran once")
  T.eq(r.scaled.value, 25.0, "value from saved inputs")
  local d = read_json(results_path("study_alone"))
  T.eq(d.steps.data.result.n, 3, "earlier steps kept in the file")
  -- from = runs the rest
  calls = {}
  make("study_alone", calls):run{ from = "mean" }
  T.eq(calls.data, nil, "from: data skipped")
  T.eq(calls.mean, 1, "from: mean ran")
  T.eq(calls.scaled, 1, "from: scaled ran")
end)

T.case("a missing earlier result is an error naming the step and the file", function()
  os.remove(results_path("study_missing"))
  local s = make("study_missing", {})
  local err = T.raises(function() s:run{ only = "mean" } end, "results of step 'data' are needed")
  T.truthy(err:find("study_missing.json", 1, true), "names the file: " .. err)
end)

T.case("a failing step: error names it, results so far are saved", function()
  local s = study.new{ name = "study_fail", out = dir, results = results_path("study_fail"), quiet = true }
  s:step("ok", function() return { a = 1 } end)
  s:step("boom", function() error("solver diverged at x = 3") end)
  s:step("never", function() error("must not run") end)
  T.raises(function() s:run() end, "step 'boom' failed: ")
  local ok, err = pcall(s.run, s)
  T.truthy(tostring(err):find("solver diverged at x = 3", 1, true), "keeps the message")
  local d = read_json(results_path("study_fail"))
  T.eq(d.steps.ok.result.a, 1, "earlier step saved")
  T.eq(d.steps.boom.status, "failed", "failure recorded")
  T.truthy(d.steps.boom.error:find("solver diverged", 1, true), "error recorded")
  T.eq(d.steps.never, nil, "later step not run")
end)

T.case("a failing step whose failure cannot be saved says both", function()
  local s = study.new{ name = "study_fail_unsaved", out = dir, results = dir .. "/no_such_folder/r.json", quiet = true }
  s:step("boom", function() error("solver diverged at x = 4") end)
  local ok, err = pcall(s.run, s)
  T.eq(ok, false, "the run fails")
  T.truthy(tostring(err):find("solver diverged at x = 4", 1, true), "the step's error comes first: " .. tostring(err))
  T.truthy(tostring(err):find("not recorded", 1, true), "the lost record is said: " .. tostring(err))
end)

T.case("misuse is reported clearly", function()
  T.raises(function() study.new{} end, "'name' is missing")
  local s = study.new{ name = "study_misuse", out = dir, results = results_path("study_misuse"), quiet = true }
  s:step("a", function() return {} end)
  T.raises(function() s:step("a", function() end) end, "already exists")
  T.raises(function() s:step("b") end, "expects a function")
  T.raises(function() s:run{ only = "nope" } end, "unknown step 'nope' (steps: a)")
  s:step("c", function() return 5 end)
  T.raises(function() s:run() end, "return a table of results")
  s = study.new{ name = "study_misuse2", out = dir, results = results_path("study_misuse2"), quiet = true }
  s:step("x", function(ctx) return { v = ctx.results.y } end)
  s:step("y", function() return {} end)
  T.raises(function() s:run() end, "it has not run yet")
end)

T.case("parse_args", function()
  local o = study.parse_args{ "--data", "f.csv", "--only", "kde,screening", "--only", "fit", "--quiet" }
  T.eq(table.concat(o.only, ","), "kde,screening,fit", "only")
  T.eq(o.quiet, true, "quiet")
  T.eq(table.concat(o.rest, ","), "--data,f.csv", "rest")
  T.eq(study.parse_args{ "--from", "fit" }.from, "fit", "from")
  T.raises(function() study.parse_args{ "--only" } end, "--only needs a step name")
end)

T.case("a study with a report writes report.html with its steps", function()
  local s = study.new{ name = "study_report", out = dir, results = results_path("study_report"), quiet = true, report = { title = "R" } }
  s:step("one", function(ctx) ctx.report:section("One"):text("hello") return { v = 1 } end)
  s:run()
  local f = assert(io.open(s.report_path, "rb"))
  local html = f:read("a")
  f:close()
  local X = require "smi.report.xmlcheck"
  T.truthy(X.check(html), "well-formed")
  T.truthy(html:find("Study steps", 1, true) and html:find(">one<", 1, true), "steps table")
  s:step("two", function(ctx) return { w = ctx.results.one.v + 1 } end)
  local r = s:run{ only = "two" }
  T.eq(r.two.w, 2, "partial run with the report")
  T.truthy(s.report_path:find("report-partial.html", 1, true), "partial report kept apart: " .. s.report_path)
  f = assert(io.open(s.report_path, "rb"))
  html = f:read("a")
  f:close()
  T.truthy(not html:find(">One<", 1, true), "a fresh report per run: step one's section is not repeated")
end)

T.case("annotate adds a top-level entry beside the steps, and refuses the file's own fields", function()
  os.remove(results_path("study_annotate")) -- a previous run's file
  local s = make("study_annotate", {})
  T.raises(function() s:annotate("conclusion", { verdict = "valid" }) end, "run the study first", "before the run")
  s:run()
  s:annotate("conclusion", { verdict = "valid", undetermined = {} })
  local d = read_json(results_path("study_annotate"))
  T.eq(d.conclusion.verdict, "valid", "the entry")
  T.eq(d.steps.scaled.result.value, 25.0, "the steps kept")
  T.raises(function() s:annotate("steps", {}) end, "reserved", "a reserved key")
  T.eq(read_json(results_path("study_annotate")).steps.data.result.n, 3, "the file untouched by the refused call")
end)

T.case("a partial run that changes a step's result marks the steps that read it stale", function()
  local calls = {}
  make("study_stale", calls):run()
  -- the same study, but "mean" now computes something else (an edited module, say)
  local s = study.new{ name = "study_stale", out = dir, results = results_path("study_stale"), quiet = true }
  local d0 = read_json(results_path("study_stale"))
  T.truthy(d0.steps.scaled.inputs.results.mean == d0.steps.mean.result_hash, "scaled recorded the result it read")
  T.eq(d0.schema, study.SCHEMA, "schema")
  s:step("data", function() return { x = { 1.5, 2.5, 3.5 }, n = 3 } end)
  s:step("mean", function() return { mean = 99 } end)
  s:step("scaled", function(ctx) return { value = 10 * ctx.results.mean.mean } end)
  local r = s:run{ only = "mean" }
  T.eq(r.mean.mean, 99, "the recomputed step")
  T.raises(function() return r.scaled.value end, "step 'scaled' is stale")
  local d = read_json(results_path("study_stale"))
  T.truthy(d.steps.scaled.stale and d.steps.scaled.stale.reason:find("step 'mean'", 1, true), "marked in results.json")
  T.eq(d.steps.data.stale, nil, "an earlier step it did not touch stays current")
  -- a step reading the stale one is refused, with the command to run
  s:step("report", function(ctx) return { v = ctx.results.scaled.value } end)
  T.raises(function() s:run{ only = "report" } end, "step 'scaled' is stale")
  -- running from the recomputed step on brings everything up to date
  r = s:run{ from = "scaled" }
  T.eq(r.report.v, 990, "up to date")
  T.eq(read_json(results_path("study_stale")).steps.scaled.stale, nil, "mark cleared")
end)

T.case("volatile keys (timings) do not make later steps stale", function()
  local function mk(t)
    local s = study.new{ name = "study_volatile", out = dir, results = results_path("study_volatile"), quiet = true,
                         volatile = { "wall_seconds" } }
    s:step("a", function() return { x = 1, wall_seconds = t } end)
    s:step("b", function(ctx) return { y = ctx.results.a.x + 1 } end)
    return s
  end
  mk(1):run()
  local r = mk(2):run{ only = "a" } -- the same numbers, another timing
  T.eq(r.b.y, 2, "b still current")
  T.eq(read_json(results_path("study_volatile")).steps.b.stale, nil, "not marked")
end)

T.case("a volatile key deeper in the result (a timing per candidate) does not change its hash", function()
  -- smi.improve's refinement step records each candidate's run time inside its decision matrix:
  -- it changed the step's result_hash on every run, so its readers were stale after any rerun.
  local function mk(t)
    local s = study.new{ name = "study_volatile_deep", out = dir, results = results_path("study_volatile_deep"),
                         quiet = true, volatile = { "run_seconds" } }
    s:step("a", function() return { x = 1, candidates = { { name = "c1", run_seconds = t }, { name = "c2", run_seconds = 2 * t } } } end)
    s:step("b", function(ctx) return { y = ctx.results.a.x + 1 } end)
    return s
  end
  mk(0.25):run()
  local h1 = read_json(results_path("study_volatile_deep")).steps.a.result_hash
  local r = mk(0.5):run{ only = "a" } -- the same numbers, other timings
  local d = read_json(results_path("study_volatile_deep"))
  T.eq(d.steps.a.result.candidates[2].run_seconds, 1.0, "the timing is still saved")
  T.eq(d.steps.a.result_hash, h1, "the hash leaves it out")
  T.eq(r.b.y, 2, "b still current")
  T.eq(d.steps.b.stale, nil, "not marked")
end)

T.case("values left out of results.json are listed in name order, whatever the table order", function()
  -- Twelve functions under hashed keys: their traversal order varies from run to run (Lua seeds
  -- its string hashes per state), the listed order must not.
  local name = "study_not_saved_order"
  local s = study.new{ name = name, out = dir, results = results_path(name), quiet = true }
  s:step("many", function(ctx)
    for _, k in ipairs { "k", "b", "h", "a", "l", "e", "c", "j", "f", "i", "d", "g" } do
      ctx:set(k, function() end)
    end
  end)
  s:run()
  local d = read_json(results_path(name))
  local listed = d.steps.many.not_saved
  T.eq(#listed, 12, "all twelve listed")
  local sorted = { table.unpack(listed) }
  table.sort(sorted)
  T.eq(table.concat(listed, ","), table.concat(sorted, ","), "in name order")
  T.eq(listed[1], "many.a (function)", "first by name")
end)

T.finish()
