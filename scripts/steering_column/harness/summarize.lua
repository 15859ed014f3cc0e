-- SPDX-License-Identifier: MIT
--- Summary of a robustness-harness run (run.sh): the study's conclusion against the truth of
-- each generated experiment, the calibrated means of the last trial against the true means, the
-- solver runs. arg: experiments.csv, the harness output folder, the ids run ("1,2,..."), and
-- --check to exit 1 unless every experiment meets the issue's criteria:
--   rigid truth:  trial 1 (the initial model, the true form) valid on modes 1 and 4 and not
--                 invalid on mode 2, its calibration converged; the verdict never "invalid", and
--                 never "valid" in a form the truth lacks: "valid" in the initial form, or
--                 "undetermined" with the initial form among the supported forms (mode 2 left
--                 undetermined by nine specimens triggers refinement, as an invalid one does, and
--                 the forms tried then fit equally well);
--   spring truth: trial 1 invalid, the first refinement "airbag modelling type", the last trial
--                 spring airbag, valid on modes 1 and 4, mode 2 valid or inconclusive, its
--                 calibration converged, airbag stiffness mean within 15 % of the truth, and
--                 "valid" only in a form with the spring airbag.
local json = require "smi.report.json"

local csv_path, out, ids, check = arg[1], arg[2], arg[3] or "", arg[4] == "--check"
local wanted = {}
for id in ids:gmatch("[^,]+") do wanted[id] = true end

local function read(path)
  local f = io.open(path, "rb")
  if not f then return nil end
  local s = f:read("a")
  f:close()
  return s
end

local header, rows = nil, {}
for line in io.lines(csv_path) do
  local cells = {}
  for c in (line .. ","):gmatch("([^,]*),") do cells[#cells + 1] = c end
  if not header then header = cells else
    local r = {}
    for i, h in ipairs(header) do r[h] = cells[i] end
    if wanted[r.id] then rows[#rows + 1] = r end
  end
end

local UNKNOWNS = { "column_frame_E", "ecu_bracket_thickness", "wheel_cover_rho", "wheel_cover_thickness",
                   "airbag_stiffness" }

-- The conclusion's path in words (a column of the confusion table).
local function outcome(c)
  if not c then return "study failed" end
  local last = c.trials[#c.trials]
  local path = #c.refinements == 0 and "no refinement" or ("refined: " .. table.concat(c.refinements, " > "))
  local und = c.undetermined and #c.undetermined > 0
    and (" (" .. table.concat(c.undetermined, ", ") .. " undetermined)")
  return ("%s, %s airbag, %s%s"):format(path, last.airbag, c.verdict, und or "")
end

-- The criteria for a rigid truth (see the header): the initial form is the truth, so it must
-- fit, and no other form may be called valid.
local function judge_rigid(c)
  local first, why = c.trials[1], {}
  local function need(ok, what) if not ok then why[#why + 1] = what end end
  need(first.modes.mode1 == "valid" and first.modes.mode4 == "valid", "trial 1 invalid on a calibrated mode")
  need(first.modes.mode2 ~= "invalid", "trial 1 invalid on mode 2")
  need(first.calibration.converged, "trial 1's calibration not converged")
  local initial
  for _, f in ipairs(c.forms or {}) do
    if #f.applied == 0 then initial = f end
    if f.chosen and c.verdict == "valid" and #f.applied > 0 then
      why[#why + 1] = "called a form the truth lacks valid: " .. table.concat(f.applied, " + ")
    end
  end
  need(c.verdict ~= "invalid", "verdict invalid")
  need(c.verdict ~= "undetermined" or (initial and initial.supported),
       "undetermined without the initial (true) form among the supported forms")
  if #why > 0 then return false, table.concat(why, "; ") end
  return true, c.verdict
end

-- ... and for a spring truth: see the header.
local function judge_spring(r, c)
  local first, last, why = c.trials[1], c.trials[#c.trials], {}
  local function need(ok, what) if not ok then why[#why + 1] = what end end
  need(first.modes.mode1 == "invalid" or first.modes.mode4 == "invalid" or first.modes.mode2 == "invalid",
       "trial 1 not invalid")
  need(c.refinements[1] == "airbag modelling type", "first refinement " .. tostring(c.refinements[1]))
  need(last.airbag == "spring", "last trial " .. last.airbag)
  need(last.modes.mode1 == "valid" and last.modes.mode4 == "valid", "last trial invalid on a calibrated mode")
  need(last.modes.mode2 ~= "invalid", "mode 2 invalid")
  need(last.calibration.converged, "last calibration not converged")
  for _, f in ipairs(c.forms or {}) do
    local spring = false
    for _, a in ipairs(f.applied) do spring = spring or a == "airbag modelling type" end
    need(not (f.chosen and c.verdict == "valid" and not spring),
         "called a form the truth lacks valid: " .. (#f.applied > 0 and table.concat(f.applied, " + ") or "the initial model"))
  end
  local k = last.calibration.means.airbag_stiffness
  need(k and math.abs(k / tonumber(r.airbag_stiffness) - 1) <= 0.15,
       ("airbag stiffness %s vs %s"):format(tostring(k), r.airbag_stiffness))
  if #why > 0 then return false, table.concat(why, "; ") end
  return true, "valid"
end

local function judge(r, c)
  if not c then return false, "no conclusion" end
  if r.truth == "rigid" then return judge_rigid(c) end
  return judge_spring(r, c)
end

-- The last trial's calibrated means against the truth (and the airbag stiffness's range over the
-- near-optimal set: how well the data fix it), and the convergence of each trial.
local function errors(r, R, c)
  local last = c.trials[#c.trials]
  local cv = {}
  for i, t in ipairs(c.trials) do cv[i] = t.calibration.converged and "yes" or "no" end
  local cal = R.steps["trial" .. #c.trials .. "_calibration"].result
  local ranges = cal.near_optimal and cal.near_optimal.mean_ranges or {}
  local errs = {}
  for _, n in ipairs(UNKNOWNS) do
    local m, t = last.calibration.means[n], tonumber(r[n])
    if m and t then
      local e = ("%s %+.0f%%"):format(n:gsub("wheel_cover_", "cover_"):gsub("_thickness", "_t"), 100 * (m / t - 1))
      local rg = n == "airbag_stiffness" and ranges[n]
      if rg then e = e .. (" [%+.0f, %+.0f]"):format(100 * (rg[1] / t - 1), 100 * (rg[2] / t - 1)) end
      errs[#errs + 1] = e
    end
  end
  return table.concat(errs, ", "), table.concat(cv, "/")
end

local LINE = "%-4s %-6s %-6s %-74s %-5s %-9s %s"
local confusion, order, lines, all_ok = {}, {}, {}, true
local totals = { launched = 0, points = 0, reused = 0 }
local per_study = {} -- each study's solver runs as if it ran alone (results.json `cost`)
print(LINE:format("exp", "truth", "noise", "conclusion", "right", "converged",
  "calibrated mean / true mean - 1 (last trial)"))
for _, r in ipairs(rows) do
  local text = read(("%s/exp%s/study/results.json"):format(out, r.id))
  local R = text and json.decode(text)
  local c = R and R.conclusion
  local ok, why = judge(r, c)
  all_ok = all_ok and ok
  local key = r.truth .. " truth"
  local o = outcome(c)
  confusion[key] = confusion[key] or {}
  confusion[key][o] = (confusion[key][o] or 0) + 1
  if not order[o] then order[o] = true; order[#order + 1] = o end
  local errs, conv = "", "-"
  if c then
    errs, conv = errors(r, R, c)
    local s = R.steps.summary and R.steps.summary.result.solver_totals
    if s then for k in pairs(totals) do totals[k] = totals[k] + (s[k] or 0) end end
    if R.cost then per_study[#per_study + 1] = R.cost.solver_runs end
  end
  print(LINE:format(r.id, r.truth, r.noise, o, ok and "yes" or "NO", conv, errs))
  if not ok then lines[#lines + 1] = ("experiment %s: %s"):format(r.id, why) end
end
print("")
print("Confusion table (rows: truth; columns: the study's conclusion; counts):")
for _, o in ipairs(order) do
  print(("  %-74s rigid truth %d, spring truth %d"):format(o, (confusion["rigid truth"] or {})[o] or 0,
    (confusion["spring truth"] or {})[o] or 0))
end
print(("Solver runs over these experiments (one shared store): %d points, %d processes launched, %d points"
  .. " reused."):format(totals.points, totals.launched, totals.reused))
if #per_study > 0 then
  table.sort(per_study)
  print(("Solver runs per study as if run alone (the budget: 1,000): %d to %d."):format(per_study[1],
    per_study[#per_study]))
end
for _, l in ipairs(lines) do print("WRONG " .. l) end
print(("%d experiment(s), %d right"):format(#rows, #rows - #lines))
if check and not all_ok then os.exit(1) end
