-- SPDX-License-Identifier: MIT
--- The steering-column study's trial-2 PR calibration, timed (the target: "converges in at
-- most 10 s on 2 cores, with the same optimum from 4 starts"). From a study output folder (its
-- results.json and trial2_mode{1,4}.kriging) and the data file the study ran on, it rebuilds the
-- study's stage-2 call with the study's own code (calibration.lua: M.pr_stage, M.grids_of,
-- M.experimental_pdfs; the unknowns, specs, n and seed from results.json), first once as the study
-- ran it (one start) to check that it reproduces the recorded start, then with multistart = 4 and
-- threads = 2 (the starts side by side) from the stage-1 point and from the declared starts, each
-- repeated --repeats times; then the study's identifiability pass at the best point (its tolerance
-- and a short restart, as calibration.lua's optimum() does). Prints a summary, writes <label>.json
-- and <label>.md under --out (bench/run_calibrate_trial2.sh assembles the results file).
--   smi-lua --lib scripts --allow-read STUDY --allow-read DATA_DIR --allow-read /proc/loadavg --out OUT \
--     bench/calibrate_trial2.lua --study STUDY [--data FILE] [--results FILE] [--label NAME] [--repeats 3]
local calibration = require "smi.improve.calibration"
local ALL = { "mode1", "mode2", "mode4" } -- the study's responses in declared order
local options = require "smi.options"

local opt = options.parse(arg, {
  name = "calibrate_trial2",
  summary = "times the steering-column study's trial-2 PR calibration (4 starts, 2 threads)",
  usage = "smi-lua --lib scripts --allow-read STUDY --out OUT bench/calibrate_trial2.lua --study STUDY [options]",
  { name = "study", type = "path", meaning = "the study's output folder (results.json, trial2_mode1.kriging, trial2_mode4.kriging)" },
  { name = "results", type = "path", meaning = "the study's results.json (default: <study>/results.json)" },
  { name = "data", type = "path", default = (smi.script_dir or "bench") .. "/../scripts/steering_column/data/tests.csv",
    meaning = "the measurements the study ran on (mode1_hz, mode2_hz, mode4_hz)" },
  { name = "data-name", type = "string", meaning = "how the output names the data set (default: the --data path)" },
  { name = "label", type = "string", default = "committed",
    meaning = "the data set's name in the output (files <label>.json and <label>.md)" },
  { name = "repeats", type = "integer", default = 3, min = 1, meaning = "timed runs of each calibration (the median is reported)" },
  { name = "multistart", type = "integer", default = 4, min = 1, meaning = "starts per calibration" },
  { name = "threads", type = "integer", default = 2, min = 1, meaning = "smi.calibrate's threads (the starts side by side)" },
})
if not opt.study then error("calibrate_trial2: --study DIR is required (the output folder of scripts/steering_column.lua)", 0) end
local MODES = { "mode1", "mode4" } -- the calibrated ones
local results_file = opt.results or (opt.study .. "/results.json")

-- ---------------------------------------------------------------------------------------------
-- The study's trial 2, as results.json records it
-- ---------------------------------------------------------------------------------------------
local R = smi.json.read(results_file)
local function step(name)
  local s = R.steps and R.steps[name]
  if not (s and s.result) then error(("%s: no step '%s' (did the study run a trial 2?)"):format(results_file, name), 0) end
  if s.result.skipped then
    error(("%s: step '%s' did not run (%s): this data set has no trial 2"):format(results_file, name, tostring(s.result.reason)), 0)
  end
  return s.result
end
local sur, cal, recorded_data = step("trial2_surrogate"), step("trial2_calibration"), step("data")
local T = sur.model

-- The data, read as the study's data step reads it, and checked against the rows it recorded:
-- a data file that is not the study's would calibrate against other PDFs than the Krigings' study.
local cols = smi.csv.read(opt.data)
local data, data_tables = {}, {}
for _, m in ipairs(ALL) do
  local col = cols[m .. "_hz"]
  if type(col) ~= "userdata" then error(("%s: no numeric column '%s_hz'"):format(opt.data, m), 0) end
  local rec = recorded_data[m]
  if #col ~= #rec then
    error(("%s: %d rows, but the study in %s ran on %d (%s): give the study's --data file"):format(
      opt.data, #col, results_file, #rec, tostring(recorded_data.file)), 0)
  end
  for i = 1, #col do
    if col[i] ~= rec[i] then
      error(("%s: row %d, %s_hz = %.17g differs from the study's %.17g (%s): give the study's --data file"):format(
        opt.data, i, m, col[i], rec[i], tostring(recorded_data.file)), 0)
    end
  end
  data[m], data_tables[m] = col, col:totable()
end

local kriging = {}
for _, m in ipairs(MODES) do kriging[m] = smi.kriging.load(("%s/trial2_%s.kriging"):format(opt.study, m)) end

-- calibration.lua's t for pr_stage: everything the study's calibration_step passes that the PR
-- stage reads (no prior: the study's default)
local t = { unknowns = T.unknowns, specs = T.specs, kriging = kriging, metric = cal.metric, n = cal.n, seed = cal.seed,
            data = data, f_exp = calibration.experimental_pdfs(data_tables, R.seed, ALL), maxeval = cal.maxeval,
            calibrate = MODES }
if cal.metric ~= "pr" then error(("%s: trial 2 was calibrated with metric '%s'; this bench times the PR calibration"):format(
  results_file, tostring(cal.metric)), 0) end
if #(cal.priors or {}) > 0 then error(("%s: trial 2 was calibrated with a prior; this bench has none"):format(results_file), 0) end
local grids = calibration.grids_of(data, MODES, { mode1 = 25, mode4 = 25 })

-- parameter names, bounds and the declared starts (calibration.lua's declared_params order)
local names, bounds, declared = {}, {}, {}
for _, n in ipairs(T.unknowns) do
  local u = T.specs[n]
  for _, part in ipairs{ "mean", "std" } do
    local name = n .. "." .. part
    names[#names + 1] = name
    bounds[name] = { u[part][1], u[part][2] }
    declared[name] = u[part][3]
  end
end
local stage1 = cal.moments_stage.params

-- ---------------------------------------------------------------------------------------------
-- Runs
-- ---------------------------------------------------------------------------------------------
local function loadavg()
  local f = io.open("/proc/loadavg", "r")
  if not f then return "unknown (give --allow-read /proc/loadavg)" end
  local s = f:read("l")
  f:close()
  return s:match("^(%S+ %S+ %S+)") or s
end

local function timed(o)
  local w0, c0 = smi.now(), os.clock()
  local r = calibration.pr_stage(t, grids, o)
  return r, smi.now() - w0, os.clock() - c0
end

local function median(v)
  local s = {}
  for i, x in ipairs(v) do s[i] = x end
  table.sort(s)
  local n = #s
  return n % 2 == 1 and s[(n + 1) // 2] or 0.5 * (s[n // 2] + s[n // 2 + 1])
end

-- Each parameter's spread over the starts' optima in units of its range, largest first.
local function spreads(starts)
  local out = {}
  for _, name in ipairs(names) do
    local lo, hi = math.huge, -math.huge
    for _, s in ipairs(starts) do lo, hi = math.min(lo, s.params[name]), math.max(hi, s.params[name]) end
    out[#out + 1] = { name = name, spread = (hi - lo) / (bounds[name][2] - bounds[name][1]) }
  end
  table.sort(out, function(a, b) return a.spread > b.spread end)
  return out
end

-- Any table as one line of text (r.agreement's keys are not fixed yet: print what it has).
local function show(v)
  if type(v) ~= "table" then return tostring(v) end
  local ok, s = pcall(smi.json.encode, v)
  return ok and s or tostring(v)
end

local function summary(r, walls, cpus)
  local starts = {}
  for i, s in ipairs(r.starts) do
    starts[i] = { objective = s.objective, status = s.status, evaluations = s.evaluations, converged = s.converged,
                  params = s.params, start = s.start }
  end
  local optima = {}
  for i, o in ipairs(r.optima or {}) do optima[i] = { objective = o.objective, start = o.start, params = o.params } end
  local best_gap = 0
  for _, s in ipairs(r.starts) do best_gap = math.max(best_gap, s.objective - r.objective) end
  return { objective = r.objective, metrics = r.metrics, params = r.params, status = r.status, converged = r.converged,
           evaluations = r.evaluations, model_runs = r.model_runs, gradient = r.gradient, starts = starts,
           optima = optima, starts_agree = r.starts_agree, agreement = r.agreement, walls = walls, cpus = cpus,
           wall_median = median(walls), cpu_median = median(cpus), objective_gap = best_gap,
           spreads = spreads(r.starts), at_bounds = r.at_bounds }
end

-- One calibration, repeated: the summary of the first run and whether the repeats gave the same.
local function repeated(start, label)
  local walls, cpus, first, same = {}, {}, nil, true
  for k = 1, opt.repeats do
    local r, w, c = timed{ f_exp = t.f_exp, data = t.data, start = start, maxeval = t.maxeval, identifiability = false,
                           multistart = opt.multistart, threads = opt.threads }
    walls[k], cpus[k] = w, c
    if not first then first = r elseif r.objective ~= first.objective or r.evaluations ~= first.evaluations then same = false end
    if not smi.quiet then io.stderr:write(("  %s, run %d: %.2f s wall, %.2f s CPU, objective %.8f\n"):format(
      label, k, w, c, r.objective)) end
  end
  local s = summary(first, walls, cpus)
  s.repeats_identical = same
  return s, first
end

local out = { label = opt.label, study = opt.study, results = results_file, data = opt.data, n = t.n, seed = t.seed,
              maxeval = t.maxeval, multistart = opt.multistart, threads = opt.threads, repeats = opt.repeats,
              unknowns = T.unknowns, candidate = T.candidate, airbag = T.airbag, bounds = bounds,
              grids = grids, recorded = { objective = cal.objective, evaluations = cal.evaluations, status = cal.status,
                                          start_objective = cal.starts[1].objective,
                                          start_evaluations = cal.starts[1].evaluations } }

-- 1. The study's call as it ran (one start, default threads): must reproduce the recorded start.
do
  local r, w = timed{ f_exp = t.f_exp, data = t.data, start = stage1, maxeval = t.maxeval, identifiability = false,
                      multistart = 1 }
  local rec = cal.starts[1]
  local same = r.starts[1].objective == rec.objective and r.starts[1].evaluations == rec.evaluations
  for _, name in ipairs(names) do same = same and r.starts[1].params[name] == rec.params[name] end
  out.reproduction = { objective = r.starts[1].objective, evaluations = r.starts[1].evaluations,
                       status = r.starts[1].status, wall = w, identical = same }
end

-- 2. Four starts on two threads, timed: from the stage-1 point (the study's start) and from the
-- declared starts. The load average around the timed runs: the machine is shared.
out.load_before = loadavg()
out.stage1_start = repeated(stage1, "stage-1 start")
out.declared_start = repeated(declared, "declared start")
out.load_after = loadavg()

-- 3. The study's identifiability pass at the best of the four starts (optimum() in
-- calibration.lua: the tolerance from the data, a restart from the optimum with the directions).
do
  local best = out.stage1_start.objective <= out.declared_start.objective and out.stage1_start or out.declared_start
  local w0 = smi.now()
  -- smi.calibrate measures the tolerance at the point it ends on (from here: the best point)
  local r0 = calibration.pr_stage(t, grids, { f_exp = t.f_exp, data = t.data, start = best.params, maxeval = 1,
    identifiability = false, overlap_start = false, threads = opt.threads })
  local tol = { value = r0.tolerance, basis = r0.tolerance_basis }
  local r = calibration.pr_stage(t, grids, { f_exp = t.f_exp, data = t.data, start = best.params, maxeval = 40,
    identifiability = { rel_tol = 1e-9, abs_tol = tol.value, tolerance = tol.value }, threads = opt.threads })
  local dirs = {}
  for i, d in ipairs(r.identifiability and r.identifiability.directions or {}) do
    local l = {}
    for name, v in pairs(d.loadings) do l[#l + 1] = { name = name, loading = v } end
    table.sort(l, function(a, b) return math.abs(a.loading) > math.abs(b.loading) end)
    dirs[i] = { determined = d.determined, curvature = d.curvature, rise = d.rise, top = { l[1], l[2], l[3] } }
  end
  out.identifiability = { tolerance = tol.value, tolerance_basis = tol.basis, from = best == out.stage1_start
    and "stage-1 start" or "declared start", objective = r.objective, wall = smi.now() - w0, directions = dirs,
    weak = r.identifiability and r.identifiability.weak or {} }

  -- Where the starts' optima lie relative to the best: each one's offset from the best point in
  -- scaled units (each parameter over its range, the optimizer's units) and the share of that
  -- offset inside the span of the not-determined directions (1: the starts differ only where the
  -- data are silent; 0: they differ along what the data determine, i.e. distinct local optima).
  local basis = {}
  for _, d in ipairs(r.identifiability and r.identifiability.directions or {}) do
    if not d.determined then
      local v = {}
      for j, name in ipairs(names) do v[j] = d.loadings[name] or 0 end
      for _, b in ipairs(basis) do
        local c = 0
        for j = 1, #v do c = c + v[j] * b[j] end
        for j = 1, #v do v[j] = v[j] - c * b[j] end
      end
      local nv = 0
      for j = 1, #v do nv = nv + v[j] ^ 2 end
      nv = math.sqrt(nv)
      if nv > 1e-9 then for j = 1, #v do v[j] = v[j] / nv end basis[#basis + 1] = v end
    end
  end
  for _, s in ipairs{ out.stage1_start, out.declared_start } do
    for _, st in ipairs(s.starts) do
      local dv, n2 = {}, 0
      for j, name in ipairs(names) do
        dv[j] = (st.params[name] - r.params[name]) / (bounds[name][2] - bounds[name][1])
        n2 = n2 + dv[j] ^ 2
      end
      local p2 = 0
      for _, b in ipairs(basis) do
        local c = 0
        for j = 1, #dv do c = c + dv[j] * b[j] end
        p2 = p2 + c * c
      end
      st.offset = math.sqrt(n2)
      st.undetermined_share = n2 > 0 and math.sqrt(p2 / n2) or nil
    end
  end
end

smi.json.write(smi.out(opt.label .. ".json"), out, { nonfinite = "encode" })

-- ---------------------------------------------------------------------------------------------
-- Text: the terminal summary and the results file's section
-- ---------------------------------------------------------------------------------------------
local L = {}
local function w(fmt, ...) L[#L + 1] = select("#", ...) > 0 and fmt:format(...) or fmt end
local function short(name) return (name:gsub("wheel_cover_", "wc_"):gsub("ecu_bracket_", "ecu_"):gsub("column_frame_", "cf_")) end

local function moved(s)
  local parts = {}
  for _, p in ipairs(s.spreads) do
    if p.spread >= 0.01 then parts[#parts + 1] = ("%s %.2f"):format(p.name, p.spread) end
  end
  return #parts > 0 and table.concat(parts, ", ") or "none (every parameter within 1 % of its range)"
end

local function run_section(title, s)
  w("")
  w("**%s**: wall median **%.2f s** (runs: %s), CPU median %.2f s, %d objective evaluations over the %d starts (%s"
    .. " model runs), gradient %s; repeats identical: %s.", title, s.wall_median,
    table.concat((function() local v = {} for i, x in ipairs(s.walls) do v[i] = ("%.2f"):format(x) end return v end)(), ", "),
    s.cpu_median, s.evaluations, #s.starts, tostring(s.model_runs), tostring(s.gradient), s.repeats_identical and "yes" or "**no**")
  w("")
  local header = { "start", "objective", "status", "evaluations", "offset from the best", "share not determined" }
  for _, name in ipairs(names) do header[#header + 1] = short(name) end
  w("| " .. table.concat(header, " | ") .. " |")
  w("|" .. string.rep("---|", #header))
  for i, st in ipairs(s.starts) do
    local row = { tostring(i), ("%.8f"):format(st.objective), st.status, tostring(st.evaluations), ("%.3f"):format(st.offset),
                  (st.undetermined_share and st.offset >= 0.01) and ("%.2f"):format(st.undetermined_share) or "—" }
    for _, name in ipairs(names) do row[#row + 1] = ("%.5g"):format(st.params[name]) end
    w("| " .. table.concat(row, " | ") .. " |")
  end
  w("")
  local opts = {}
  for _, o in ipairs(s.optima) do opts[#opts + 1] = ("%.8f (start %d)"):format(o.objective, o.start) end
  w("- r.optima: %d distinct: %s; r.starts_agree = %s; largest objective gap to the best %.3g.", #s.optima,
    table.concat(opts, ", "), tostring(s.starts_agree), s.objective_gap)
  if s.agreement ~= nil then
    local keys = {}
    for k in pairs(s.agreement) do keys[#keys + 1] = k end
    table.sort(keys)
    local parts = {}
    for _, k in ipairs(keys) do parts[#parts + 1] = ("%s = %s"):format(k, show(s.agreement[k])) end
    w("- r.agreement: %s", table.concat(parts, "; "))
  else
    w("- r.agreement: not in this build's result")
  end
  w("- parameters that differ between the starts (spread over the 4 optima in units of the parameter's range, >= 0.01): %s.",
    moved(s))
end

w("## %s: %s", opt.label, opt.data_name or opt.data)
w("")
w("Trial 2 (%s, %s airbag), %d parameters, n = %d CRN samples, seed %d, PR grids of %d nodes, budget %d evaluations per"
  .. " start, multistart %d, threads %d; load average (1/5/15 min) %s before the timed runs, %s after.",
  tostring(T.candidate), tostring(T.airbag), #names, t.n, t.seed, grids[MODES[1]].nodes, t.maxeval, opt.multistart,
  opt.threads, out.load_before, out.load_after)
w("")
local function verdict(s)
  return ("%s (median %.2f s)"):format(s.wall_median <= 10 and "met" or "**not met**", s.wall_median)
end
-- "The same optimum" where the data can tell is smi.calibrate's r.agreement (start_agreement.hpp):
-- objectives within its tolerance and the same predictions (or no barrier between); the points
-- themselves differ along what the data do not determine (r.starts_agree, one point, stays false).
local function agree(s)
  local a = s.agreement
  local verdict = a and (a.agree and "yes" or "**no**") or "unknown (no r.agreement in this build)"
  return ("%s (r.agreement: %s of 4 starts at the best's optimum, objectives within %.3g against its tolerance %s,"
    .. " predictions within %s standard errors of the data's; as points, %d distinct optima, r.starts_agree = %s; the"
    .. " study's own tolerance for \"fits as well\" is %.3g)"):format(verdict, a and tostring(a.same) or "?",
    s.objective_gap, a and ("%.3g"):format(a.tolerance) or "?",
    a and a.largest_prediction_distance and ("%.2g"):format(a.largest_prediction_distance) or "?", #s.optima,
    tostring(s.starts_agree), out.identifiability.tolerance)
end
w("- the target, at most 10 s on 2 cores: from the stage-1 point %s, from the declared starts %s; the same"
  .. " optimum from 4 starts: from the stage-1 point %s, from the declared starts %s.", verdict(out.stage1_start),
  verdict(out.declared_start), agree(out.stage1_start), agree(out.declared_start))
w("- the study's own call (one start, from the stage-1 point) reproduced: objective %.12g in %d evaluations (%s, %.2f s)"
  .. " against the recorded %.12g in %d: %s.", out.reproduction.objective, out.reproduction.evaluations,
  out.reproduction.status, out.reproduction.wall, cal.starts[1].objective, cal.starts[1].evaluations,
  out.reproduction.identical and "identical" or "**different**")
run_section("From the stage-1 point (the study's start) + 3 seeded points", out.stage1_start)
run_section("From the declared starts + 3 seeded points", out.declared_start)
w("")
w("Offset from the best: the distance of the start's optimum from the best point found, each parameter in units of"
  .. " its range (the optimizer's scaled units); share not determined: the part of that offset inside the span of"
  .. " the not-determined directions below (1: the starts differ only where the data are silent; 0: along what the"
  .. " data determine, distinct local optima; — for an offset under 0.01, the best point itself).")
w("")
local id = out.identifiability
local dl, flags, ndet = {}, {}, 0
for i, d in ipairs(id.directions) do
  flags[i] = tostring(d.determined)
  if d.determined then ndet = ndet + 1 else
    local top = {}
    for _, l in ipairs(d.top) do top[#top + 1] = ("%s %+.2f"):format(l.name, l.loading) end
    dl[#dl + 1] = ("direction %d (%s)"):format(i, table.concat(top, ", "))
  end
end
w("Identifiability at the best optimum (the study's pass: from the %s, tolerance %.4g from the data, %.1f s):"
  .. " r.identifiability.directions' determined flags %s: %d of %d determined; not determined: %s.", id.from,
  id.tolerance, id.wall, table.concat(flags, ", "), ndet, #id.directions, #dl > 0 and table.concat(dl, "; ") or "none")
local text = table.concat(L, "\n") .. "\n"
smi.write_file(smi.out(opt.label .. ".md"), text)
print(text)
