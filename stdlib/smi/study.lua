-- SPDX-License-Identifier: MIT
--- smi.study: a study as named steps that run in order, are timed, report progress, and save
-- their results to results.json, so that any step can be re-run alone later.
--
--   local study = require "smi.study"
--   local s = study.new{name = "beam", out = smi.out_dir, report = {title = "Beam study"}}
--   s:step("data", function(ctx) return {n = 9, mean = 12.5} end)
--   s:step("fit", function(ctx)
--     local d = ctx.results.data             -- a previous step's results (this run or results.json)
--     ctx:log("fitting %d points", d.n)      -- a progress line on stderr (unless quiet)
--     ctx.report:section("Fit")              -- when the study has a report
--     return {slope = 0.3}                   -- this step's results (or ctx:set("slope", 0.3))
--   end)
--   s:run()                                  -- all steps; writes results.json (+ report.html)
--   s:run{only = "fit"}                      -- "data" comes from the saved results.json
--   s:run(study.parse_args(arg))             -- --only NAME[,NAME] --from NAME --quiet --force
--
-- A whole run reuses every saved step whose inputs (options, data, code, earlier results, the
-- smi-lua binary) are unchanged, up to the first that must run (smi.study_reuse); --force runs all.
--
-- results.json: {schema=2, study=, seed=, order={...}, steps={name={status=, seconds=, result={...},
-- result_hash=, inputs={options=, files=, results=}, stale=}}, provenance=smi.provenance()} (every
-- file read, program, option, library and the build; docs/provenance.md), so that `smi-lua verify
-- results.json` can check a rerun, and a partial run knows which saved steps are still current
-- (smi.study_inputs): it refuses to read a saved step whose inputs changed, naming what changed
-- and the command to run, and marks later steps stale when it recomputes what they read.
-- Values JSON cannot hold (a surrogate model userdata, say) stay available to later steps of the
-- same run, are left out of the file, and are listed under the step's "not_saved".
-- host functions for the stdlib only (the stdlib searcher passes them); taken by syntax and never
-- handed to a global function, which a script may have replaced
local _, _, internal = ...
local json = require "smi.report.json"
local fmt = require "smi.report.format"
local inputs = require "smi.study_inputs"
local reuse = require "smi.study_reuse"
local sorted_keys = inputs.sorted_keys

local doc = require "smi.doc"
doc.add[==[
@ module smi.study
A study as named steps that run in order, are timed, report progress, and save their results to
results.json, so that any step can run again alone later (s:run{only = "fit"}).

results.json, schema 2 (smi.study.SCHEMA; docs/provenance.md lists every field): "schema" (the
layout's version; a file without it is schema 1, from an older smi-lua; a newer one is refused);
"study", "seed", "order"; "steps" by name, each {status = "ok" | "failed", seconds, result,
result_hash, inputs = {options = {seed, arguments}, files = {[path] = {kind, hash, size}},
results = {[earlier step] = hash}}, stale = {reason, command} when a partial run changed what it
read, not_saved}; "provenance" (smi.provenance(): every file read, program, option, library and
the build). A partial run (only, from) refuses to read a saved step whose inputs changed, naming
the change and the command to run, and marks later steps stale when it recomputes what they
read; a stale step's results are never returned as current. A whole run reuses the saved steps
whose inputs (options, data files, the script and every Lua file it loaded, earlier results, the
smi-lua binary) are unchanged, in order up to the first step that must run; that step and every
later one run again, and run{force = true} (--force) runs them all (docs/provenance.md).
]==]
local M = {}

-- An error in the user's data, options or declaration: one line, no traceback (smi.fail); with
-- `trace`, an error in the user's code carried out of a step with its own traceback.
local function fail(msg, trace)
  if type(smi) == "table" and type(smi.fail) == "function" then smi.fail(msg, trace) end
  error(msg, 0)
end
local function failure(e)
  return type(smi) == "table" and type(smi.failure) == "function" and smi.failure(e) or nil
end

local Study = {}
Study.__index = Study

-- What produced this run's numbers (host function; absent when run outside smi-lua).
local function provenance(opts)
  if type(smi) == "table" and type(smi.provenance) == "function" then return smi.provenance(opts) end
  return nil
end

local function now()
  -- wall time when the host offers it (a solver's child processes use no CPU time of ours)
  if type(smi) == "table" and type(smi.now) == "function" then return smi.now(), "wall" end
  return os.clock(), "cpu"
end

doc.add[==[
@ smi.study.new(opts) -> study
A new study; add steps with s:step and run them with s:run.
options:
  name = (required)    -- the study's name (in results.json and messages)
  out = smi.out_dir    -- the folder of results.json and report.html
  results = nil        -- the path of results.json (default <out>/results.json)
  quiet = nil          -- no progress lines (default: smi.quiet)
  seed = smi.seed      -- recorded in results.json
  volatile = nil       -- result keys that differ between identical runs (timings, counts of reused
                       -- solver runs), e.g. {"wall_seconds"}: left out, at any depth, of the result
                       -- hash that decides whether later steps are stale (every step; steps add their own)
  report = nil         -- {title =, subtitle =, ...}: creates ctx.report (smi.report), written at the end
returns: a study with the methods smi.study:step, :run, :load
errors: no name ("expects {name = \"...\", out = folder}")
example:
  local study = require "smi.study"
  local s = study.new{name = "doc", out = smi.out(), results = smi.out("doc_study.json"), quiet = true}
  s:step("data", function(ctx) return {n = 3} end)
  print(s:run().data.n)
]==]
--- opts: name (required), out (folder for results.json/report.html; default smi.out_dir or "."),
-- results (path of results.json, default <out>/results.json), quiet, seed (recorded; default
-- smi.seed), report ({title=, subtitle=, ...}: creates ctx.report, written at the end of run).
function M.new(opts)
  if type(opts) ~= "table" or type(opts.name) ~= "string" or opts.name == "" then
    error("smi.study.new: expects {name = \"...\", out = folder}; 'name' is missing", 2)
  end
  local out = opts.out or (type(smi) == "table" and smi.out_dir) or "."
  out = tostring(out):gsub("/+$", "")
  if out == "" then out = "/" end
  local s = setmetatable({
    name = opts.name, out = out, steps = {}, by_name = {},
    results_path = opts.results or (out .. "/results.json"),
    quiet = opts.quiet, seed = opts.seed or (type(smi) == "table" and smi.seed) or nil,
    report_opts = opts.report, volatile = opts.volatile or {},
  }, Study)
  -- the results file is this study's output: reading it back is not an input of the run
  if internal ~= nil then internal.not_input(s.results_path) end
  return s
end

doc.add[==[
@ smi.study:step(name [, opts], fn) -> study
Adds a step. fn(ctx) returns a table of results (or sets them with ctx:set(key, value)); ctx.results
holds the earlier steps' results (from this run or results.json), ctx:log(fmt, ...) writes a
progress line, ctx.report is the study's report when it has one. A step with nothing to do now
returns ctx:skip("why") (or {skipped = true, reason = "why"}): it is recorded and reported as
"not run" with that reason, never as passed.
options:
  description = nil   -- a sentence on what the step does
  volatile = nil      -- result keys left out of its result hash (as in smi.study.new)
returns: the study (calls chain)
errors: a name already used; fn not a function
example:
  local s = require("smi.study").new{name = "doc_step", out = smi.out(), results = smi.out("doc_step.json"), quiet = true}
  s:step("a", function() return {x = 1} end):step("b", function(ctx) return {y = ctx.results.a.x + 1} end)
  print(s:run().b.y)
]==]
--- Adds a step: s:step(name, fn) or s:step(name, {description = ...}, fn). fn(ctx) returns a
-- table of results (or nil, using ctx:set).
function Study:step(name, opts, fn)
  if fn == nil then opts, fn = {}, opts end
  if type(name) ~= "string" or name == "" then error("study:step: the step name must be a non-empty string", 2) end
  if type(fn) ~= "function" then error(("study:step '%s': expects a function(ctx)"):format(name), 2) end
  if self.by_name[name] then error(("study:step: a step named '%s' already exists (step names must be unique)"):format(name), 2) end
  local st = { name = name, fn = fn, opts = opts or {}, index = #self.steps + 1 }
  self.steps[#self.steps + 1] = st
  self.by_name[name] = st
  return self
end

function Study:_quiet()
  if self.quiet ~= nil then return self.quiet end
  return type(smi) == "table" and smi.quiet == true
end

function Study:_say(fmt_, ...)
  if self:_quiet() then return end
  io.stderr:write(("[%s] " .. fmt_ .. "\n"):format(self.name, ...))
  io.stderr:flush()
end

doc.add[==[
@ smi.study:load() -> results | nil, why
The saved results.json as a table (what steps not run in a partial run read).
returns: the decoded table, or nil and the reason (no file yet, invalid JSON)
errors: none
example:
  local s = require("smi.study").new{name = "doc_load", out = smi.out(), results = smi.out("doc_load.json"), quiet = true}
  s:step("a", function() return {x = 2} end)
  s:run()
  print(s:load().steps.a.result.x)
]==]
--- The saved results.json as a table, or nil and the reason.
function Study:load()
  local f, err = io.open(self.results_path, "rb")
  if not f then return nil, "cannot read " .. self.results_path .. ": " .. tostring(err) end
  local text = f:read("a")
  f:close()
  local ok, data = pcall(json.decode, text)
  if not ok then fail(("study '%s': %s is not valid JSON (%s); delete it and run the whole study"):format(self.name, self.results_path, data)) end
  if type(data) ~= "table" or type(data.steps) ~= "table" then
    fail(("study '%s': %s has no 'steps' table; is it a results file of smi.study?"):format(self.name, self.results_path))
  end
  local schema = M.SCHEMA
  if data.schema ~= nil and (math.type(data.schema) ~= "integer" or data.schema > schema) then
    fail(("study '%s': %s has schema %s, newer than this smi-lua reads (%d); run it with the smi-lua that wrote it, or run the whole study again"):format(
      self.name, self.results_path, tostring(data.schema), schema))
  end
  return data
end

doc.add[==[
@ smi.study:annotate(key, value)
Adds a top-level entry to the saved results.json beside the steps (a study's conclusion, say, where
outside checks read it), after s:run. The file is rewritten whole (as the steps' results are).
key: a name other than the file's own fields (schema, study, seed, order, steps, provenance)
returns: nothing
errors: no results.json yet (run the study first); a reserved key
example:
  local s = require("smi.study").new{name = "doc_annotate", out = smi.out(), results = smi.out("doc_annotate.json"), quiet = true}
  s:step("a", function() return {x = 2} end)
  s:run()
  s:annotate("conclusion", {verdict = "valid"})
  print(s:load().conclusion.verdict)
]==]
local RESERVED = { study = true, seed = true, order = true, steps = true, provenance = true, schema = true }
--- Adds a top-level entry to the saved results.json (see the doc above).
function Study:annotate(key, value)
  if type(key) ~= "string" or RESERVED[key] then
    error(("study '%s': annotate: '%s' is not a free top-level key of results.json (reserved: schema, study, seed, order, steps, provenance)"):format(self.name, tostring(key)), 2)
  end
  if type(smi) == "table" and smi.dry_run then return end -- a dry run writes no results (as _save)
  local saved, why = self:load()
  if not saved then error(("study '%s': annotate('%s'): %s; run the study first"):format(self.name, key, why), 2) end
  saved[key] = value
  self:_save(saved)
end

-- results.json is replaced whole or not at all (smi.file: temporary file, checked writes, fsync,
-- rename): a full disk or a kill mid-write leaves the previous file, and the error says so.
function Study:_save(saved)
  if type(smi) == "table" and smi.dry_run then return end -- a dry run's numbers are not results
  saved.schema = M.SCHEMA
  saved.provenance = self:_provenance(saved) -- what was read so far: asked again at every save
  local text = json.encode(saved, { indent = "  ", root = "results" })
  require("smi.file").write(self.results_path, text .. "\n", ("study '%s'"):format(self.name))
end

-- Which steps to run, from run{only=..., from=...}.
function Study:_selection(opts)
  local selected = {}
  local function need(name, what)
    if not self.by_name[name] then
      local names = {}
      for i, st in ipairs(self.steps) do names[i] = st.name end
      local near = type(smi) == "table" and type(smi._closest) == "function" and smi._closest(tostring(name), names) or {}
      fail(("study '%s': --%s names an unknown step '%s'%s (steps: %s)"):format(self.name, what, tostring(name),
        near[1] and (" (did you mean " .. near[1] .. "?)") or "", table.concat(names, ", ")))
    end
    return self.by_name[name]
  end
  if opts.only ~= nil and opts.from ~= nil then fail(("study '%s': give --only or --from, not both"):format(self.name)) end
  if opts.only ~= nil then
    local list = type(opts.only) == "table" and opts.only or { opts.only }
    for _, n in ipairs(list) do selected[need(n, "only").name] = true end
  elseif opts.from ~= nil then
    local first = need(opts.from, "from").index
    for i = first, #self.steps do selected[self.steps[i].name] = true end
  else
    for _, st in ipairs(self.steps) do selected[st.name] = true end
  end
  return selected
end

-- The results saved so far, to merge this run into. Every run merges into them: a step that
-- does not run now (not selected, or not reached because an earlier one failed or the run was
-- stopped) keeps its saved result, so results.json never shrinks. A file that does not parse is
-- an error for a partial run (its steps are needed) and is replaced by a full run.
function Study:_saved_results(partial)
  local saved = { schema = M.SCHEMA, study = self.name, seed = self.seed, order = {}, steps = {} }
  local old, why
  if partial then
    old, why = self:load()
  else
    local okl, o, w = pcall(self.load, self)
    if okl then old, why = o, w else why = tostring(o) end
  end
  if old then
    saved.steps = old.steps
    if old.schema == nil and partial then
      self.load_problem = self.results_path .. " was written before results files had a schema (schema 1): its steps' inputs were not recorded, so whether they are current is unknown; run the whole study once"
      self.old_schema = true
    end
  else
    self.load_problem = why
  end
  for i, st in ipairs(self.steps) do saved.order[i] = st.name end
  return saved
end

-- Whether saved step `name` is still current for this run: nil, or why not (a sentence). A saved
-- step is current when it succeeded, ran with this run's options, its data files hash the same
-- now, and every step it read is current with the result it read (this run's when recomputed).
-- Memoized per run in self.currency.
function Study:_why_not_current(name, saved, live_hash)
  local memo = self.currency
  if memo[name] ~= nil then return memo[name] or nil end
  memo[name] = false -- a cycle cannot happen (steps read earlier steps), but never loop
  local s = saved.steps[name]
  local why
  if not s or s.status ~= "ok" then
    why = ("step '%s' has no successful saved result"):format(name)
  elseif s.stale then
    why = ("step '%s' is stale: %s"):format(name, tostring(s.stale.reason))
  elseif inputs.available() and not s.inputs then
    why = ("step '%s' was saved without its inputs (%s)"):format(name, self.old_schema and "results.json of schema 1, from an older smi-lua" or "by an older smi.study")
    self.old_schema = true -- the command to give is then the whole study: no step before it is known current
  elseif s.inputs then
    local change = inputs.options_change(s.inputs.options, self.options)
    if change ~= "" then why = ("step '%s' ran with other options: %s"):format(name, change) end
    why = why or (function()
      local f = inputs.files_change(s.inputs.files)
      return f and ("step '%s' read %s"):format(name, f)
    end)()
    if not why then
      local recorded = s.inputs.results or {}
      for _, dep in ipairs(sorted_keys(recorded)) do -- name order: the reason given is the same every run
        local h = recorded[dep]
        local now = live_hash[dep] or (saved.steps[dep] and saved.steps[dep].result_hash)
        if live_hash[dep] == nil then
          local w = self:_why_not_current(dep, saved, live_hash)
          if w then why = ("step '%s' read step '%s', and %s"):format(name, dep, w) break end
        end
        if now ~= h then
          why = ("step '%s' read the results of step '%s', which %s"):format(name, dep,
            live_hash[dep] and "this run recomputed with a different result" or "changed since")
          break
        end
      end
    end
  end
  memo[name] = why or false
  return why
end

-- ctx.results: read-only; this run's results first (`live`, with values JSON cannot hold), then
-- the saved results of steps not selected now, if they are still current (else an error naming
-- what changed and the command to run); a missing one is an error saying why. Every read is
-- noted in study.reading (the running step's inputs).
local function results_view(study, selected, saved, live)
  return setmetatable({}, {
    __index = function(_, name)
      if live[name] ~= nil then
        if study.reading then study.reading[name] = study.live_hash[name] end
        return live[name]
      end
      -- a step selected in this run is read from this run only, never from an older file
      local s = not selected[name] and saved.steps[name] or nil
      if s and s.status == "ok" and s.result ~= nil then
        local why = study:_why_not_current(name, saved, study.live_hash)
        if why then
          fail(("study '%s': the saved results of step '%s' cannot be used: %s. Run: %s"):format(study.name, name, why,
            inputs.rerun_command(not study.old_schema and name or nil)))
        end
        if study.reading then study.reading[name] = s.result_hash or study:_result_hash(name, s.result) end
        return s.result
      end
      local why = not study.by_name[name] and "there is no such step"
        or (selected[name] and "it has not run yet in this run (steps run in the order they were added)")
        or ("it did not run now and " .. (study.load_problem or (study.results_path .. " holds no successful result of it")))
      fail(("study '%s': results of step '%s' are needed but %s"):format(study.name, tostring(name), why))
    end,
    __newindex = function() error("study: ctx.results is read-only; return a table from the step instead", 2) end,
  })
end

-- A fresh report for every run, from the options given to new{report = ...}.
function Study:_fresh_report()
  if not self.report_opts then return end
  local report = require "smi.report"
  local ro = {}
  for k, v in pairs(self.report_opts) do ro[k] = v end
  ro.title = ro.title or self.name
  ro.out = ro.out or self.out
  self.report = report.new(ro)
end

-- The ctx a step function receives.
local function step_context(study, st, results)
  local ctx = {
    name = st.name, study = study, results = results, out = study.out, seed = study.seed,
    report = study.report, result = {},
  }
  function ctx.log(c, fmt_, ...)
    if c ~= ctx then return ctx:log(c, fmt_, ...) end -- allow ctx.log("...") too
    if not study:_quiet() then
      io.stderr:write(("[%s]   %s: %s\n"):format(study.name, st.name, fmt_:format(...)))
      io.stderr:flush()
    end
  end
  function ctx.set(c, key, value) c.result[key] = value end
  -- a step that has nothing to do now: return ctx:skip("why") (the record {skipped = true,
  -- reason = ...}, which a step may also return itself)
  function ctx.skip(c, reason)
    if c ~= ctx then reason = c end
    return { skipped = true, reason = tostring(reason or "no reason given") }
  end
  return ctx
end

-- Runs step st's function: ok, its return value (or the error), the traceback, seconds, clock.
local function call_step(st, ctx)
  local t0, clock = now()
  local trace
  local ok, ret = xpcall(st.fn, function(e)
    -- a failure (bad data, options, declaration) is said in one line; an error in code keeps
    -- where it happened
    -- (the stdlib's own error(message, 0) is a failure too: internal.as_failure looks at who raised it)
    if internal ~= nil then e = internal.as_failure(e) end
    if not failure(e) then trace = debug and debug.traceback and debug.traceback(tostring(e), 2) or tostring(e) end
    return e
  end, ctx)
  local dt = now() - t0
  if ok then
    if ret ~= nil and type(ret) ~= "table" then
      ok, ret = false, ("step returned a %s; return a table of results (or nil and use ctx:set)"):format(type(ret))
    end
  end
  return ok, ret, trace, dt, clock
end

-- A failed step: the failure is recorded (a result saved by an earlier run is kept beside it),
-- the results saved, and the error raised with the step named.
function Study:_step_failed(st, k, nsel, saved, ret, trace, dt, clock)
  local prev = saved.steps[st.name]
  if prev and prev.status == "failed" then prev = prev.previous end
  saved.steps[st.name] = { status = "failed", seconds = dt, clock = clock, error = tostring(ret), traceback = trace,
                           previous = prev }
  self.timings[#self.timings + 1] = { st.name, "failed", dt }
  -- the step's error comes first; a results file that could not be written is said after it
  local saved_ok, save_err = pcall(self._save, self, saved)
  self:_say("step %d/%d %s FAILED after %s", k, nsel, st.name, fmt.seconds(dt))
  local also = saved_ok and "" or ("; and the failure was not recorded: " .. tostring(save_err))
  if type(smi) == "table" and type(smi.progress_label) == "function" then smi.progress_label() end
  local msg = ("study '%s': step '%s' failed: %s%s"):format(self.name, st.name, tostring(ret), also)
  -- an error in code goes on with the traceback of where it happened (not of this line)
  fail(msg, not failure(ret) and trace and trace:match("stack traceback:.*$") or nil)
end

-- The hash of a step's saved result that later steps record when they read it: every key but the
-- volatile ones, at any depth (timings and the like, which differ between identical runs and would
-- make every later step stale after any rerun; a timing inside a list of records counts too).
local function without(v, skip)
  if type(v) ~= "table" then return v end
  local c = {}
  for k, x in pairs(v) do if not skip[k] then c[k] = without(x, skip) end end
  return c
end

function Study:_result_hash(name, result)
  local skip = {}
  for _, k in ipairs(self.volatile) do skip[k] = true end
  local st = self.by_name[name]
  for _, k in ipairs(st and st.opts.volatile or {}) do skip[k] = true end
  if type(result) ~= "table" or next(skip) == nil then return inputs.hash(result) end
  return inputs.hash(without(result, skip))
end

-- Runs step st (the k-th of nsel selected) and saves its result: all of it in `live`, what
-- JSON can hold in results.json.
function Study:_run_step(st, k, nsel, results, saved, live)
  self:_say("step %d/%d %s ...", k, nsel, st.name)
  -- the progress lines of the step's work (calibration, solver runs) say whose they are
  if type(smi) == "table" and type(smi.progress_label) == "function" then
    smi.progress_label(("[%s] %s"):format(self.name, st.name))
  end
  local ctx = step_context(self, st, results)
  local seq0 = inputs.mark()
  local report_mark = reuse.begin(self)
  self.reading = {} -- the earlier steps' results this step reads (results_view notes them)
  local ok, ret, trace, dt, clock = call_step(st, ctx)
  local reads = self.reading
  self.reading = nil
  self.currency = {} -- what is current may change with this step's result
  if not ok then self:_step_failed(st, k, nsel, saved, ret, trace, dt, clock) end
  local result = ctx.result
  for key, v in pairs(ret or {}) do result[key] = v end
  live[st.name] = result
  -- keep only what JSON can hold in the file
  local skipped = {}  -- in the encoder's key order (the file's), the same every run
  local text = json.encode(result, { skip = true, skipped = skipped, root = st.name })
  -- a step that returned {skipped = true, reason = ...} did not run: its record (status "ok", so
  -- that later steps can read why) says not_run, and the report and the console say "not run"
  local not_run = result.skipped == true and tostring(result.reason or "no reason given") or nil
  -- its inputs: the options, the data files read before the steps and while it ran, the results read
  local files = {}
  for path, d in pairs(self.preamble_files) do files[path] = d end
  for path, d in pairs(inputs.files_since(seq0)) do files[path] = d end
  local decoded = json.decode(text)
  local result_hash = self:_result_hash(st.name, decoded)
  self.live_hash[st.name] = result_hash
  saved.steps[st.name] = { status = "ok", seconds = dt, clock = clock, result = decoded, result_hash = result_hash,
                           inputs = { options = self.options, files = files, results = reads },
                           not_saved = #skipped > 0 and skipped or nil, not_run = not_run }
  reuse.record(self, st, saved.steps[st.name], report_mark) -- what a later run compares to reuse it
  self.timings[#self.timings + 1] = { st.name, not_run and "not run" or "ok", dt, not_run }
  self:_save(saved)
  if not_run then
    self:_say("step %d/%d %s not run: %s", k, nsel, st.name, not_run)
  else
    self:_say("step %d/%d %s done in %s%s", k, nsel, st.name, fmt.seconds(dt),
      #skipped > 0 and (" (not saved: " .. table.concat(skipped, ", ") .. ")") or "")
  end
end

doc.add[==[
@ smi.study:run([opts]) -> results
Runs the steps (all, or only some) and returns the results by step name. Steps not run keep their
saved results; results.json is rewritten after every step, so a failure keeps what was done; a
report (if any) is written at the end, report-partial.html after a partial run.
options:
  only = nil     -- a step name or a list: run only these
  from = nil     -- run this step and every later one
  force = nil    -- run every step, even those a whole run would reuse (inputs unchanged)
  quiet = nil    -- no progress lines for this run
returns: a table {step name = results}
errors: a step's error, with the step named; only/from naming an unknown step (the steps are
  listed); only and from together
example:
  local s = require("smi.study").new{name = "doc_run", out = smi.out(), results = smi.out("doc_run.json"), quiet = true}
  s:step("a", function() return {x = 1} end)
  s:step("b", function(ctx) return {y = 2} end)
  s:run()
  print(s:run{only = "b"}.a.x)
]==]
--- Runs the steps (all, or opts.only = name | {names}, or opts.from = name) and returns the
-- results by step name. Steps not run keep their saved results; results.json is rewritten
-- (atomically) after every step, so a failure keeps what was done. report.html is written only
-- when every step of a full run succeeded (a partial run writes report-partial.html).
function Study:run(opts)
  opts = opts or {}
  if opts.quiet ~= nil then self.quiet = opts.quiet end
  if #self.steps == 0 then error(("study '%s': no steps; add some with study:step(name, fn)"):format(self.name), 2) end
  self.console_warnings_from = type(smi) == "table" and type(smi.warnings) == "function" and #smi.warnings() or 0
  local selected = self:_selection(opts)
  -- one study per output folder at a time (the lock names the holder; it lasts until exit)
  if type(smi) == "table" and type(smi.lock_out) == "function" then smi.lock_out(self.out) end
  local partial = false
  for _, st in ipairs(self.steps) do if not selected[st.name] then partial = true end end
  local saved = self:_saved_results(partial)
  local live = {} -- results of this run, with values JSON cannot hold
  self.options = inputs.options(self.seed) -- what every step's saved inputs are compared with
  self.preamble_files = inputs.preamble() -- data read before the steps: an input of every step
  self.live_hash, self.currency = {}, {}
  local results = results_view(self, selected, saved, live)
  if partial then self:_check_kept(selected, saved) end
  self:_fresh_report()

  local nsel, k = 0, 0
  for _, st in ipairs(self.steps) do if selected[st.name] then nsel = nsel + 1 end end
  local t_start = now()
  self.timings = {}
  -- a whole run reuses the saved steps whose inputs are unchanged (smi.study_reuse); a partial
  -- run runs the steps it names
  local kept, why_run = {}, nil
  if not partial then kept, why_run = reuse.plan(self, saved, opts.force) end
  if next(kept) then
    local n = 0
    for _ in pairs(kept) do n = n + 1 end
    self:_say("%d of %d step(s) reused: their inputs are unchanged (--force runs them all)", n, nsel)
  end
  if why_run and next(saved.steps) then self:_say("%s", why_run) end
  for _, st in ipairs(self.steps) do
    if selected[st.name] then
      k = k + 1
      if kept[st.name] then
        reuse.reuse(self, st, saved, live)
        self:_say("step %d/%d %s reused", k, nsel, st.name)
      else
        self:_run_step(st, k, nsel, results, saved, live)
      end
    end
  end
  local all_kept = true
  for _, st in ipairs(self.steps) do all_kept = all_kept and kept[st.name] == true end
  if all_kept then self:_save(saved) end -- nothing ran: the file still gets this run's provenance
  local total = now() - t_start
  if partial then self:_mark_stale(selected, saved) end
  self:_say("%d step(s) in %s; results in %s", nsel, fmt.seconds(total), self.results_path)
  for _, t in ipairs(self.timings) do self:_say("  %-24s %-6s %s", t[1], t[2], fmt.seconds(t[3])) end
  if type(smi) == "table" and type(smi.progress_label) == "function" then smi.progress_label() end
  if self.report and not (type(smi) == "table" and smi.dry_run) then self:_finish_report(partial, selected, total, saved) end
  self:_console_end()

  local out = {}
  for _, st in ipairs(self.steps) do
    local s = saved.steps[st.name]
    if live[st.name] ~= nil or not (s and s.stale) then
      local ok, v = pcall(function() return results[st.name] end)
      if ok then out[st.name] = v end
    end
  end
  -- a stale step's saved result is never handed out as if current: reading it says why
  return setmetatable(out, { __index = function(_, name)
    local s = saved.steps[name]
    if s and s.stale then
      error(("study '%s': step '%s' is stale (%s); its saved results are not used. Run: %s"):format(self.name, name,
        tostring(s.stale.reason), s.stale.command or inputs.rerun_command(name)), 2)
    end
    return nil
  end })
end

-- Before a partial run: every saved step that a selected step read last time must still be
-- current, else the run stops before it starts, naming what changed and the command to run
-- (reads not known in advance are checked when they happen, in results_view).
function Study:_check_kept(selected, saved)
  for _, st in ipairs(self.steps) do
    local rec = selected[st.name] and saved.steps[st.name]
    for _, dep in ipairs(sorted_keys(rec and rec.inputs and rec.inputs.results)) do -- the same error every run
      if not selected[dep] and saved.steps[dep] then
        local why = self:_why_not_current(dep, saved, self.live_hash)
        if why then
          error(("study '%s': step '%s' reads the saved results of step '%s', which cannot be used: %s. Run: %s"):format(
            self.name, st.name, dep, why, inputs.rerun_command(not self.old_schema and dep or nil)), 0)
        end
      end
    end
  end
end

-- After a partial run: a saved step that read what this run recomputed (or whose own inputs
-- changed) is marked stale in results.json, with the reason and the command that brings it up to
-- date; a step found current again loses its mark.
function Study:_mark_stale(selected, saved)
  self.currency = {}
  local first
  local groups, order = {}, {} -- steps by reason (an option change makes them all stale alike)
  for _, st in ipairs(self.steps) do
    local s = saved.steps[st.name]
    if not selected[st.name] and s and s.status == "ok" then
      s.stale = nil
      local why = self:_why_not_current(st.name, saved, self.live_hash)
      if why then
        first = first or st.name
        s.stale = { reason = why, command = inputs.rerun_command(first) }
        local short = why:gsub("^step '[^']*' ", "")
        if not groups[short] then groups[short] = {}; order[#order + 1] = short end
        table.insert(groups[short], st.name)
      end
    end
  end
  if first then -- said even when quiet: the saved results of these steps are no longer the study's answer
    local names = {}
    for _, r in ipairs(order) do for _, n in ipairs(groups[r]) do names[#names + 1] = n end end
    io.stderr:write(("[%s] now stale, their saved results will not be used: %s\n"):format(self.name, table.concat(names, ", ")))
    for _, r in ipairs(order) do
      io.stderr:write(("[%s]   %s: %s\n"):format(self.name, table.concat(groups[r], ", "), r))
    end
    io.stderr:write(("[%s] to bring them up to date, run: %s\n"):format(self.name, inputs.rerun_command(first)))
  end
  self:_save(saved) -- the marks (set or cleared) go into results.json
end

-- The provenance saved with the results: this run's (every file read, program, option, library,
-- the build) plus the data files of saved steps that did not run now (their results depend on them).
function Study:_provenance(saved)
  local p = provenance()
  if not p then return nil end
  p.files = p.files or {}
  for _, name in ipairs(sorted_keys(saved.steps)) do -- a path two steps recorded: the same one wins every run
    local s = saved.steps[name]
    for path, d in pairs(s.inputs and s.inputs.files or {}) do
      if p.files[path] == nil then p.files[path] = d end
    end
  end
  return p
end

-- Appends the step timings and the provenance, then writes report.html next to results.json
-- (report-partial.html after a run of only some steps).
function Study:_finish_report(partial, selected, total, saved)
  local r = self.report
  if partial then
    local names = {}
    for _, st in ipairs(self.steps) do if selected[st.name] then names[#names + 1] = st.name end end
    r:callout("Partial run: only " .. table.concat(names, ", ") .. "; the other steps' results were read from " .. self.results_path .. ".", "info")
  end
  r:section("Study steps")
  local rows = {}
  for _, t in ipairs(self.timings) do
    local badge = ({ ok = { status = "pass", text = "ran" }, failed = { status = "fail", text = "failed" },
                     reused = { status = "info", text = "reused: inputs unchanged" } })[t[2]]
      or { status = "skip", text = t[4] }
    rows[#rows + 1] = { t[1], badge, (t[2] == "not run" or t[2] == "reused") and "" or t[3] }
  end
  r:table{ caption = ("Steps of this run, %s in total; a step not run says why."):format(fmt.seconds(total)),
           columns = { "Step", "Status", { title = "Time (s)", format = "%.2f" } }, rows = rows }
  -- what produced the numbers comes last: every file and program with its hash
  require("smi.report.provenance").begin(r):fill(self:_provenance(saved), { study = self.name, results = self.results_path })
  r:provenance{ study = self.name, seed = self.seed, results = self.results_path }
  local p = provenance{ files = false }
  if p then
    local libs = {}
    for _, l in ipairs(p.libraries) do
      libs[l.name] = ("%s, %s, %s, %s"):format(l.version, l.hash:sub(1, 19), l.commit and ("commit " .. l.commit:sub(1, 12)) or "no commit", l.path)
    end
    r:provenance{ smi_lua = p.smi_lua, libraries = next(libs) and libs or "none" }
  end
  -- a partial run must not overwrite the full report
  self.report_path = r:write(self.out .. (partial and "/report-partial.html" or "/report.html"))
  -- the verdicts are the study's answer, not progress: printed on stdout even when quiet
  local words = require("smi.report.html").STATUS_TEXT
  local gone = r:_superseded()
  for i, it in ipairs(r.items) do
    if it.kind == "verdict" and not gone[i] then
      io.stdout:write(("%-7s %s%s\n"):format(words[it.status], it.name, it.detail and (": " .. it.detail) or ""))
      for _, c in ipairs(it.checks or {}) do
        io.stdout:write(("        %s: %s%s\n"):format(c.name, words[c.status]:lower(), c.detail and (" (" .. c.detail .. ")") or ""))
      end
      if it.governs then io.stdout:write("        ", it.governs, "\n") end
    end
  end
  local n, counted = r:tally()
  if n.pass + n.fail + n.warn + n.inconclusive + n.skip > 0 then io.stdout:write(counted, "\n") end
end

-- The end of a run on the console: the distinct warnings in full, grouped with their counts
-- (on stderr, unless quiet: --quiet keeps them in the report and smi.warnings()), then the files
-- to open, results.json and the report, on stdout, piped or not, --quiet or not (only a study
-- made with quiet = true prints nothing).
function Study:_console_end()
  local groups
  if self.report then
    groups = self.report:warning_groups()  -- superseded sections' too: each group names its sections
  elseif type(smi) == "table" and type(smi.warnings) == "function" then
    local entries, all = {}, smi.warnings()
    for k = (self.console_warnings_from or 0) + 1, #all do entries[#entries + 1] = { text = all[k] } end
    groups = require("smi.report.warnings").group(entries)
  end
  if groups and #groups > 0 and not self:_quiet() then
    local total = 0
    for _, g in ipairs(groups) do total = total + g.count end
    io.stderr:write(("[%s] %d warning%s (%d distinct):\n"):format(self.name, total, total == 1 and "" or "s", #groups))
    for _, line in ipairs(require("smi.report.warnings").lines(groups)) do io.stderr:write(line, "\n") end
    io.stderr:flush()
  end
  -- (a study its code made silent, quiet = true, prints nothing: a doc example, a test)
  if (type(smi) == "table" and smi.dry_run) or self.quiet == true then return end
  io.stdout:write(("results: %s\n"):format(self.results_path))
  if self.report_path then io.stdout:write(("report:  %s\n"):format(self.report_path)) end
  io.stdout:flush()
end

doc.add[==[
@ smi.study.parse_args(argv) -> opts
Splits command-line arguments: --only NAME[,NAME] (repeatable), --from NAME, --quiet, --force; the
rest is kept in opts.rest. (smi.options with options.study_steps does the same and also checks the
study's own options.)
returns: {only =, from =, quiet =, rest = {...}}
errors: --only or --from without a step name
example:
  local study = require "smi.study"
  local o = study.parse_args{"--only", "fit,check", "--quick"}
  print(#o.only, o.rest[1])
]==]
--- Splits command-line arguments: --only NAME[,NAME...] (repeatable), --from NAME, --quiet;
-- everything else is kept, in order, in .rest (for the study's own options).
function M.parse_args(argv)
  -- one parser (smi.options) over the one list of the steps' options (options.study_steps);
  -- everything else is kept in o.rest for the study's own parser
  local o, err = require("smi.options").check(argv, { rest = true, require("smi.options").study_steps })
  if not o then fail("study: " .. err) end
  return o
end

--- The version of results.json's layout this smi.study writes and reads (docs/provenance.md).
M.SCHEMA = type(smi) == "table" and smi.results_schema or 2

if type(smi) == "table" and smi.study == nil then smi.study = M end
return M
