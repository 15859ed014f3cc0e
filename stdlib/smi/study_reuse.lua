-- SPDX-License-Identifier: MIT
--- smi.study_reuse: a whole run of a study reuses the saved steps whose inputs are all as they were,
-- so that a rerun with nothing changed costs the script's top level and the report's rewrite.
--
-- A step's reuse key is what its saved record holds (smi.study_inputs: the options, the data files
-- it and the script's top level read, the results of earlier steps it read) plus two keys saved
-- for reuse only:
--   inputs.code   = {[path] = {kind, hash, size}}  -- the script and every Lua file read from disk
--                                                  -- up to the step's end (modules, libraries, a
--                                                  -- stdlib loaded with --stdlib-dir)
--   inputs.binary = "sha256:..."                   -- this smi-lua's executable (the embedded stdlib,
--                                                  -- the kernels, the version and the build)
-- Reuse goes in step order and stops at the first step that must run: it and every later step run
-- again (a step may read any earlier one, and a module's state or a file in the output folder is
-- not a recorded input, so nothing after a recomputed step is trusted). A step that kept values
-- JSON cannot hold (not_saved) is reused only when every later step is too, since a step that
-- runs may need them.
--
-- What a step wrote into the study's report is saved beside results.json (".<name>.replay.json",
-- not an input of the run) and replayed when the step is reused, so the report is the same page;
-- a step whose report part JSON cannot hold exactly (checked by rendering both) is never reused.
-- Why the code counts although a partial run (--only) ignores it: a partial run is the user
-- choosing what runs; reuse is the study choosing for the user, so it must not trust anything
-- that could change a result.
local json = require "smi.report.json"
local inputs = require "smi.study_inputs"

local M = {}

-- The host's internal functions (the stdlib searcher passes them to stdlib modules only; see
-- smi.study_inputs). Taken from `...` by syntax, never handed to a global function.
local _, _, internal = ...
local host = internal ~= nil

-- Kinds of recorded files that are code. Embedded stdlib modules are covered by the binary's hash.
local CODE = { script = true, lua = true, stdlib = true }

--- The code read so far: {[path] = {kind, hash, size}}.
function M.code_files()
  local out = {}
  if not host then return out end
  for path, d in pairs(internal.inputs(0).files) do
    if CODE[d.kind] and not path:match("^embedded:") then
      out[path] = { kind = d.kind, hash = d.hash, size = d.size, large = d.large, mtime = d.mtime }
    end
  end
  return out
end

--- The hash of the running smi-lua executable (once per study object).
function M.binary(study)
  if not host then return nil end
  if study.binary_hash == nil then study.binary_hash = internal.digest("", "binary").hash end
  return study.binary_hash
end

--- Where the replayed report parts live: beside results.json, hidden.
function M.replay_path(study)
  local dir, base = study.results_path:match("^(.*)/([^/]*)$")
  if not dir then dir, base = ".", study.results_path end
  return ("%s/.%s.replay.json"):format(dir == "" and "/" or dir, (base:gsub("%.json$", "")))
end

-- The replay file is an output of the run, like results.json: never one of its inputs.
local function not_input(study)
  if study.replay_not_input or not host then return end
  internal.not_input(M.replay_path(study))
  study.replay_not_input = true
end

local function load_replay(study)
  not_input(study)
  local path = M.replay_path(study)
  local f = io.open(path, "rb")
  if not f then return {} end
  local text = f:read("a")
  f:close()
  local ok, data = pcall(json.decode, text)
  if not ok or type(data) ~= "table" or type(data.steps) ~= "table" then return {} end
  return data.steps
end

-- The report's state a step leaves (what its later steps and the page depend on).
local function report_state(r)
  local ids = {}
  for id in pairs(r.ids) do ids[#ids + 1] = id end
  table.sort(ids)
  return { counts = r.counts, ids = ids, prov = r.prov, results = r.results }
end

-- JSON has one kind of number: 6.0 is written "6" and reads back as the integer 6, which a
-- report formats differently ("6" against "6.00"). A float with an integral value is saved as
-- {["smi.float"] = 6} and read back as 6.0.
local FLOAT = "smi.float"
local function pack(v)
  if math.type(v) == "float" and v == math.floor(v) and v - v == 0 then return { [FLOAT] = v } end
  if type(v) ~= "table" or getmetatable(v) ~= nil then return v end
  local c = {}
  for k, x in pairs(v) do c[k] = pack(x) end
  return c
end
local function unpack_floats(v)
  if type(v) ~= "table" then return v end
  local f = v[FLOAT]
  if f ~= nil and next(v, next(v)) == nil then return f + 0.0 end
  for k, x in pairs(v) do v[k] = unpack_floats(x) end
  return v
end

local function render(items)
  return require("smi.report.html").render{ title = "replay", items = items }
end

--- Before a step runs: where its report part starts.
function M.begin(study)
  return { items = study.report and #study.report.items or 0 }
end

--- After a step succeeded: the reuse keys into its saved record `entry`, and its report part into
-- the replay file (left out when JSON cannot hold it exactly: the step is then never reused).
function M.record(study, st, entry, mark)
  if not host then return end
  entry.inputs.code = M.code_files()
  entry.inputs.binary = M.binary(study)
  if not study.report then return end
  local r = study.report
  local items = {}
  for i = mark.items + 1, #r.items do items[#items + 1] = r.items[i] end
  local replay = study.replay or load_replay(study)
  study.replay = replay
  replay[st.name] = nil
  -- the part is kept only when it reads back exactly (rendering adds formatters to the tables it
  -- renders, so each side renders its own copy); anything else leaves the step not reusable
  local ok, why = pcall(function()
    local o = { skip = true, skipped = {} }
    local text = json.encode(pack({ result_hash = entry.result_hash, items = items, state = report_state(r) }), o)
    local back = function() return unpack_floats(json.decode(text)) end
    if #o.skipped == 0 and render(back().items) == render(items) then replay[st.name] = json.decode(text) end
    if type(smi) == "table" and smi.dry_run then return end
    not_input(study)
    require("smi.file").write(M.replay_path(study), json.encode({ steps = replay }, { root = "replay" }) .. "\n", ("study '%s'"):format(study.name))
  end)
  -- reuse saves time; it never costs a result: a part that cannot be saved means the step runs next time
  if not ok then study:_say("step %s will run again next time: its report part was not saved (%s)", st.name, tostring(why)) end
end

-- Why saved step st cannot be reused now (nil: it can). `kept` holds the steps reused before it.
local function why_not(study, st, saved, kept, cache)
  local s = saved.steps[st.name]
  if not s or s.status ~= "ok" then return "it has no successful saved result" end
  if s.stale then return "its saved result is stale" end
  local ins = s.inputs
  if not ins or not ins.code or not ins.binary then return "it was saved by an older smi-lua, without the inputs reuse compares" end
  if ins.binary ~= M.binary(study) then return "smi-lua changed (another build or version) since it ran" end
  local change = inputs.options_change(ins.options, study.options)
  if change ~= "" then return "the options changed: " .. change end
  for _, path in ipairs(inputs.sorted_keys(study.preamble_files)) do
    if not (ins.files or {})[path] then return ("the script now reads %s before the steps"):format(path) end
  end
  local f = inputs.files_change(ins.files, cache)
  if f then return "it read " .. f end
  f = inputs.files_change(ins.code, cache)
  if f then return "its code changed: " .. f end
  for _, dep in ipairs(inputs.sorted_keys(ins.results)) do
    if not kept[dep] then return ("it read step '%s', which runs again"):format(dep) end
    if saved.steps[dep].result_hash ~= ins.results[dep] then return ("the result of step '%s' it read has changed"):format(dep) end
  end
  if study.report then
    local part = study.replay[st.name]
    if not part or part.result_hash ~= s.result_hash then return "its part of the report was not saved" end
  end
  return nil
end

--- The steps a whole run reuses: {[name] = true} (a prefix of the steps), and why the first
-- other step runs (nil when all are reused). force: none.
function M.plan(study, saved, force)
  local kept = {}
  if force then return kept, "--force: every step runs" end
  if not host then return kept, nil end
  study.replay = load_replay(study)
  local cache, why, n = {}, nil, 0
  for _, st in ipairs(study.steps) do
    local w = why_not(study, st, saved, kept, cache)
    if w then why = ("step '%s' runs again: %s"):format(st.name, w) break end
    kept[st.name] = true
    n = n + 1
  end
  if n < #study.steps then
    for _, st in ipairs(study.steps) do
      if not kept[st.name] then break end
      if saved.steps[st.name].not_saved then -- a later step may need what results.json cannot hold
        local first
        for _, s2 in ipairs(study.steps) do
          if first or s2.name == st.name then first = true; kept[s2.name] = nil end
        end
        why = ("step '%s' runs again: it holds values results.json cannot (%s), which the steps that run may read; %s"):format(
          st.name, table.concat(saved.steps[st.name].not_saved, ", "), why)
        break
      end
    end
  end
  return kept, why
end

--- Reuses saved step st: its result for the later steps, its report part, its line in the timings.
function M.reuse(study, st, saved, live)
  local s = saved.steps[st.name]
  live[st.name] = s.result
  study.live_hash[st.name] = s.result_hash
  local part = study.report and study.replay[st.name]
  if part then
    part = unpack_floats(json.decode(json.encode(part))) -- later steps change the report's tables: not the saved part
    local r = study.report
    for _, it in ipairs(part.items) do r.items[#r.items + 1] = it end
    for k, v in pairs(part.state.counts) do r.counts[k] = v end
    for _, id in ipairs(part.state.ids) do r.ids[id] = true end
    r.prov, r.results = part.state.prov, part.state.results
  end
  study.timings[#study.timings + 1] = { st.name, s.not_run and "not run" or "reused", 0, s.not_run or "reused" }
end

return M
